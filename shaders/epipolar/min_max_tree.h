// 1D min/max binary trees over an epipolar slice (yusov2013 "1D min/max binary trees", after
// Chen et al. 2011), and the two marches that read them: the accelerated one (fully lit tree nodes
// integrated in one step, fully shadowed ones skipped, mixed ones descended) and the plain one
// (every 1D sample, no tree; the fix-up pass and the tree-off profile). Both give the same lit
// set, so the tree changes the cost, never the answer (integration-tests/unit/test_min_max_tree.cpp).
//
// ## The 1D slice and its cells
// A slice's line in shadow-map texel units (uv · N; texel (i, j) covers [i, i+1) × [j, j+1), the
// convention of common/texel_walk.glsl) is p(u) = origin + u · step, u ∈ [0, L]. Cell k = the part
// u ∈ [k, k+1] (k = 0..L−1). The ray march's only question is, per point, "z(u) ≤ depth?".
//   - The plain march answers it in cell k against ONE depth, the cell's sample d_k = the texel
//     under the cell centre p(k + ½) (tyn_min_max_sample_texel), solving the linear inequality
//     exactly inside the cell (tyn_min_max_lit_part).
//   - A tree node covers 2^(level+1) consecutive cells and stores (min, max) over the 2×2 texel
//     block around each cell centre (tyn_min_max_footprint_origin), the block a bilinear/PCF tap or
//     textureGather at p(k + ½) reads.
// IMPORTANT (the footprint guarantee): with max(|step.x|, |step.y|) ≤ 1 texel, the segment
// p([k, k+1]) stays within ½ texel of p(k + ½) along each axis, so every texel it touches, however
// barely, lies in that 2×2 block (floor(c − ½) and floor(c + ½) = floor(c − ½) + 1 per axis). The
// block also holds d_k's texel. Hence a node's (min, max) bounds both the plain march's samples and
// every texel the texel-exact 2D walk (the Reference) meets along the node's span: where the tree
// decides "lit" or "shadowed", the plain march and the Reference agree with it. Recommended
// step: direction / max(|dir.x|, |dir.y|) in texels (max-norm exactly 1), so L = N samples span any
// line through an N² map. A longer step silently breaks the guarantee (a test shows it does).
//
// ## Depth conventions (those of common/texel_walk.glsl)
// A point is lit when z ≤ d. A depth d ≥ 1 (the clear value: no occluder) lights every point, even
// z > 1 beyond the map's far plane. Texels outside the map read as 1: outside a directional map
// everything is lit (a spot light's rays are truncated to its frustum before they get here). The
// ray's depth must be linear in u: true for a directional light, and for a spot light too when z
// means z/w (a projective map sends the 3D line to a line in (u, z/w)); a spot light's distance is
// not linear in u, hence TYN_MIN_MAX_INTEGRATE below.
//
// ## Accuracy against the Reference (printed by the unit test MinMaxConservative.*)
// The tree's decisions never contradict the texel-exact walk (193k decisions checked). The leaf
// rule's single sample per cell can, only in cells whose footprint is mixed: 0.1–0.35% of the
// marched length on box and smooth maps, 1.5–2.2% on per-texel noise (lit integral off by
// 0.1–0.3% and 0.6–0.9% of the unshadowed integral respectively; 32² maps, seven seeds).
//
// ## Storage: one texture row per slice, level after level
// L = 2^n samples, 2 ≤ L ≤ 4096 (pad a shorter slice up to a power of two with the clear value 1:
// padding is outside the map, hence lit). Level l ∈ [0, n−1] has L >> (l+1) nodes, node i covering
// cells [i·2^(l+1), (i+1)·2^(l+1)); level 0 = pairs of cells, level n−1 = the whole slice. Level l
// starts at column L − (L >> l) of the row, so the full tree takes L − 1 texels (≤ 4095: fits one
// row of a 4096-wide texture), and a tree built up to `top_level` only takes
// tyn_min_max_row_length(L, top_level). Format: RG16 UNORM (x = min, y = max), stored through
// tyn_min_max_stored_bounds: min rounded down and max up by a 16-bit code, so that a node still
// bounds its samples (a looser node only descends more often: the cost, never the answer), and a
// clear node (1) stays exactly 1.
//
// ## Accessors (GLSL has no pointers): define before including, as needed
//   TYN_MIN_MAX_SHADOW_TEXEL(texel)  float: shadow-map depth of ivec2 texel, 1.0 outside the map
//                                    (building level 0, and samples straight from the shadow map)
//   TYN_MIN_MAX_SAMPLE(k)            float: d_k, the cell's sample (k ∈ [0, L)). Either stored, or
//                                    tyn_min_max_cell_sample(origin, step, k) from the shadow map
//   TYN_MIN_MAX_FETCH(level, index)  vec2 (min, max) of a tree node; its column in the slice's row
//                                    is tyn_min_max_level_offset(L, level) + index
//   TYN_MIN_MAX_INTEGRATE(ray, a, b) optional, vec3: ∫ over the lit part u ∈ [a, b]; defaults to the
//                                    directional closed form (a spot light plugs its LUT in here)
//   TYN_MIN_MAX_COLOR_MEAN(a, b)     optional, vec3: the light's mean colour over [a, b] (coloured
//                                    shafts, tyn_min_max_add_colored; light_color_sums.h gives it
//                                    from prefix sums); defaults to white
// Only the functions whose accessors are defined are compiled. Example (march pass):
//   #define TYN_MIN_MAX_FETCH(level, index) texelFetch(min_max_tree,
//       ivec2(tyn_min_max_level_offset(L, level) + (index), slice), 0).xy     (on one line)
// In C++ each of these functions is a template whose first parameter is an accessor object with
// the members it uses: `float shadow_texel(ivec2) const`, `float sample(int) const`,
// `vec2 fetch(int level, int index) const`, `vec3 color_mean(float a, float b) const`. The arguments after it are
// the same in both languages.
// IMPORTANT: the samples and the tree must be built from the same shadow map with the same
// origin/step, or the tree is no longer exact.
#ifndef TYNDALL_MIN_MAX_TREE_H
#define TYNDALL_MIN_MAX_TREE_H

