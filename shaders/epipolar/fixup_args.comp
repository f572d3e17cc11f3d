#version 460
// Sizes the indirect fix-up dispatch by the number of flagged pixels: zero groups, and so no
// work, when the unwarp flagged none.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = 1) in;

void main() {
  fixup_groups[0] = (fixup_count + TYN_EPIPOLAR_FIXUP_GROUP - 1u) / TYN_EPIPOLAR_FIXUP_GROUP;
  fixup_groups[1] = 1u;
  fixup_groups[2] = 1u;
}
