// Row depth bounds: exact verdicts for the view rays that moments cannot be sure about.
//
// A prefix sum holds the distribution of occluder depths along its row up to a ray's end, and the
// reconstruction bounds the fraction in front of the ray's depth z_r. The bounds are sharp only
// for distributions of a few points: a spread of depths that ends just short of z_r (a room's
// roof above every point of a ray that ends on the ceiling) leaves a Gauss–Radau weight of doubt
// at z_r (1/9 of the mass with 4 moments, 1/16 with 6, more with the bias α_b), and β = ½ lets half
// of it through — a leak that is several times the mean where the scene is mostly dark. Yet that
// ray is entirely in shadow, and the row says so: every occluder depth up to the ray's end is
// smaller than z_r. The same holds the other way for a ray with nothing in front of it.
//
// So the rectification also writes each texel's smallest and largest occluder depth (of the host
// texels its lookup mixes: rectify.glsl), the prefix-sum pass their running minimum and maximum along the row, and the
// evaluation takes, over the texels its bilinear lookup at the ray's end reads:
//   max < z_r  → the whole ray is in shadow: visibility 0, exactly what the representation holds;
//   min ≥ z_r  → nothing is in front anywhere: visibility 1;
//   otherwise  → the moments (or Fourier series) as before.
// Both verdicts are the representation's own answer (every texel the lookup mixes agrees), so they
// can only remove reconstruction error. The idea is yusov2013's 1D min/max trees, reduced to the
// prefix along a row because every prefiltered lookup covers a ray from the camera.
//
// Storage: RG16_UNORM, min rounded down and max rounded up (tyn_depth_bounds_quantize), so that
// rounding never turns a mixed row into a verdict.
#ifndef TYNDALL_PREFILTERED_DEPTH_BOUNDS_H
#define TYNDALL_PREFILTERED_DEPTH_BOUNDS_H

#include "common/cpp_glsl.h"

TYN_BEGIN

// UNORM16 steps; the margin keeps float rounding of x·65535 from crossing an integer.
TYN_CONST float TYN_DEPTH_BOUNDS_STEPS = 65535.0f;
TYN_CONST float TYN_DEPTH_BOUNDS_MARGIN = 0.01f;

// No occluder yet: the identities of min and max.
TYN_FUNC vec2 tyn_depth_bounds_empty() { return vec2(1.0f, 0.0f); }

TYN_FUNC vec2 tyn_depth_bounds_merge(vec2 a, vec2 b) { return vec2(min(a.x, b.x), max(a.y, b.y)); }

// (min, max) of depths in [0, 1] to values a UNORM16 channel holds exactly, outwards.
TYN_FUNC vec2 tyn_depth_bounds_quantize(vec2 bounds) {
  float lo = floor(bounds.x * TYN_DEPTH_BOUNDS_STEPS - TYN_DEPTH_BOUNDS_MARGIN);
  float hi = ceil(bounds.y * TYN_DEPTH_BOUNDS_STEPS + TYN_DEPTH_BOUNDS_MARGIN);
  return vec2(clamp(lo, 0.0f, TYN_DEPTH_BOUNDS_STEPS), clamp(hi, 0.0f, TYN_DEPTH_BOUNDS_STEPS)) /
         TYN_DEPTH_BOUNDS_STEPS;
}

// The verdict of a ray at rectified depth `depth_ray` over occluders within `bounds`: 0 (in
// shadow along its whole length), 1 (lit along its whole length) or −1 (the reconstruction decides).
// An occluder shadows where its depth is smaller than the ray's (a cleared texel has depth 1).
TYN_FUNC float tyn_depth_bounds_verdict(vec2 bounds, float depth_ray) {
  if (bounds.y < depth_ray) return 0.0f;
  if (bounds.x >= depth_ray) return 1.0f;
  return -1.0f;
}