#include "common/segment_integral.h"

#ifdef __cplusplus
#define TYN_MIN_MAX_TEMPLATE template <class TynAccess>
#define TYN_MIN_MAX_ACCESS const TynAccess &tyn_access,
#define TYN_MIN_MAX_PASS tyn_access,
#define TYN_MIN_MAX_SHADOW_TEXEL(texel) tyn_access.shadow_texel(texel)
#define TYN_MIN_MAX_SAMPLE(k) tyn_access.sample(k)
#define TYN_MIN_MAX_FETCH(level, index) tyn_access.fetch(level, index)
#define TYN_MIN_MAX_COLOR_MEAN(a, b) tyn_access.color_mean(a, b)
#else
#define TYN_MIN_MAX_TEMPLATE
#define TYN_MIN_MAX_ACCESS
#define TYN_MIN_MAX_PASS
#endif

#ifndef TYN_MIN_MAX_INTEGRATE
#define TYN_MIN_MAX_INTEGRATE(ray, a, b) tyn_min_max_directional_integral(ray, a, b)
#endif
#ifndef TYN_MIN_MAX_COLOR_MEAN
#define TYN_MIN_MAX_COLOR_MEAN(a, b) vec3(1.0f)
#endif

TYN_BEGIN

TYN_CONST int TYN_MIN_MAX_MAX_SAMPLES = 4096;
// Classification of a ray section against a depth range.
TYN_CONST int TYN_MIN_MAX_SHADOWED = 0;
TYN_CONST int TYN_MIN_MAX_LIT = 1;
TYN_CONST int TYN_MIN_MAX_MIXED = 2;

// ---- Layout (L = sample_count, a power of two in [2, 4096]) ----

// n − 1 for L = 2^n: the level whose single node spans the whole slice.
TYN_FUNC int tyn_min_max_highest_level(int sample_count) { return findMSB(sample_count) - 1; }

// Cells covered by one node of `level`; level −1 denotes the cells themselves.
TYN_FUNC int tyn_min_max_node_span(int level) { return 1 << (level + 1); }

TYN_FUNC int tyn_min_max_level_nodes(int sample_count, int level) {
  return sample_count >> (level + 1);
}

// Column of a level's node 0 in the slice's row: Σ_{j<l} L >> (j+1) = L − (L >> l).
TYN_FUNC int tyn_min_max_level_offset(int sample_count, int level) {
  return sample_count - (sample_count >> level);
}

// Texels of the row used by levels 0..top_level (L − 1 for the full tree).
TYN_FUNC int tyn_min_max_row_length(int sample_count, int top_level) {
  return tyn_min_max_level_offset(sample_count, top_level + 1);
}

