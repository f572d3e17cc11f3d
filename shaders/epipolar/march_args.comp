#version 460
// Starts a round of ray marching: its entries are those listed since the previous round started,
// and the indirect dispatch runs TYN_EPIPOLAR_MARCH_GROUP / parts entries per workgroup (parts:
// march.comp's threads per entry, specialised like the march), at most
// TYN_EPIPOLAR_MAX_GROUPS groups (march.comp's groups stride over the rest).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(constant_id = 2) const uint TYN_MARCH_PARTS = 1u;

layout(local_size_x = 1) in;

void main() {
  march_first = march_round_end;
  march_round_end = march_count;
  uint per_group = TYN_EPIPOLAR_MARCH_GROUP / TYN_MARCH_PARTS;
  march_groups[0] = min((march_count - march_first + per_group - 1u) / per_group, TYN_EPIPOLAR_MAX_GROUPS);
  march_groups[1] = 1u;
  march_groups[2] = 1u;
}
