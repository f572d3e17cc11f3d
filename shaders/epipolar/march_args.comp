#version 460
// Starts a round of ray marching: its entries are those listed since the previous round started,
// and the indirect dispatch runs one thread per entry.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = 1) in;

void main() {
  march_first = march_round_end;
  march_round_end = march_count;
  march_groups[0] = (march_count - march_first + TYN_EPIPOLAR_MARCH_GROUP - 1u) / TYN_EPIPOLAR_MARCH_GROUP;
  march_groups[1] = 1u;
  march_groups[2] = 1u;
}