// yusov2013's "maximum step" in samples (a power of two ≥ 2) → the highest level the march may use.
TYN_FUNC int tyn_min_max_level_for_max_step(int max_step_samples) {
  return findMSB(max_step_samples) - 1;
}

// L for a shadow map of `shadow_size` texels: the power of two ≥ the size (and ≥ 2), so that L
// cells of max-norm one texel span any line through the map.
TYN_FUNC int tyn_min_max_sample_count(int shadow_size) {
  return 1 << (findMSB(max(shadow_size, 2) - 1) + 1);
}

// The recommended step for a line with direction `direction` (any length): max-norm one texel.
TYN_FUNC vec2 tyn_min_max_step_texels(vec2 direction) {
  return direction / max(abs(direction.x), abs(direction.y));
}

// The 1D parameter u of a point of the line (texel units): p(u) = origin + u · step.
TYN_FUNC float tyn_min_max_u(vec2 origin_texels, vec2 step_texels, vec2 point_texels) {
  return dot(point_texels - origin_texels, step_texels) / dot(step_texels, step_texels);
}

// ---- Building ----

// A node from its two children (min of mins, max of maxes); also level 0 from two cells' bounds.
TYN_FUNC vec2 tyn_min_max_merge(vec2 a, vec2 b) { return vec2(min(a.x, b.x), max(a.y, b.y)); }

// A node's (min, max) as 16-bit UNORM values c / 65535 that still bound it: one code below the
// floor and one above the ceiling, so that neither the product's rounding nor the conversions
// (to the code and back to a float) can cross the true bound; 1 (clear) is kept exactly.
TYN_FUNC vec2 tyn_min_max_stored_bounds(vec2 node) {
  const float codes = 65535.0f;
  float low = node.x >= 1.0f ? codes : max(floor(node.x * codes) - 1.0f, 0.0f);
  float high = node.y >= 1.0f ? codes : min(ceil(node.y * codes) + 1.0f, codes);
  return vec2(low, high) / codes;
}

// Bounds of a 2×2 block of depths (e.g. a textureGather's four texels).
TYN_FUNC vec2 tyn_min_max_footprint_bounds(vec4 depths) {
  return vec2(min(min(depths.x, depths.y), min(depths.z, depths.w)),
              max(max(depths.x, depths.y), max(depths.z, depths.w)));
}

// Centre p(k + ½) of cell k, in texel units.
TYN_FUNC vec2 tyn_min_max_cell_center(vec2 origin_texels, vec2 step_texels, int k) {
  return origin_texels + (float(k) + 0.5f) * step_texels;
}

// Lower-left texel of the 2×2 block around a cell centre (the block textureGather reads).
// IMPORTANT: compute it with this function and texelFetch rather than trusting a hardware gather,
// whose sub-texel precision (often 8 bits) may pick the neighbouring block when the centre lies
// within 1/256 texel of a texel centre, missing a sliver the line crosses.
TYN_FUNC ivec2 tyn_min_max_footprint_origin(vec2 center) { return ivec2(floor(center - 0.5f)); }

// The texel whose depth is the cell's sample d_k (nearest texel to the centre; in the 2×2 block).
TYN_FUNC ivec2 tyn_min_max_sample_texel(vec2 center) { return ivec2(floor(center)); }

#if defined(TYN_MIN_MAX_SHADOW_TEXEL)
// d_k read straight from the shadow map (the fix-up pass's TYN_MIN_MAX_SAMPLE).
TYN_MIN_MAX_TEMPLATE
TYN_FUNC float tyn_min_max_cell_sample(TYN_MIN_MAX_ACCESS vec2 origin_texels, vec2 step_texels, int k) {
  return TYN_MIN_MAX_SHADOW_TEXEL(tyn_min_max_sample_texel(tyn_min_max_cell_center(origin_texels, step_texels, k)));
}

