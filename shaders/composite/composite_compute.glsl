// out = in · T + L_in written in place by a compute pass, for back buffers the host created with
// STORAGE usage: no rasterisation, no render pass, and a dispatch fused into a compute chain.
// The back buffer is read and written, so its format qualifier must be declared (one SPIR-V per
// format, TYN_COMPOSITE_FORMAT: reading storage images without one is an optional feature). Alpha
// is kept, as by the fragment composite's blend.
#include "common/shared_constants.h"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

layout(set = 0, binding = TYN_BINDING_FRAME, std140) uniform FrameBlock { FrameConstants frame; };
layout(set = 0, binding = TYN_BINDING_DEPTH) uniform sampler2D depth_buffer;
layout(set = 0, binding = TYN_COMPOSITE_BINDING_TARGET) uniform sampler2D in_scattering;
layout(set = 0, binding = TYN_COMPOSITE_BINDING_COLOR, TYN_COMPOSITE_FORMAT) uniform image2D back_buffer;

#include "common/view_ray.glsl"
#include "composite/upsample.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, frame.output_extent))) return;
  float depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  vec4 color = imageLoad(back_buffer, ivec2(pixel));
  color.rgb = color.rgb * tyn_view_transmittance(pixel, depth) + tyn_upsampled_in_scattering(pixel, depth);
  imageStore(back_buffer, ivec2(pixel), color);
}