// The texels of a row's prefix bounds that cover a lookup at the ray's end u (texture
// coordinate along the row) and row coordinate v: the column holding u (the bilinear lookup at
// tyn_prefix_lookup_u(u) reads it and the one before, whose prefix it contains) and the two rows
// the row interpolation reads (wrapping when `wrap`, else clamped). Returns (column, row0, row1).
TYN_FUNC ivec3 tyn_depth_bounds_texels(float u, float v, int columns, int rows, bool wrap) {
  int column = clamp(int(floor(u * float(columns))), 0, columns - 1);
  int row0 = int(floor(v * float(rows) - 0.5f));
  int row1 = row0 + 1;
  if (wrap) {
    row0 = (row0 % rows + rows) % rows;
    row1 = (row1 % rows + rows) % rows;
  } else {
    row0 = clamp(row0, 0, rows - 1);
    row1 = clamp(row1, 0, rows - 1);
  }
  return ivec3(column, row0, row1);
}

// ---------------------------------------------------------------------------------------------
// Min/max trees along the rows: trimmed segments
//
// A segment of a ray (weight_taps.h) whose texels are not all on one side of z_r may still be on
// one side for most of its length: a ray that leaves a roof's shadow into a window's beam has a
// run of texels in shadow, then a run that is lit. Its moments leave doubt about the occluders
// just in front of z_r (the run in shadow ends there) and β lets a share through. The row says
// where each run ends, so the evaluation trims both runs off the segment, counts them exactly
// (0 or 1, with the pixel's own weights) and reconstructs only what lies between: the columns
// from the first texel that is not on the first texel's side to the last that is not on the last
// texel's side. Finding those ends is yusov2013's 1D min/max tree (one per row), searched from
// the segment's two ends in O(log N) nodes.
//
// Layout: the tree's levels side by side in the texel image, level 0 (the texels) at x ∈ [0, N),
// level l ≥ 1 (node j = the merge of texels [j·2^l, (j+1)·2^l)) right after level l − 1; a level
// holds ⌈N / 2^l⌉ nodes and the last level one. The rectification writes level 0, the prefix-sum
// pass the others.

TYN_CONST uint TYN_DEPTH_BOUNDS_MAX_LEVELS = 13u;  // N ≤ 4096 columns: levels 0..12

// Nodes of level `level` of a row of `columns` texels: ⌈N / 2^l⌉.
TYN_FUNC int tyn_depth_bounds_level_nodes(int columns, uint level) {
  return (columns + (1 << level) - 1) >> level;
}

// Levels of a row's tree, down to one node: 1 + ⌈log2 N⌉ (1 for one column).
TYN_FUNC uint tyn_depth_bounds_levels(int columns) {
  return columns > 1 ? uint(findMSB(columns - 1)) + 2u : 1u;
}

// x of the first node of `level`: Σ_{j<l} ⌈N/2^j⌉ in closed form, since every search reads it for
// every node it visits. With M = N − 1, ⌈N/2^j⌉ = ⌊M/2^j⌋ + 1, and Σ_{j≥0} ⌊M/2^j⌋ = 2M − popcount(M)
// (Legendre), so the first l terms are that sum less the same sum for ⌊M/2^l⌋ (the test checks it
// against the levels' node counts).
TYN_FUNC int tyn_depth_bounds_level_offset(int columns, uint level) {
  int m = columns - 1;
  int rest = m >> level;
  return int(level) + (2 * m - bitCount(m)) - (2 * rest - bitCount(rest));
}

// Width of the image holding a row's whole tree (< 2N + levels).
TYN_FUNC int tyn_depth_bounds_tree_width(int columns) {
  uint levels = tyn_depth_bounds_levels(columns);
  return tyn_depth_bounds_level_offset(columns, levels);
}

// Node `index` of `level` of the tree of the rows a lookup reads (both rows of its bilinear
// lookup merged; rows_columns = (row0, row1, N)): defined by the includer (prefiltered_common.glsl
// reads the image; the unit test reads its own rows).
vec2 tyn_depth_bounds_node(ivec3 rows_columns, uint level, int index);

