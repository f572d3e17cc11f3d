#version 460
#extension GL_GOOGLE_include_directive : require
// Prefix sums of the moments6_96 storage variant (prefix_sums.glsl).
#define TYN_PF_BASIS 3
#include "prefiltered/prefix_sums.glsl"
