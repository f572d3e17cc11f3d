#version 460
// Coordinate texture (yusov2013): the screen position of every epipolar sample and the length
// of its view ray, to the surface of the pixel the sample falls in at the sample's own position.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;  // x: sample, y: slice
  if (id.x >= epipolar.samples_per_slice || id.y >= epipolar.slice_count) return;
  vec2 extent = tyn_output_extent();
  vec4 end_points = imageLoad(slice_end_points, ivec2(id.y, 0));
  uint count = tyn_slice_sample_count(end_points, extent, epipolar.samples_per_slice, epipolar.epipole_density,
                                      epipolar.improved_placement != 0u);
  if (id.x >= count) {
    imageStore(epipolar_coordinates, ivec2(id), vec4(0.0));
    return;
  }
  vec2 ndc = tyn_sample_position(end_points, float(id.x), count, epipolar.epipole_density);
  // Samples lie on the hull of the pixel centres: the pixel containing one is always on screen.
  uvec2 pixel = uvec2(clamp(floor(tyn_pixel_from_ndc(ndc, extent)), vec2(0.0), extent - 1.0));
  float pixel_depth = texelFetch(depth_buffer, ivec2(pixel), 0).r;
  // The pixel's depth is that of its centre, up to half a pixel away. On ground seen at a grazing
  // angle the ray length changes by several percent per pixel there, and improved placement's
  // one-pixel spacing keeps the samples at nearly the same offset from their pixels' centres over
  // many pixels, so a point-sampled depth biases every sample alike wherever L_in depends on the
  // ray's length (a ray ending inside a spot light's beam), which interpolation cannot average
  // out. The ray ends on the pixel's plane instead (epipolar_geometry.h), or at its depth where
  // it has none (a sliver one pixel wide, a crease).
  vec2 offset = tyn_pixel_from_ndc(ndc, extent) - (vec2(pixel) + 0.5);
  float depth = tyn_epipolar_depth_at(pixel_depth, tyn_epipolar_depth_slopes(ivec2(pixel), pixel_depth), offset);
  TynViewRay ray = tyn_view_ray_ndc(ndc, depth);
  imageStore(epipolar_coordinates, ivec2(id), vec4(ndc, ray.surface_distance, 1.0));
}
