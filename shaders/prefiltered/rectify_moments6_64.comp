#version 460
#extension GL_GOOGLE_include_directive : require
// Rectification into the moments6_64 storage variant (rectify.glsl).
#define TYN_PF_BASIS 2
#include "prefiltered/rectify.glsl"
