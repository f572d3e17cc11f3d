#version 460
#extension GL_GOOGLE_include_directive : require
// An rgba16f light's L_in added to an rgba32f frame target (light_sum.glsl).
#define TYN_LIGHT_SUM_FORMAT rgba32f
#define TYN_LIGHT_FORMAT rgba16f
#include "composite/light_sum.glsl"
