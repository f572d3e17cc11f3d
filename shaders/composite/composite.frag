#version 460
// out = in · T + L_in in one pass with dual-source blending: source 0 carries L_in (added with
// factor ONE), source 1 carries T (the destination factor SRC1_COLOR). The back buffer's alpha
// is kept. Works for any blendable format, sRGB ones included (blending happens in linear).
layout(set = 0, binding = 0) uniform sampler2D in_scattering;
layout(set = 0, binding = 1) uniform sampler2D in_transmittance;

layout(location = 0, index = 0) out vec4 out_add;
layout(location = 0, index = 1) out vec4 out_multiply;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  out_add = vec4(texelFetch(in_scattering, pixel, 0).rgb, 0.0);
  out_multiply = vec4(texelFetch(in_transmittance, pixel, 0).rgb, 1.0);
}