// Conservative bounds of cell k: the 2×2 block around its centre (see the footprint guarantee).
TYN_MIN_MAX_TEMPLATE
TYN_FUNC vec2 tyn_min_max_cell_bounds(TYN_MIN_MAX_ACCESS vec2 origin_texels, vec2 step_texels, int k) {
  ivec2 t = tyn_min_max_footprint_origin(tyn_min_max_cell_center(origin_texels, step_texels, k));
  return tyn_min_max_footprint_bounds(vec4(TYN_MIN_MAX_SHADOW_TEXEL(t),
                                           TYN_MIN_MAX_SHADOW_TEXEL(t + ivec2(1, 0)),
                                           TYN_MIN_MAX_SHADOW_TEXEL(t + ivec2(0, 1)),
                                           TYN_MIN_MAX_SHADOW_TEXEL(t + ivec2(1, 1))));
}

// Level-0 node `index` (cells 2·index and 2·index + 1).
TYN_MIN_MAX_TEMPLATE
TYN_FUNC vec2 tyn_min_max_level0_node(TYN_MIN_MAX_ACCESS vec2 origin_texels, vec2 step_texels, int index) {
  return tyn_min_max_merge(tyn_min_max_cell_bounds(TYN_MIN_MAX_PASS origin_texels, step_texels, 2 * index),
                           tyn_min_max_cell_bounds(TYN_MIN_MAX_PASS origin_texels, step_texels, 2 * index + 1));
}
#endif

// ---- The view ray along the slice ----

// Shadow depth and view distance are both linear in u; they are evaluated relative to u_begin
// (not u = 0) so that a ray far along the slice does not lose its depth to cancellation.
struct TynMinMaxRay {
  float u_begin;      // 1D parameter where the march starts (samples)
  float u_end;        // where it ends; the march covers [u_begin, u_end] ∩ [0, L]
  float depth_begin;  // shadow depth z at u_begin (z/w for a spot light)
  float depth_slope;  // dz/du
  float t_begin;      // view distance at u_begin (scene units, ≥ 0)
  float t_slope;      // dt/du (scene units per sample; ≥ 0 along a slice, either sign accepted)
  vec3 sigma_t;       // extinction per scene unit
};

// The ray from its values at both ends of [u_begin, u_end] (slopes 0 when the interval is empty).
TYN_FUNC TynMinMaxRay tyn_min_max_ray(float u_begin, float u_end, float depth_begin,
                                      float depth_end, float t_begin, float t_end, vec3 sigma_t) {
  TynMinMaxRay ray;
  float du = u_end - u_begin;
  ray.u_begin = u_begin;
  ray.u_end = u_end;
  ray.depth_begin = depth_begin;
  ray.depth_slope = du > 0.0f ? (depth_end - depth_begin) / du : 0.0f;
  ray.t_begin = t_begin;
  ray.t_slope = du > 0.0f ? (t_end - t_begin) / du : 0.0f;
  ray.sigma_t = sigma_t;
  return ray;
}

// Monotonic in u (each rounding is), which the tree's decisions rely on: a section's depths lie
// between those at its ends.
TYN_FUNC float tyn_min_max_depth_at(TynMinMaxRay ray, float u) {
  return ray.depth_begin + (u - ray.u_begin) * ray.depth_slope;
}

TYN_FUNC float tyn_min_max_distance_at(TynMinMaxRay ray, float u) {
  return ray.t_begin + (u - ray.u_begin) * ray.t_slope;
}

// ∫ e^{−σ_t t} dt over the view distances of u ∈ [a, b]
//   = e^{−σ t_near} · len · (1 − e^{−σ len}) / (σ len),  len = (b − a)·|dt/du|.
// tyn_transmittance_integral's form, but fed the length directly: a difference of two distances
// carries float's absolute error of the whole distance (1.5e-5 at t = 200), which would swamp a
// short lit section (measured: 0.3% on a 4e-4 section at t = 43).
TYN_FUNC vec3 tyn_min_max_directional_integral(TynMinMaxRay ray, float a, float b) {
  float len = max(b - a, 0.0f) * abs(ray.t_slope);
  float t_near = max(tyn_min_max_distance_at(ray, ray.t_slope >= 0.0f ? a : b), 0.0f);
  vec3 x = ray.sigma_t * len;
  vec3 ratio = vec3(tyn_one_minus_exp_over_x(x.x), tyn_one_minus_exp_over_x(x.y),
                    tyn_one_minus_exp_over_x(x.z));
  return exp(-ray.sigma_t * t_near) * len * ratio;
}

// ---- The shadow test on a section [a, b] with depths za = z(a), zb = z(b) ----

