#version 460
// Debug views, first pass: a dimmed grey L_in (luminance / (1 + luminance), times 0.4) under the
// marks the next pass draws, so that they show where they fall in the picture.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_PIXEL_GROUP_SIZE, local_size_y = TYN_PIXEL_GROUP_SIZE) in;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, frame.target_extent))) return;  // drawn at L_in's resolution
  vec3 in_scattering = imageLoad(out_scattering, ivec2(pixel)).rgb * frame.target_unscale;
  float luminance = dot(in_scattering, vec3(0.2126, 0.7152, 0.0722));
  float grey = 0.4 * max(luminance, 0.0) / (1.0 + max(luminance, 0.0));
  imageStore(debug_image, ivec2(pixel), vec4(vec3(grey), 1.0));
}
