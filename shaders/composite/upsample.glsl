// L_in at an output pixel from the L_in target: read directly at full resolution, upsampled with
// common/upsample.h's joint bilateral weights otherwise; unscaled (FrameConstants::target_scale). Needs `frame`, `depth_buffer` and
// `in_scattering` (the target, sampled) in scope, and common/view_ray.glsl.
#ifndef TYNDALL_UPSAMPLE_GLSL
#define TYNDALL_UPSAMPLE_GLSL

#include "common/upsample.h"

vec3 tyn_upsampled_in_scattering(uvec2 pixel, float depth) {
  if (frame.target_stride == 1u) return texelFetch(in_scattering, ivec2(pixel), 0).rgb * frame.target_unscale;
  vec2 position = tyn_upsample_position(pixel, frame.target_stride, frame.target_offset);
  ivec2 base = ivec2(floor(position));
  vec2 f = position - vec2(base);
  ivec2 last = ivec2(frame.target_extent) - 1;
  ivec2 taps[4] = ivec2[4](clamp(base, ivec2(0), last), clamp(base + ivec2(1, 0), ivec2(0), last),
                           clamp(base + ivec2(0, 1), ivec2(0), last), clamp(base + ivec2(1, 1), ivec2(0), last));
  vec4 tap_distance;
  for (int i = 0; i < 4; ++i) {
    uvec2 at = tyn_output_pixel(uvec2(taps[i]));
    tap_distance[i] = tyn_view_distance(tyn_pixel_ndc(at), texelFetch(depth_buffer, ivec2(at), 0).r);
  }
  vec4 w = tyn_upsample_weights(f, tap_distance, tyn_view_distance(tyn_pixel_ndc(pixel), depth));
  vec3 sum = vec3(0.0);
  for (int i = 0; i < 4; ++i) {
    if (w[i] > 0.0) sum += w[i] * texelFetch(in_scattering, taps[i], 0).rgb;
  }
  return sum * frame.target_unscale;
}

#endif
