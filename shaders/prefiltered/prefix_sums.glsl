// Transmittance-weighted prefix sums along each row of the rectified map (klehm2014 §3.2 and
// Appendix A, peters2017 §5.1.1): texel i of a row receives the normalised weighted average
//   b_Σ(i) = Σ_{j ≤ i} w_j b(j) / Σ_{j ≤ i} w_j,  w_j = ∫ e^{−σ t} dt over texel j of the row's
// reference ray (rectification.h), which keeps the stored range, so unorm textures work.
// One workgroup layer (gl_WorkGroupID.z) per (prefix-sum set, slot): the slots of a
// representation and the sets of the per-channel extinctions are independent (peters2017 App. C:
// "if the shadow map consists of multiple textures, they are processed in parallel").
// Three schemes, one source; the workgroup size is specialised (constant_id 0, 1), the scan's walk
// by constant_id 2:
//   - row-parallel (peters2017 Appendix C), TYN_PF_ROW_THREADS × TYN_PF_ROWS_PER_GROUP: every
//     thread of a row accumulates the whole row but writes only its texel of each block of
//     TYN_PF_ROW_THREADS texels, so a row's writes are contiguous (coalesced) and eight times as
//     many threads run; the reads are repeated, from the texture cache;
//   - one thread per row (klehm2014 §3.3), 1 × TYN_PF_THREAD_PER_ROW_GROUP.
//   - a workgroup scan, TYN_PF_SCAN_THREADS × 1: a row's threads each blend their own run of
//     consecutive texels, a scan over the runs (log2 of the threads rounds in shared memory) gives
//     each run what comes before it, and each thread blends its run again from there, writing.
//     The two schemes above are a chain of `columns` dependent blends per row (a 2048-step chain
//     on a GPU, whatever its width); this one is `2·columns/threads + log2(threads)` steps.
// The first two produce the same values bit for bit (every thread runs the same sequence of
// blends); the scan merges runs in another order, so its values differ by rounding.
// The first layer's workgroups also take the running min and max of the rectified texels' depth
// bounds along the row (depth_bounds.h), with the same lanes and writes. With trimmed segments one
// more layer of workgroups builds the rows' min/max trees (tyn_pf_build_bounds_tree).
// Included by prefix_sums_<variant>.comp after defining TYN_PF_BASIS.

#include "prefiltered/prefiltered_common.glsl"
#include "prefiltered/storage_variants.glsl"

layout(local_size_x_id = 0, local_size_y_id = 1) in;
// 1: the workgroup scan (one row per workgroup, gl_WorkGroupSize.x ≤ TYN_PF_SCAN_THREADS lanes).
layout(constant_id = 2) const uint TYN_PF_SCAN = 0u;

// The workgroup scan's partials, one per lane: a run's weighted average, its weight and its depth
// bounds (the first layer's).
shared vec4 tyn_scan_average[TYN_PF_SCAN_THREADS];
shared float tyn_scan_weight[TYN_PF_SCAN_THREADS];
shared vec2 tyn_scan_bounds[TYN_PF_SCAN_THREADS];

// A row's reference ray, which weights its texels (rectification.h).
struct TynPfRowRay {
  bool projective;
  float eta;
  float reference_sin;
  float spacing;
  float sigma;
};

float tyn_pf_texel_weight(TynPfRowRay ray, uint i, uint columns) {
  vec2 span = ray.projective ? tyn_projective_texel_span(pf.projective, i, float(columns), ray.eta, ray.reference_sin)
                             : tyn_nonlinear_texel_span(i, ray.spacing);
  return tyn_prefix_weight(span, ray.sigma);
}

// Adds texel i to a run: its weighted average, the run's weight and (bounds_layer) its depth bounds.
// weight_sum > 0 from the first texel of a row on (it starts at the camera and has positive
// length); the guard only keeps a degenerate row (zero-length texels) finite.
void tyn_pf_add_texel(TynPfRowRay ray, uint i, uint row, uint slot, bool bounds_layer, inout vec4 average,
                      inout float weight_sum, inout vec2 running) {
  float weight = tyn_pf_texel_weight(ray, i, pf.map_columns);
  weight_sum += weight;
  if (weight_sum > 0.0) average = tyn_prefix_blend(average, tyn_pf_load_rectified(ivec2(i, row), slot), weight, weight_sum);
  if (bounds_layer) running = tyn_depth_bounds_merge(running, imageLoad(depth_bounds_texels, ivec2(i, row)).xy);
}

