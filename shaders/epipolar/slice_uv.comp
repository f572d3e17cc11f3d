#version 460
// Slice origin and direction in shadow-map UV (yusov2013 "Slice Origin and Direction"): every
// view ray of a slice lies in one epipolar plane, whose image in the shadow map is one line; the
// slice's 1D min/max tree is built along it and its samples are marched along it.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_SLICE_GROUP) in;

void main() {
  uint slice = gl_GlobalInvocationID.x;
  if (slice >= epipolar.slice_count) return;
  vec4 end_points = imageLoad(slice_end_points, ivec2(slice, 0));
  vec4 origin_direction = vec4(TYN_EPIPOLAR_INVALID_COORD);
  if (tyn_slice_valid(end_points)) {
    // A spot light's rays are bounded by its cone; a directional map is bounded by its square.
    vec3 cone = frame.light_type == TYN_LIGHT_SPOT
                    ? tyn_spot_cone_uv(frame.world_to_shadow[0], frame.light_position,
                                       frame.light_direction, frame.cos_outer_cone)
                    : vec3(0.0);
    float uv_length;
    tyn_slice_shadow_uv(frame.world_to_shadow[0], frame.view_to_world[3].xyz,
                        tyn_view_direction(vec2(end_points.z, end_points.w)), cone, origin_direction,
                        uv_length);
  }
  imageStore(slice_uv, ivec2(slice, 0), origin_direction);
}
