#version 460
// The nearest and farthest occluder depth over each block of tyn_shadow_block_size()² texels (the
// last row and column of blocks clipped to the map) of each shadow map, map m's blocks in rows
// [m · side, (m + 1) · side) of the image: the block steps of the walk (block_walk.glsl). One
// thread per block; z: the map (one for a directional light, six for a point light).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"

layout(local_size_x = TYN_EPIPOLAR_SHADOW_BLOCK_GROUP, local_size_y = TYN_EPIPOLAR_SHADOW_BLOCK_GROUP) in;

// 2 × 2 texels of one shadow map (constant indices only: see tyn_shadow_texel).
vec4 tyn_gather_shadow(uint map, vec2 uv) {
  switch (map) {
    case 0u: return textureGather(shadow_maps[0], uv);
    case 1u: return textureGather(shadow_maps[1], uv);
    case 2u: return textureGather(shadow_maps[2], uv);
    case 3u: return textureGather(shadow_maps[3], uv);
    case 4u: return textureGather(shadow_maps[4], uv);
    default: return textureGather(shadow_maps[5], uv);
  }
}

void main() {
  int size = int(frame.shadow_map_size);
  int block_size = tyn_shadow_block_size();
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  uint map = gl_GlobalInvocationID.z;
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
      vec4 depth = tyn_gather_shadow(map, vec2(x + 1, y + 1) / n);
      range = vec2(min(range.x, min(min(depth.x, depth.y), min(depth.z, depth.w))),
                   max(range.y, max(max(depth.x, depth.y), max(depth.z, depth.w))));
    }
  }
  int side = (size + block_size - 1) / block_size;
  imageStore(shadow_blocks, ivec2(block.x, int(map) * side + block.y), vec4(range, 0.0, 0.0));
}
