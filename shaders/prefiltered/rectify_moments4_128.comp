#version 460
#extension GL_GOOGLE_include_directive : require
// Rectification into the moments4_128 storage variant (rectify.glsl).
#define TYN_PF_BASIS 1
#include "prefiltered/rectify.glsl"
