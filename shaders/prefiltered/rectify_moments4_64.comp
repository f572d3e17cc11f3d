#version 460
#extension GL_GOOGLE_include_directive : require
// Rectification into the moments4_64 storage variant (rectify.glsl).
#define TYN_PF_BASIS 0
#include "prefiltered/rectify.glsl"
