#version 460
// The nearest and farthest occluder depth of shadow map 0 over each block of
// TYN_EPIPOLAR_SHADOW_BLOCK² texels (the last row and column of blocks clipped to the map): the
// fix-up's block steps (block_walk.glsl). One thread per block.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_SHADOW_BLOCK_GROUP, local_size_y = TYN_EPIPOLAR_SHADOW_BLOCK_GROUP) in;

void main() {
  int size = int(frame.counts.w);
  int block_size = int(TYN_EPIPOLAR_SHADOW_BLOCK);
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(block * block_size, ivec2(size)))) return;
  ivec2 lo = block * block_size;
  ivec2 hi = min(lo + block_size, ivec2(size));
  vec2 range = vec2(1.0, 0.0);
  // 2 × 2 texels per gather, taken at the corner they share (a whole texel from the footprint's
  // other choices, so rounding cannot move it). Blocks have an even side: only a map of odd size
  // has a last texel without a partner, and there the corner is the map's edge, whose clamp
  // repeats that texel.
  float n = float(size);
  for (int y = lo.y; y < hi.y; y += 2) {
    for (int x = lo.x; x < hi.x; x += 2) {
      vec4 depth = textureGather(shadow_maps[0], vec2(x + 1, y + 1) / n);
      range = vec2(min(range.x, min(min(depth.x, depth.y), min(depth.z, depth.w))),
                   max(range.y, max(max(depth.x, depth.y), max(depth.z, depth.w))));
    }
  }
  imageStore(shadow_blocks, block, vec4(range, 0.0, 0.0));
}
