#version 460
// The floor a post-process cannot beat when it composites with a compute pass: one invocation per
// pixel reads the depth buffer and the back buffer and writes the back buffer in place as a storage
// image (GENERAL layout; each invocation reads and writes only its own texel). The back buffer is
// read through a sampler and written without a format qualifier, so one pipeline serves every
// storage-capable back-buffer format (shaderStorageImageWriteWithoutFormat).
#extension GL_GOOGLE_include_directive : require
#include "floor_fog.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D in_depth;
layout(set = 0, binding = 1) uniform sampler2D in_color;
layout(set = 0, binding = 2) writeonly uniform image2D out_color;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(out_color)))) return;
  float f = floor_fog_transmittance(texelFetch(in_depth, pixel, 0).r);
  vec4 color = texelFetch(in_color, pixel, 0);
  imageStore(out_color, pixel, vec4(color.rgb * f + floor_constants.fog.rgb * (1.0 - f), color.a));
}