// The first column in [first, last] whose texel is not on `side` (the verdict 0 or 1 a run
// shares), or last + 1 when the whole range is: a descent from the left, skipping whole nodes
// that are on `side` and climbing while the next node is a left child.
TYN_FUNC int tyn_depth_bounds_run_end(ivec3 rows_columns, int first, int last, float depth_ray, float side) {
  int columns = rows_columns.z;
  uint levels = tyn_depth_bounds_levels(columns);
  int i = first;
  uint level = 0u;
  // A search climbs, then descends, at most once through the levels: about 2 nodes per level.
  for (uint step = 0u; step < 4u * TYN_DEPTH_BOUNDS_MAX_LEVELS; ++step) {
    if ((i << level) > last || i >= tyn_depth_bounds_level_nodes(columns, level)) return last + 1;
    if (tyn_depth_bounds_verdict(tyn_depth_bounds_node(rows_columns, level, i), depth_ray) == side) {
      i += 1;
      while ((i & 1) == 0 && level + 1u < levels) {
        i >>= 1;
        level += 1u;
      }
    } else {
      if (level == 0u) return i;
      i *= 2;
      level -= 1u;
    }
  }
  return min(i << level, last + 1);  // not reached; the start of the node left is a safe end
}

// The last column in [first, last] whose texel is not on `side`, or first − 1 when the whole
// range is: the mirror image of tyn_depth_bounds_run_end.
TYN_FUNC int tyn_depth_bounds_run_begin(ivec3 rows_columns, int first, int last, float depth_ray, float side) {
  int columns = rows_columns.z;
  uint levels = tyn_depth_bounds_levels(columns);
  int i = last;
  uint level = 0u;
  for (uint step = 0u; step < 4u * TYN_DEPTH_BOUNDS_MAX_LEVELS; ++step) {
    if (i < 0 || ((i + 1) << level) - 1 < first) return first - 1;
    // A node past the end of its level (the right child of a level's last node) holds nothing.
    bool on_side = i >= tyn_depth_bounds_level_nodes(columns, level) ||
                   tyn_depth_bounds_verdict(tyn_depth_bounds_node(rows_columns, level, i), depth_ray) == side;
    if (on_side) {
      i -= 1;
      while ((i & 1) == 1 && level + 1u < levels) {
        i >>= 1;
        level += 1u;
      }
    } else {
      if (level == 0u) return i;
      i = 2 * i + 1;
      level -= 1u;
    }
  }
  return max(((i + 1) << level) - 1, first - 1);
}

// ---------------------------------------------------------------------------------------------
// Texel walk
//
// What a trimmed segment leaves between its two runs is reconstructed from the difference of two
// lookups: the distribution of every occluder of those columns, which for a ray that crosses a
// window beam is the wall's edge in front of it, the beam, and the other edge. The moments leave
// doubt at both edges and β lets a share of it through. The row knows more: the runs inside the
// middle are decided too, and an undecided texel is a distribution of two depths (the filtered
// resampling's, Algorithm 2: the representation's own content), whose visibility at z_r is exact.
// So the evaluation walks the middle from its start, a bounded number of steps: a decided run is
// skipped with the tree search and counts 0 or 1, an undecided texel counts the share of its two
// depths at or beyond z_r, both rows of the lookup interpolated as the bilinear lookup does. What
// the steps do not reach is reconstructed as before.
//
// Storage: RGBA16_UNORM per rectified texel, (z1, z2, w2): the two rectified depths and the weight
// of the second (w1 = 1 − w2). Without filtered resampling a texel has one depth: (z, 1, 0).

// The visibility at `depth_ray` of one texel's two depths: the weight of those not in front.
TYN_FUNC float tyn_two_depth_visibility(vec3 texel, float depth_ray) {
  return (1.0f - texel.z) * (texel.x >= depth_ray ? 1.0f : 0.0f) + texel.z * (texel.y >= depth_ray ? 1.0f : 0.0f);
}

TYN_END

#endif
