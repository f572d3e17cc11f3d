#version 460
#extension GL_GOOGLE_include_directive : require
// Rectification into the fourier32 storage variant (rectify.glsl).
#define TYN_PF_BASIS 5
#include "prefiltered/rectify.glsl"
