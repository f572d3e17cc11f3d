#version 460
// Epipolar slices (engelhardt2010 §4.1, yusov2013 "Sample generation"): one thread per slice
// writes its entry and exit points, or the culled sentinel. The slices are spread over the
// frame's border arc (epipolar_geometry.h "Slice arc").
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_SLICE_GROUP) in;

void main() {
  uint slice = gl_GlobalInvocationID.x;
  if (slice >= epipolar.slice_count) return;
  vec2 extent = tyn_output_extent();
  vec2 exit_point = tyn_arc_exit_point(float(slice), epipolar.slice_count, vec2(epipolar.arc_start, epipolar.arc_length), extent);
  vec4 end_points;
  tyn_slice_end_points(epipolar.epipole, exit_point, extent, end_points);
  imageStore(slice_end_points, ivec2(slice, 0), end_points);
}
