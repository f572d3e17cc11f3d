#version 460
// Ray marching of the epipolar samples the refinement chose: the Reference's exact texel walk,
// run for those samples instead of every pixel.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#include "reference/reference_march.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;  // x: sample, y: slice
  if (id.x >= epipolar.counts.y || id.y >= epipolar.counts.x) return;
  // Only the samples the refinement chose are ray-marched; the others are interpolated next.
  uint source = imageLoad(interpolation_source, ivec2(id)).x;
  if (source != TYN_EPIPOLAR_NO_SOURCE && (source & 0xffffu) != id.x) return;
  vec4 coordinates = imageLoad(epipolar_coordinates, ivec2(id));
  vec3 in_scattering = vec3(0.0);
  if (coordinates.w > 0.5 && frame.extent.z != 0u) {
    in_scattering = tyn_reference_in_scattering(frame.view_to_world[3].xyz,
                                                tyn_view_direction(coordinates.xy), coordinates.z);
  }
  imageStore(epipolar_scattering, ivec2(id), vec4(in_scattering, 0.0));
}
