#version 460
// 1D min/max binary trees (yusov2013 "Min/max binary tree construction"), one workgroup per slice:
// level 0 from the shadow map along the slice's line (each cell's conservative 2×2 footprint, so
// that the accelerated march equals the plain one), then each coarser level from the one below,
// up to the highest level the march may use. Levels ping-pong between two halves of shared
// memory; every level is also written to the slice's row of the tree texture.
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#define TYN_MIN_MAX_SHADOW_TEXEL(texel) tyn_epipolar_shadow_texel(texel)
#include "epipolar/min_max_tree.h"

layout(local_size_x = TYN_EPIPOLAR_TREE_GROUP) in;

// Level l (l even) at [0, L/2), level l + 1 at [L/2, 3L/4): 24 KiB for L = 4096.
shared vec2 tyn_nodes[TYN_EPIPOLAR_TREE_MAX_SAMPLES / 2 + TYN_EPIPOLAR_TREE_MAX_SAMPLES / 4];

void main() {
  int slice = int(gl_WorkGroupID.x);
  vec4 origin_direction = imageLoad(slice_uv, ivec2(slice, 0));
  // Uniform across the workgroup: the march does not read the tree of a slice without a line.
  if (!tyn_slice_valid(origin_direction)) return;
  int sample_count = int(epipolar.tree_samples);
  int top_level = int(epipolar.tree_top_level);
  int thread = int(gl_LocalInvocationIndex);
  int group = int(TYN_EPIPOLAR_TREE_GROUP);
  vec2 origin = vec2(origin_direction.x, origin_direction.y) * float(frame.shadow_map_size);
  vec2 step = tyn_min_max_step_texels(vec2(origin_direction.z, origin_direction.w));

  int nodes = tyn_min_max_level_nodes(sample_count, 0);
  for (int i = thread; i < nodes; i += group) {
    vec2 node = tyn_min_max_level0_node(origin, step, i);
    tyn_nodes[i] = node;
    imageStore(min_max_tree, ivec2(tyn_min_max_level_offset(sample_count, 0) + i, slice), vec4(node, 0.0, 0.0));
  }
  int from = 0;
  int to = sample_count / 2;
  for (int level = 1; level <= top_level; ++level) {
    barrier();
    nodes = tyn_min_max_level_nodes(sample_count, level);
    for (int i = thread; i < nodes; i += group) {
      vec2 node = tyn_min_max_merge(tyn_nodes[from + 2 * i], tyn_nodes[from + 2 * i + 1]);
      tyn_nodes[to + i] = node;
      imageStore(min_max_tree, ivec2(tyn_min_max_level_offset(sample_count, level) + i, slice),
                 vec4(node, 0.0, 0.0));
    }
    int swap = from;
    from = to;
    to = swap;
  }
}