// Against a range (min, max) of depths. Lit: every depth ≥ the ray's (or all are clear);
// shadowed: every depth < the ray's and none clear; mixed: neither can be told.
TYN_FUNC int tyn_min_max_classify(float za, float zb, vec2 bounds) {
  if (bounds.x >= 1.0f || max(za, zb) <= bounds.x) return TYN_MIN_MAX_LIT;
  if (bounds.y < 1.0f && min(za, zb) > bounds.y) return TYN_MIN_MAX_SHADOWED;
  return TYN_MIN_MAX_MIXED;
}

// The lit part of [a, b] against one depth d (the leaf rule): vec2(begin, end), empty when
// end ≤ begin. When mixed, z crosses d inside: za ≤ d < zb or zb ≤ d < za, so zb ≠ za.
TYN_FUNC vec2 tyn_min_max_lit_part(float a, float b, float za, float zb, float d) {
  int c = tyn_min_max_classify(za, zb, vec2(d));
  if (c == TYN_MIN_MAX_LIT) return vec2(a, b);
  if (c == TYN_MIN_MAX_SHADOWED) return vec2(b, b);
  float u = a + (b - a) * clamp((d - za) / (zb - za), 0.0f, 1.0f);
  return za <= d ? vec2(a, u) : vec2(u, b);
}

// ---- Lit sections, merged ----
// Both marches hand their lit parts, in order, to one accumulator that merges touching parts and
// integrates each maximal lit interval once: the two marches then integrate the same intervals
// with the same arithmetic, and a fully lit slice costs one closed form instead of L.

struct TynMinMaxLitSpan {
  vec3 integral;  // over the intervals already closed
  float begin;    // the open interval
  float end;
};

TYN_FUNC TynMinMaxLitSpan tyn_min_max_lit_span(float u) {
  TynMinMaxLitSpan span;
  span.integral = vec3(0.0f);
  span.begin = u;
  span.end = u;
  return span;
}

TYN_FUNC void tyn_min_max_add_lit(TYN_INOUT(TynMinMaxLitSpan) span, TynMinMaxRay ray, vec2 part) {
  if (part.y <= part.x) return;
  if (part.x != span.end) {
    if (span.end > span.begin) span.integral += TYN_MIN_MAX_INTEGRATE(ray, span.begin, span.end);
    span.begin = part.x;
  }
  span.end = part.y;
}

TYN_FUNC vec3 tyn_min_max_close(TynMinMaxLitSpan span, TynMinMaxRay ray) {
  return span.end > span.begin ? span.integral + TYN_MIN_MAX_INTEGRATE(ray, span.begin, span.end)
                               : span.integral;
}

// Coloured shafts: with a light-colour texture a long lit section cannot be integrated in one
// step times one colour, the colour varies along it (yusov2013 "Colored Light Shafts" walks lit
// sections at the fine step for that reason). Here lit parts are merged only within a chunk of
// `chunk` cells (a power of two, EpipolarSettings::coloredStep capped by tyn_min_max_colored_chunk)
// and each merged section is integrated on its own, uncoloured (TYN_MIN_MAX_INTEGRATE), times the
// light's mean colour over it (TYN_MIN_MAX_COLOR_MEAN, from light_color_sums.h's prefix sums). The
// mean is exact for the colour; what a longer chunk loses is the covariance of the colour with the
// integrand's own variation inside it (the attenuation, a spot light's fall-off). Both marches
// close sections at the same chunk boundaries and gaps, so they still add the same terms.
TYN_MIN_MAX_TEMPLATE
TYN_FUNC vec3 tyn_min_max_colored_integral(TYN_MIN_MAX_ACCESS TynMinMaxRay ray, float a, float b) {
  return TYN_MIN_MAX_COLOR_MEAN(a, b) * TYN_MIN_MAX_INTEGRATE(ray, a, b);
}

TYN_MIN_MAX_TEMPLATE
TYN_FUNC void tyn_min_max_add_colored(TYN_MIN_MAX_ACCESS TYN_INOUT(TynMinMaxLitSpan) span, TynMinMaxRay ray,
                                      vec2 part, float chunk) {
  if (part.y <= part.x) return;
  // Parts never straddle a chunk boundary (cells and chunks are aligned; u is an integer there).
  if (part.x != span.end || part.x == floor(part.x / chunk) * chunk) {
    if (span.end > span.begin) span.integral += tyn_min_max_colored_integral(TYN_MIN_MAX_PASS ray, span.begin, span.end);
    span.begin = part.x;
  }
  span.end = part.y;
}

