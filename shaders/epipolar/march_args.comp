#version 460
// Sizes the indirect march dispatch by the number of ray-marching samples the refinement listed.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = 1) in;

void main() {
  march_groups[0] = (march_count + TYN_EPIPOLAR_MARCH_GROUP - 1u) / TYN_EPIPOLAR_MARCH_GROUP;
  march_groups[1] = 1u;
  march_groups[2] = 1u;
}
