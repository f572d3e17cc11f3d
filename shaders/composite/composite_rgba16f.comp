#version 460
#extension GL_GOOGLE_include_directive : require
// The compute composite for back buffers stored as rgba16f (composite_compute.glsl).
#define TYN_COMPOSITE_FORMAT rgba16f
#include "composite/composite_compute.glsl"