TYN_MIN_MAX_TEMPLATE
TYN_FUNC vec3 tyn_min_max_close_colored(TYN_MIN_MAX_ACCESS TynMinMaxLitSpan span, TynMinMaxRay ray) {
  return span.end > span.begin ? span.integral + tyn_min_max_colored_integral(TYN_MIN_MAX_PASS ray, span.begin, span.end)
                               : span.integral;
}

// Most optical depth (σ_t · view distance, the largest channel's) one chunk of a coloured march
// spans: a chunk's relative error is at most (max c − min c) · τ e^τ for a chunk of optical depth τ
// (MinMaxMarch.ColoredChunkErrorWithinItsBound derives it), so in dense fog the chunks shorten
// until the colour's covariance with the attenuation inside one stays within about a tenth.
TYN_CONST float TYN_MIN_MAX_COLORED_OPTICAL_DEPTH = 0.1f;

// The chunk of a coloured march along `ray`: `max_chunk` cells (EpipolarSettings::coloredStep), or
// the largest power of two below it whose optical depth, at the ray's mean dt/du, is at most
// TYN_MIN_MAX_COLORED_OPTICAL_DEPTH (one cell at least). The same for both marches of one ray.
TYN_FUNC int tyn_min_max_colored_chunk(TynMinMaxRay ray, int max_chunk) {
  float tau_per_cell = max(max(ray.sigma_t.x, ray.sigma_t.y), ray.sigma_t.z) * abs(ray.t_slope);
  if (!(tau_per_cell * float(max_chunk) > TYN_MIN_MAX_COLORED_OPTICAL_DEPTH)) return max_chunk;
  float cells = TYN_MIN_MAX_COLORED_OPTICAL_DEPTH / tau_per_cell;  // < max_chunk
  return cells >= 1.0f ? 1 << findMSB(int(cells)) : 1;
}

// The part of the ray the marches cover: [u_begin, u_end] ∩ [0, L] as (a, b), a ≤ b.
TYN_FUNC vec2 tyn_min_max_range(int sample_count, TynMinMaxRay ray) {
  float end = float(sample_count);
  float a = clamp(ray.u_begin, 0.0f, end);
  return vec2(a, clamp(ray.u_end, a, end));
}

// The level a stackless march resumes at after a decided node ending at cell k > 0: the parent at
// level + 1 starts at k when k is a multiple of its span 2^(level+2), so the march climbs while
// that holds, up to `highest`; the highest such level is findLSB(k) − 1. In closed form: no loop
// nested in the march's, and no iterations.
TYN_FUNC int tyn_min_max_climb(int level, int highest, int k) {
  return max(level, min(highest, findLSB(k) - 1));
}

// What a march returns.
struct TynMinMaxMarch {
  vec3 lit_integral;  // Σ over the lit parts of ∫ e^{−σ_t t} dt (or TYN_MIN_MAX_INTEGRATE's)
  int steps;          // cells (plain) or nodes and cells (tree) tested: the cost, for stats
};

#if defined(TYN_MIN_MAX_SAMPLE)
// The plain march: every cell of [u_begin, u_end] ∩ [0, L] against its sample. `colored_chunk`: 0
// without a light-colour texture, else the chunk of tyn_min_max_add_colored.
// tyn_min_max_march_plain over [a, b] ⊆ [0, L] only (one part of a ray several threads share).
TYN_MIN_MAX_TEMPLATE
TYN_FUNC TynMinMaxMarch tyn_min_max_march_plain_range(TYN_MIN_MAX_ACCESS int sample_count, TynMinMaxRay ray,
                                                      int colored_chunk, float a, float b) {
  TynMinMaxLitSpan span = tyn_min_max_lit_span(a);
  TynMinMaxMarch result;
  result.steps = 0;
  for (int k = min(int(floor(a)), sample_count - 1); k < sample_count && float(k) < b; ++k) {
    float ca = max(a, float(k));
    float cb = min(b, float(k + 1));
    if (cb <= ca) continue;
    ++result.steps;
    vec2 part = tyn_min_max_lit_part(ca, cb, tyn_min_max_depth_at(ray, ca), tyn_min_max_depth_at(ray, cb),
                                     TYN_MIN_MAX_SAMPLE(k));
    if (colored_chunk > 0) {
      tyn_min_max_add_colored(TYN_MIN_MAX_PASS span, ray, part, float(colored_chunk));
    } else {
      tyn_min_max_add_lit(span, ray, part);
    }
  }
  result.lit_integral = colored_chunk > 0 ? tyn_min_max_close_colored(TYN_MIN_MAX_PASS span, ray)
                                          : tyn_min_max_close(span, ray);
  return result;
}

