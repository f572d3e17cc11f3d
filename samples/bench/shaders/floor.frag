#version 460
// The floor a post-process cannot beat when it composites with a fragment pass: one full-screen
// pass that reads the depth buffer and the back buffer and writes the back buffer, blended like
// Tyndall's fragment composite (dual source: the back buffer is read by the blender, not sampled).
#extension GL_GOOGLE_include_directive : require
#include "floor_fog.glsl"

layout(set = 0, binding = 0) uniform sampler2D in_depth;

layout(location = 0, index = 0) out vec4 out_add;
layout(location = 0, index = 1) out vec4 out_multiply;

void main() {
  float f = floor_fog_transmittance(texelFetch(in_depth, ivec2(gl_FragCoord.xy), 0).r);
  out_add = vec4(floor_constants.fog.rgb * (1.0 - f), 0.0);
  out_multiply = vec4(vec3(f), 1.0);
}
