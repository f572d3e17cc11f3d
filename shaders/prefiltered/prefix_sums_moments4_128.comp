#version 460
#extension GL_GOOGLE_include_directive : require
// Prefix sums of the moments4_128 storage variant (prefix_sums.glsl).
#define TYN_PF_BASIS 1
#include "prefiltered/prefix_sums.glsl"