TYN_MIN_MAX_TEMPLATE
TYN_FUNC TynMinMaxMarch tyn_min_max_march_plain(TYN_MIN_MAX_ACCESS int sample_count, TynMinMaxRay ray,
                                                int colored_chunk) {
  vec2 range = tyn_min_max_range(sample_count, ray);
  return tyn_min_max_march_plain_range(TYN_MIN_MAX_PASS sample_count, ray, colored_chunk, range.x, range.y);
}
#endif

#if defined(TYN_MIN_MAX_SAMPLE) && defined(TYN_MIN_MAX_FETCH)
// The accelerated march, stackless. State: the current position u, its cell k and a level
// (−1 = single cells, resolved by the leaf rule exactly as the plain march does). Each iteration
// tests the section [u, min(node end, u_end)] of the level's node containing k: a decided node
// is integrated or skipped and u moves to its end, then the level climbs while the node after it
// starts its parent; a mixed node descends one level (to the child containing k). The march
// starts at `top_level` (−1: no tree, the plain march; levels above the tree's are clamped), so
// no step exceeds 2^(top_level+1) samples: yusov2013's maximum step.
// Every node is tested at most once and the tree has < 2L nodes, which bounds the loop.
// `colored_chunk` (tyn_min_max_add_colored; 0: no light-colour texture): a lit node larger than a
// chunk is walked chunk by chunk (at most L more iterations); only shadowed nodes are skipped whole.
// Over [a, b] ⊆ [0, L] only: one part of a ray several threads share (march.comp); the parts'
// sections end at the part boundaries, so their sum differs from one march by rounding alone.
TYN_MIN_MAX_TEMPLATE
TYN_FUNC TynMinMaxMarch tyn_min_max_march_tree_range(TYN_MIN_MAX_ACCESS int sample_count, int top_level,
                                                     TynMinMaxRay ray, int colored_chunk, float a, float b) {
  int highest = min(top_level, tyn_min_max_highest_level(sample_count));
  bool colored = colored_chunk > 0;
  int colored_level = colored ? findMSB(colored_chunk) - 1 : -1;  // the level whose nodes are chunks
  TynMinMaxLitSpan span = tyn_min_max_lit_span(a);
  TynMinMaxMarch result;
  result.steps = 0;

  float u = a;
  int k = min(int(floor(a)), sample_count - 1);
  int level = highest;
  // Coloured marches walk the chunks of a lit node one per iteration: chunks before lit_until are
  // known to be lit whole (the node's minimum bounds their samples). One loop without `continue`
  // or an inner cell loop, and one call site of the integral after the branches: lavapipe's JIT
  // miscompiled the other forms of this march (its coloured spot-light results differed from the
  // plain march's, by 1.7% relative RMSE on stained-glass with High's settings and by 140% with
  // max-tree-step=2, while the same march compiled as C++ agrees at every maximum step). Most
  // likely lavapipe's loop budget rather than a miscompile (docs/REFERENCE.md "Loop budget on
  // lavapipe"): each call site's quadrature loops cost budget at every step, taken or not.
  int lit_until = -1;
  int max_iterations = 3 * sample_count + highest + 2;
  for (int i = 0; i < max_iterations && u < b; ++i) {
    int span_log2 = level + 1;
    int node = k >> span_log2;
    int node_end = (node + 1) << span_log2;
    float sb = min(b, float(node_end));
    float za = tyn_min_max_depth_at(ray, u);
    float zb = tyn_min_max_depth_at(ray, sb);
    ++result.steps;
    bool advance = true;
    vec2 part = vec2(u);  // empty: a skipped or descended node adds nothing
    if (k < lit_until) {
      part = vec2(u, sb);  // a chunk (or cell) of a lit node being walked
    } else if (level < 0) {
      part = tyn_min_max_lit_part(u, sb, za, zb, TYN_MIN_MAX_SAMPLE(k));
    } else {
      int c = tyn_min_max_classify(za, zb, TYN_MIN_MAX_FETCH(level, node));
      if (c == TYN_MIN_MAX_MIXED) {
        --level;
        advance = false;
      } else if (c == TYN_MIN_MAX_LIT && colored && level > colored_level) {
        lit_until = node_end;
        level = colored_level;
        advance = false;
      } else if (c == TYN_MIN_MAX_LIT) {
        part = vec2(u, sb);
      }
    }
    // One call site for the integral, after the branches (see above).
    if (colored) {
      tyn_min_max_add_colored(TYN_MIN_MAX_PASS span, ray, part, float(colored_chunk));
    } else {
      tyn_min_max_add_lit(span, ray, part);
    }
    if (advance) {
      u = sb;
      k = node_end;
      // Not inside a lit node whose chunks are being walked.
      if (k >= lit_until) level = tyn_min_max_climb(level, highest, k);
    }
  }
  result.lit_integral = colored ? tyn_min_max_close_colored(TYN_MIN_MAX_PASS span, ray) : tyn_min_max_close(span, ray);
  return result;
}

