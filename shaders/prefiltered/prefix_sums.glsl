// Transmittance-weighted prefix sums along each row of the rectified map (klehm2014 §3.2 and
// Appendix A, peters2017 §5.1.1): texel i of a row receives the normalised weighted average
//   b_Σ(i) = Σ_{j ≤ i} w_j b(j) / Σ_{j ≤ i} w_j,  w_j = ∫ e^{−σ t} dt over texel j of the row's
// reference ray (rectification.h), which keeps the stored range, so unorm textures work.
// One workgroup layer (gl_WorkGroupID.z) per (prefix-sum set, slot): the slots of a
// representation and the sets of the per-channel extinctions are independent (peters2017 App. C:
// "if the shadow map consists of multiple textures, they are processed in parallel").
// Two schemes, one source; the workgroup size is specialised (constant_id 0, 1):
//   - row-parallel (peters2017 Appendix C), TYN_PF_ROW_THREADS × TYN_PF_ROWS_PER_GROUP: every
//     thread of a row accumulates the whole row but writes only its texel of each block of
//     TYN_PF_ROW_THREADS texels, so a row's writes are contiguous (coalesced) and eight times as
//     many threads run; the reads are repeated, from the texture cache;
//   - one thread per row (klehm2014 §3.3), 1 × TYN_PF_THREAD_PER_ROW_GROUP.
// Both produce the same values bit for bit: every thread runs the same sequence of blends.
// The first layer's workgroups also take the running min and max of the rectified texels' depth
// bounds along the row (depth_bounds.h), with the same lanes and writes. With trimmed segments one
// more layer of workgroups builds the rows' min/max trees (tyn_pf_build_bounds_tree).
// Included by prefix_sums_<variant>.comp after defining TYN_PF_BASIS.

#include "prefiltered/prefiltered_common.glsl"
#include "prefiltered/storage_variants.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1) in;

// The levels ≥ 1 of the min/max tree of one row (depth_bounds.h), level by level from the one
// below: the row's lanes share each level's nodes, then wait for each other (the image is
// coherent) before the next. N − 1 merges per row, a few percent of the prefix sums' blends.
// Called by every invocation of the workgroup (it synchronises them); rows past the map idle.
void tyn_pf_build_bounds_tree(uint lane, uint lanes, uint row, uint rows) {
  int columns = int(pf.map.x);
  uint levels = tyn_depth_bounds_levels(columns);
  int below = 0;
  int nodes_below = columns;
  for (uint level = 1u; level < levels; ++level) {
    int offset = below + nodes_below;
    int nodes = tyn_depth_bounds_level_nodes(columns, level);
    if (row < rows) {
      for (int j = int(lane); j < nodes; j += int(lanes)) {
        vec2 left = imageLoad(depth_bounds_texels, ivec2(below + 2 * j, row)).xy;
        vec2 right = 2 * j + 1 < nodes_below ? imageLoad(depth_bounds_texels, ivec2(below + 2 * j + 1, row)).xy
                                             : tyn_depth_bounds_empty();
        imageStore(depth_bounds_texels, ivec2(offset + j, row), vec4(tyn_depth_bounds_merge(left, right), 0.0, 0.0));
      }
    }
    memoryBarrierImage();
    barrier();
    below = offset;
    nodes_below = nodes;
  }
}

void main() {
  uint lane = gl_LocalInvocationID.x;
  uint lanes = gl_WorkGroupSize.x;
  uint row = gl_WorkGroupID.y * gl_WorkGroupSize.y + gl_LocalInvocationID.y;
  uint columns = pf.map.x;
  uint rows = pf.map.y;
  // The layer after the prefix sums' (set, slot) layers: the trees (uniform per workgroup).
  if (gl_WorkGroupID.z == pf.options.z * TYN_PF_SLOTS) {
    tyn_pf_build_bounds_tree(lane, lanes, row, rows);
    return;
  }
  if (row >= rows) return;
  uint slot = gl_WorkGroupID.z % TYN_PF_SLOTS;
  uint set = gl_WorkGroupID.z / TYN_PF_SLOTS;
  float sigma = pf.set_extinction[set];

  // The row's slice and its reference ray (per-slice spacing Δ(v)).
  float v = (float(row) + 0.5) / float(rows);
  float reference_sin = tyn_pf_reference_sin(tyn_pf_row_phi(v));
  bool projective = tyn_pf_projective();
  float eta = projective ? tyn_projective_eta(pf.projective, v) : 0.0;
  float spacing = tyn_slice_sample_spacing(pf.nonlinear.origin.w / float(columns), reference_sin);

  vec4 average = vec4(0.0);
  float weight_sum = 0.0;
  bool bounds_layer = tyn_pf_depth_bounds() && gl_WorkGroupID.z == 0u;
  vec2 running = tyn_depth_bounds_empty();
  for (uint base = 0u; base < columns; base += lanes) {
    vec4 mine = vec4(0.0);
    vec2 mine_bounds = running;
    for (uint k = 0u; k < lanes; ++k) {
      uint i = base + k;
      if (i >= columns) break;
      vec2 span = projective ? tyn_projective_texel_span(pf.projective, i, float(columns), eta, reference_sin)
                             : tyn_nonlinear_texel_span(i, spacing);
      float weight = tyn_prefix_weight(span, sigma);
      weight_sum += weight;
      // weight_sum > 0 from the first texel on (it starts at the camera and has positive
      // length); the guard only keeps a degenerate row (zero-length texels) finite.
      if (weight_sum > 0.0) {
        average = tyn_prefix_blend(average, tyn_pf_load_rectified(ivec2(i, row), slot), weight, weight_sum);
      }
      if (bounds_layer) running = tyn_depth_bounds_merge(running, imageLoad(depth_bounds_texels, ivec2(i, row)).xy);
      if (k == lane) {
        mine = average;
        mine_bounds = running;
      }
    }
    if (base + lane < columns) {
      tyn_pf_store_prefix(ivec2(base + lane, row), set, slot, mine);
      if (bounds_layer) imageStore(depth_bounds_prefix, ivec2(base + lane, row), vec4(mine_bounds, 0.0, 0.0));
    }
  }
}
