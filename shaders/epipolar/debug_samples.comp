#version 460
// Debug view DebugView::EpipolarSamples: every ray-marched epipolar sample (an interpolation
// source of itself), yellow, at the pixel it lies in; blue where the shadow test found its whole
// ray in shadow and set it to zero without marching (shadow_test.comp marks those with alpha 1).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;  // x: sample, y: slice
  if (id.x >= epipolar.samples_per_slice || id.y >= epipolar.slice_count) return;
  uint source = imageLoad(interpolation_source, ivec2(id)).x;
  if (source == TYN_EPIPOLAR_NO_SOURCE || (source & 0xffffu) != id.x) return;
  // Drawn at L_in's resolution: the target pixel whose block the sample lies in.
  vec2 extent = vec2(frame.target_extent);
  vec2 ndc = imageLoad(epipolar_coordinates, ivec2(id)).xy;
  vec2 output_pixel = tyn_pixel_from_ndc(ndc, tyn_output_extent());
  ivec2 pixel = ivec2(clamp(floor(output_pixel / float(frame.target_stride)), vec2(0.0), extent - 1.0));
  bool in_shadow = imageLoad(epipolar_scattering, ivec2(id)).a > 0.5;
  imageStore(debug_image, pixel, in_shadow ? vec4(0.1, 0.45, 1.0, 1.0) : vec4(1.0, 0.85, 0.0, 1.0));
}