TYN_MIN_MAX_TEMPLATE
TYN_FUNC TynMinMaxMarch tyn_min_max_march_tree(TYN_MIN_MAX_ACCESS int sample_count, int top_level,
                                               TynMinMaxRay ray, int colored_chunk) {
  vec2 range = tyn_min_max_range(sample_count, ray);
  return tyn_min_max_march_tree_range(TYN_MIN_MAX_PASS sample_count, top_level, ray, colored_chunk, range.x, range.y);
}
#endif

#if defined(TYN_MIN_MAX_FETCH)
// ---- Whole-ray shadow test (a light that reaches no visible point: DESIGN.md "Model only what
// the scene requires") ----

// True when the tree shows every point of the ray's part [u_begin, u_end] ∩ [0, L] in shadow, so
// that both marches above would return a zero lit integral, to the bit; decided without
// integrating and stopping at the first node that is not shadowed. Why exact: it walks the tree
// march's own sequence of sections (same start level, same descent on a mixed node, same climb
// after a decided one, same tyn_min_max_depth_at at the same section ends), and says true only
// when every section it met was classified shadowed, which the tree march would then skip; the
// plain march agrees with the tree march. A mixed level-0 node stops it (false) instead of
// reading cells: conservative, and it needs no TYN_MIN_MAX_SAMPLE. An empty part is shadowed:
// nothing is marched. What a caller adds outside the map (a directional light's unshadowed parts)
// is the caller's to test. A single box bound over the whole part would not do: a tilted occluder's
// depth range over a long part exceeds the occluder's thickness, where this walk descends.
TYN_MIN_MAX_TEMPLATE
TYN_FUNC bool tyn_min_max_ray_shadowed(TYN_MIN_MAX_ACCESS int sample_count, int top_level, TynMinMaxRay ray) {
  vec2 range = tyn_min_max_range(sample_count, ray);
  float a = range.x;
  float b = range.y;
  int highest = min(top_level, tyn_min_max_highest_level(sample_count));
  if (highest < 0) return b <= a;  // no tree to decide with

  float u = a;
  int k = min(int(floor(a)), sample_count - 1);
  int level = highest;
  int max_iterations = 3 * sample_count + highest + 2;
  for (int i = 0; i < max_iterations && u < b; ++i) {
    int span_log2 = level + 1;
    int node = k >> span_log2;
    int node_end = (node + 1) << span_log2;
    float sb = min(b, float(node_end));
    int c = tyn_min_max_classify(tyn_min_max_depth_at(ray, u), tyn_min_max_depth_at(ray, sb),
                                 TYN_MIN_MAX_FETCH(level, node));
    if (c == TYN_MIN_MAX_LIT || (c == TYN_MIN_MAX_MIXED && level == 0)) return false;
    if (c == TYN_MIN_MAX_MIXED) {
      --level;
    } else {
      u = sb;
      k = node_end;
      level = tyn_min_max_climb(level, highest, k);
    }
  }
  return u >= b;
}
#endif

TYN_END

#ifdef __cplusplus
#undef TYN_MIN_MAX_SHADOW_TEXEL
#undef TYN_MIN_MAX_SAMPLE
#undef TYN_MIN_MAX_FETCH
#undef TYN_MIN_MAX_COLOR_MEAN
#endif
#undef TYN_MIN_MAX_TEMPLATE
#undef TYN_MIN_MAX_ACCESS
#undef TYN_MIN_MAX_PASS

#endif
