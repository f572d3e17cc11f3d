#version 460
// The floor a post-process cannot beat: one full-screen pass that reads the depth buffer and the
// back buffer and writes the back buffer — here a depth fog, out = in · f + fog · (1 − f) with
// f = exp(−density · view distance), blended like Tyndall's composite (dual source: the back
// buffer is read by the blender, not sampled). What it computes does not matter; its memory
// traffic and its one fragment per pixel do.
layout(set = 0, binding = 0) uniform sampler2D in_depth;

layout(push_constant) uniform Constants {
  vec4 fog;         // rgb: fog radiance, a: density per scene unit
  vec4 projection;  // P[2][2], P[3][2] of the host's projection: view z from clip depth
} constants;

layout(location = 0, index = 0) out vec4 out_add;
layout(location = 0, index = 1) out vec4 out_multiply;

void main() {
  float depth = texelFetch(in_depth, ivec2(gl_FragCoord.xy), 0).r;
  // Perspective clip depth d = −P22 − P32 / z_view (w = −z_view): |z_view| = |P32 / (d + P22)|.
  float viewDistance = abs(constants.projection.y) / max(abs(depth + constants.projection.x), 1e-7);
  float f = exp(-constants.fog.a * viewDistance);
  out_add = vec4(constants.fog.rgb * (1.0 - f), 0.0);
  out_multiply = vec4(vec3(f), 1.0);
}
