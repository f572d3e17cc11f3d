// Coloured shafts by prefix sums: the light-colour texture along each slice's line, summed cell by
// cell, so that a lit section of any length takes its mean colour from four texels.
//
// yusov2013 ("Colored Light Shafts") walks every lit section of a coloured light at the fine step,
// one colour per step, because the colour varies along it; the min/max tree then only skips
// shadowed nodes. But along a slice's line the colour is a function of the line's 1D parameter u
// alone (every view ray of the slice projects onto the line, and the texture lies over shadow map
// 0's UV square), the same for every ray of the slice. So it is summed once per slice (the pass
// slice_setup.comp) and the march integrates a lit section [a, b] as
//     ∫ c(u) w(u) du ≈ c̄(a, b) · ∫ w(u) du,   c̄(a, b) = (1 / (b − a)) ∫_a^b c(u) du,
// with w the uncoloured integrand (a directional light's closed form, a spot light's quadrature): exact
// for a constant colour, and otherwise off by the covariance of c and w over the section, which
// grows with the section's length. The marches cut lit sections into chunks of
// EpipolarSettings::coloredStep cells (min_max_tree.h, tyn_min_max_add_colored); docs/EPIPOLAR.md
// "Coloured shafts" measures the trade.
//
// ## The colour along the line
// c(u) is constant on each cell: c_k, the texture's (bilinear) colour at the cell centre p(k + ½)
// (the colour yusov2013's fine step takes; white outside the texture's square, common/
// light_color.glsl). The pass stores the inclusive sums S_k = Σ_{i ≤ k} c_i, k ∈ [0, L), RGB of an
// RGBA32F texel (alpha unused). Then ∫_0^u c = S_{k−1} + (u − k) c_k with k = floor(u), c_k =
// S_k − S_{k−1} and S_{−1} = 0.
// Precision: S_k grows to L · max c (2048 for a 2048-texel map and a white texture), so a
// difference of two sums carries about 2.4e-4 of absolute rounding (one float ulp at 2048): a mean
// over one cell is within ~5e-4 of c_k relatively, and longer sections proportionally closer.
//
// ## Layout
// Slice s's L sums fill TYN_COLOR_SUMS_ROWS(L) rows of at most TYN_COLOR_SUMS_MAX_WIDTH texels
// (L is a power of two): sum k of slice s at (k mod W, s · rows + k / W), W = min(L, max width),
// so that a map above 4096² (L = 8192) still fits the 4096 texels Vulkan guarantees per side.
//
// ## Accessor: define before including (as min_max_tree.h's)
//   TYN_COLOR_SUM(k)   vec3: S_k of the slice being marched, k ∈ [0, L)
// In C++ the functions are templates whose first parameter has `vec3 sum(int k) const`.
#ifndef TYNDALL_LIGHT_COLOR_SUMS_H
#define TYNDALL_LIGHT_COLOR_SUMS_H

#include "common/cpp_glsl.h"

#ifdef __cplusplus
#define TYN_COLOR_SUMS_TEMPLATE template <class TynSums>
#define TYN_COLOR_SUMS_ACCESS const TynSums &tyn_sums,
#define TYN_COLOR_SUM(k) tyn_sums.sum(k)
#else
#define TYN_COLOR_SUMS_TEMPLATE
#define TYN_COLOR_SUMS_ACCESS
#endif

TYN_BEGIN

TYN_CONST int TYN_COLOR_SUMS_MAX_WIDTH = 4096;

TYN_FUNC int tyn_color_sums_width(int sample_count) { return min(sample_count, TYN_COLOR_SUMS_MAX_WIDTH); }

TYN_FUNC int tyn_color_sums_rows(int sample_count) {
  return sample_count / tyn_color_sums_width(sample_count);
}

// The texel of sum k of slice `slice`.
TYN_FUNC ivec2 tyn_color_sums_texel(int sample_count, int slice, int k) {
  int width = tyn_color_sums_width(sample_count);
  return ivec2(k % width, slice * tyn_color_sums_rows(sample_count) + k / width);
}

#if defined(TYN_COLOR_SUM)
// c̄(a, b), the mean colour over [a, b] ⊆ [0, L] (a < b): ∫_a^b c / (b − a) from the sums. A
// section inside one cell takes that cell's colour (the quotient would only add rounding).
TYN_COLOR_SUMS_TEMPLATE
TYN_FUNC vec3 tyn_color_sums_mean(TYN_COLOR_SUMS_ACCESS int sample_count, float a, float b) {
  int ka = clamp(int(floor(a)), 0, sample_count - 1);
  int kb = clamp(int(ceil(b)) - 1, ka, sample_count - 1);  // the cell holding b's left side
  vec3 sa = TYN_COLOR_SUM(ka);
  vec3 ca = ka > 0 ? sa - TYN_COLOR_SUM(ka - 1) : sa;
  if (kb == ka) return ca;
  vec3 sb_before = TYN_COLOR_SUM(kb - 1);
  vec3 cb = TYN_COLOR_SUM(kb) - sb_before;
  // The rest of cell ka, the whole cells between, the start of cell kb.
  vec3 integral = (float(ka + 1) - a) * ca + (sb_before - sa) + (b - float(kb)) * cb;
  return integral / (b - a);
}
#endif

TYN_END

#ifdef __cplusplus
#undef TYN_COLOR_SUM
#endif
#undef TYN_COLOR_SUMS_TEMPLATE
#undef TYN_COLOR_SUMS_ACCESS

#endif
