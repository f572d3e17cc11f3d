#version 460
#extension GL_GOOGLE_include_directive : require
// Prefix sums of the fourier32 storage variant (prefix_sums.glsl).
#define TYN_PF_BASIS 5
#include "prefiltered/prefix_sums.glsl"