// The workgroup scan of one row (see the top). Merging the run before (average a, weight A) with a
// run (b, B) is the blend that adds one texel: mix(a, b, B / (A + B)); the depth bounds merge by
// min and max, exactly. Every lane of the workgroup calls it (barriers); the row is uniform.
void tyn_pf_scan_row(TynPfRowRay ray, uint lane, uint lanes, uint row, uint set, uint slot, bool bounds_layer) {
  uint columns = pf.map_columns;
  uint run = (columns + lanes - 1u) / lanes;
  uint first = min(lane * run, columns);
  uint last = min(first + run, columns);
  vec4 average = vec4(0.0);
  float weight_sum = 0.0;
  vec2 running = tyn_depth_bounds_empty();
  for (uint i = first; i < last; ++i) tyn_pf_add_texel(ray, i, row, slot, bounds_layer, average, weight_sum, running);

  // Inclusive scan over the lanes (Hillis and Steele): after the round with offset d, lane k holds
  // the merge of runs k − 2d + 1 .. k.
  tyn_scan_average[lane] = average;
  tyn_scan_weight[lane] = weight_sum;
  tyn_scan_bounds[lane] = running;
  barrier();
  for (uint offset = 1u; offset < lanes; offset *= 2u) {
    if (lane >= offset) {
      float before = tyn_scan_weight[lane - offset];
      float total = before + weight_sum;
      if (total > 0.0) average = tyn_prefix_blend(tyn_scan_average[lane - offset], average, weight_sum, total);
      weight_sum = total;
      running = tyn_depth_bounds_merge(tyn_scan_bounds[lane - offset], running);
    }
    barrier();
    tyn_scan_average[lane] = average;
    tyn_scan_weight[lane] = weight_sum;
    tyn_scan_bounds[lane] = running;
    barrier();
  }

  // Each run again from everything before it (the lane before's inclusive partial), writing.
  average = lane > 0u ? tyn_scan_average[lane - 1u] : vec4(0.0);
  weight_sum = lane > 0u ? tyn_scan_weight[lane - 1u] : 0.0;
  running = lane > 0u ? tyn_scan_bounds[lane - 1u] : tyn_depth_bounds_empty();
  for (uint i = first; i < last; ++i) {
    tyn_pf_add_texel(ray, i, row, slot, bounds_layer, average, weight_sum, running);
    tyn_pf_store_prefix(ivec2(i, row), set, slot, average);
    if (bounds_layer) imageStore(depth_bounds_prefix, ivec2(i, row), vec4(running, 0.0, 0.0));
  }
}

// The levels ≥ 1 of the min/max tree of one row (depth_bounds.h), level by level from the one
// below: the row's lanes share each level's nodes, then wait for each other (the image is
// coherent) before the next. N − 1 merges per row, a few percent of the prefix sums' blends.
// Called by every invocation of the workgroup (it synchronises them); rows past the map idle.
void tyn_pf_build_bounds_tree(uint lane, uint lanes, uint row, uint rows) {
  int columns = int(pf.map_columns);
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
  uint columns = pf.map_columns;
  uint rows = pf.map_rows;
  // The layer after the prefix sums' (set, slot) layers: the trees (uniform per workgroup).
  if (gl_WorkGroupID.z == pf.prefix_sum_sets * TYN_PF_SLOTS) {
    tyn_pf_build_bounds_tree(lane, lanes, row, rows);
    return;
  }
  if (row >= rows) return;
  uint slot = gl_WorkGroupID.z % TYN_PF_SLOTS;
  uint set = gl_WorkGroupID.z / TYN_PF_SLOTS;

  // The row's slice and its reference ray (per-slice spacing Δ(v)).
  TynPfRowRay ray;
  ray.sigma = pf.set_extinction[set];
  float v = (float(row) + 0.5) / float(rows);
  ray.reference_sin = tyn_pf_reference_sin(tyn_pf_row_phi(v));
  ray.projective = tyn_pf_projective();
  ray.eta = ray.projective ? tyn_projective_eta(pf.projective, v) : 0.0;
  ray.spacing = tyn_slice_sample_spacing(pf.nonlinear.r_max / float(columns), ray.reference_sin);
  bool bounds_layer = tyn_pf_depth_bounds() && gl_WorkGroupID.z == 0u;

  if (TYN_PF_SCAN != 0u) {
    tyn_pf_scan_row(ray, lane, lanes, row, set, slot, bounds_layer);
    return;
  }
  vec4 average = vec4(0.0);
  float weight_sum = 0.0;
  vec2 running = tyn_depth_bounds_empty();
  for (uint base = 0u; base < columns; base += lanes) {
    vec4 mine = vec4(0.0);
    vec2 mine_bounds = running;
    for (uint k = 0u; k < lanes; ++k) {
      uint i = base + k;
      if (i >= columns) break;
      tyn_pf_add_texel(ray, i, row, slot, bounds_layer, average, weight_sum, running);
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
