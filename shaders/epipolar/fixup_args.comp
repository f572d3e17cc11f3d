#version 460
// Sizes the indirect fix-up dispatch by the number of flagged pixels, one workgroup per pixel up to
// the smallest maxComputeWorkGroupCount[0] Vulkan guarantees (the fix-up and its debug view loop
// over the rest): zero groups, and so no work, when the unwarp flagged none.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = 1) in;

void main() {
  fixup_groups[0] = min(fixup_count, TYN_EPIPOLAR_MAX_GROUPS);
  fixup_groups[1] = 1u;
  fixup_groups[2] = 1u;
}
