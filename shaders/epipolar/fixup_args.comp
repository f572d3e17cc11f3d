#version 460
// Sizes the indirect fix-up dispatch by the number of flagged pixels: one workgroup per pixel when
// the fix-up splits each walk over its workgroup, one thread per pixel when it does not
// (fixup.comp), up to the smallest maxComputeWorkGroupCount[0] Vulkan guarantees (the fix-up and
// its debug view loop over the rest): zero groups, and so no work, when the unwarp flagged none.
// Where a directional light's frame has a block image (EpipolarConstants::shadow_block_side, set by the context
// when its fix-up walks texel by texel) it also sizes the shadow-map blocks pass
// (shadow_blocks.comp): the blocks read the whole map, a cost the fix-up's block steps repay only
// when it walks enough rays (TYN_EPIPOLAR_SHADOW_BLOCK_PIXELS); otherwise zero groups, and the
// fix-up walks texel by texel or in steps. A point light's blocks are built before the march,
// which walks every sample: the groups written here for one are not read.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(constant_id = 3) const bool TYN_FIXUP_SERIAL = false;

layout(local_size_x = 1) in;

void main() {
  uint groups = TYN_FIXUP_SERIAL ? (fixup_count + TYN_EPIPOLAR_FIXUP_GROUP - 1u) / TYN_EPIPOLAR_FIXUP_GROUP
                                 : fixup_count;
  fixup_groups[0] = min(groups, TYN_EPIPOLAR_MAX_GROUPS);
  fixup_groups[1] = 1u;
  fixup_groups[2] = 1u;
  uint side = epipolar.shadow_block_side;
  bool blocks = side != 0u && fixup_count * TYN_EPIPOLAR_SHADOW_BLOCK_PIXELS >= frame.shadow_map_size;
  uint block_groups = (side + TYN_EPIPOLAR_SHADOW_BLOCK_GROUP - 1u) / TYN_EPIPOLAR_SHADOW_BLOCK_GROUP;
  shadow_block_groups[0] = blocks ? block_groups : 0u;
  shadow_block_groups[1] = blocks ? block_groups : 0u;
  shadow_block_groups[2] = 1u;
}
