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

TYN_END

#endif
