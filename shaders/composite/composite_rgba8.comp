#version 460
#extension GL_GOOGLE_include_directive : require
// The compute composite for back buffers stored as rgba8 (composite_compute.glsl).
#define TYN_COMPOSITE_FORMAT rgba8
#include "composite/composite_compute.glsl"
