#version 460
#extension GL_GOOGLE_include_directive : require
// Rectification into the moments6_192 storage variant (rectify.glsl).
#define TYN_PF_BASIS 4
#include "prefiltered/rectify.glsl"
