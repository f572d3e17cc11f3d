#version 460
#extension GL_GOOGLE_include_directive : require
// The compute composite for back buffers stored as rgb10_a2 (composite_compute.glsl).
#define TYN_COMPOSITE_FORMAT rgb10_a2
#include "composite/composite_compute.glsl"
