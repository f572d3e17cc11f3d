#version 460
#extension GL_GOOGLE_include_directive : require
// The compute composite for back buffers stored as rgba32f (composite_compute.glsl).
#define TYN_COMPOSITE_FORMAT rgba32f
#include "composite/composite_compute.glsl"
