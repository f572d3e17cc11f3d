#version 460
// Ray marching of the epipolar samples the refinement chose (yusov2013 "1D min/max binary
// trees"). Every view ray of a slice projects onto the slice's line in the shadow map, so the
// march runs along that line in its 1D parameter u: with the tree, fully lit sections are
// integrated in one step, fully shadowed ones skipped and mixed ones descended; without it, every
// cell is tested (the same lit set: the tree is exact). Lit sections of a directional light are
// integrated in closed form; a spot light's from yusov2013's semi-analytic table. With a
// light-colour texture lit sections are cut into chunks of EpipolarSettings::coloredStep cells
// (min_max_tree.h, tyn_min_max_add_colored), each integrated uncoloured times the light's mean
// colour over it from the slice's prefix sums (light_color_sums.h; yusov2013 "Colored Light
// Shafts" walks them at the fine step instead). A directional light's cascades cut the view ray
// into stretches by view depth (tyn_cascade_stretch), and each stretch is marched along its
// cascade's line and tree (yusov2013's cascaded version). Point lights (six maps, no single line)
// and slices without a line in a map use the Reference's texel walk, with its lit sections
// integrated from the same table (TYN_WALK_LIT_SECTIONS); a point light's walk crosses its maps
// block by block where a block decides all its texels (block_walk.glsl).
#extension GL_GOOGLE_include_directive : require
#include "epipolar/epipolar_common.glsl"
#define TYN_WALK_LIT_SECTIONS
#define TYN_WALK_SHADOW_BLOCKS
#include "epipolar/block_walk.glsl"

// A walked light's frame (point) builds its maps' blocks before the march
// (EpipolarTechnique::record); a directional light's are built after it, for the fix-up, if at all.
bool tyn_shadow_blocks_built() { return tyn_epipolar_walks_maps() && epipolar.shadow_block_side != 0u; }

// Specialised per light-colour texture: with one, lit sections are integrated chunk by chunk.
layout(constant_id = 1) const bool TYN_MARCH_LIGHT_COLOR = false;
// Threads that share one sample's ray (a power of two dividing TYN_EPIPOLAR_MARCH_GROUP), each
// marching an equal part of it, summed in shared memory. The marched samples are a few tens of
// thousands: one thread each leaves a GPU waiting on the longest rays (coloured and spot-light
// marches); a CPU driver runs best with one (ContextDesc::marchThreadsPerSample).
layout(constant_id = 2) const uint TYN_MARCH_PARTS = 1u;

// The slice, the map and the view ray being marched, for the accessors of min_max_tree.h below.
int g_slice;
uint g_map;
int g_tree_row;  // tyn_epipolar_tree_row(g_slice, g_map)
vec2 g_origin_texels;
vec2 g_step_texels;
// u = (a0 + a1 t) / (p + q t) (slice_ray.glsl); its inverse gives a spot light's lit section
// back in t.
vec4 g_u_of_t;  // (a0, a1, p, q)

#define TYN_SCATTERING_LUT_FETCH(texel) imageLoad(scattering_lut, texel).rgb
#define TYN_SCATTERING_LUT_FRAME
#include "epipolar/scattering_lut.h"

// A spot light's medium, ray and cone for the table, and the ray and its kinks for the coloured
// quadrature (hoisted out of the march).
TynMedium g_medium;
TynLightRay g_light_ray;
TynSpotCone g_cone;
TynSpotRay g_spot_ray;
TynLocalLightRay g_local_ray;
vec4 g_cuts;

float tyn_march_t_of_u(float u) {
  return (g_u_of_t.x - u * g_u_of_t.z) / (u * g_u_of_t.w - g_u_of_t.y);
}

// A spot light's lit section: from the semi-analytic table (inside the inner cone) and quadrature
// (in the penumbra), yusov2013. A coloured light's chunks take the quadrature alone, uncoloured
// (g_local_ray), which costs a fraction of the table's lookups on a chunk of a few tens of cells
// (tyn_local_light_piece's `pairwise` says why pairwise; docs/EPIPOLAR.md "Coloured shafts").
vec3 tyn_march_local_light(float u_a, float u_b) {
  float t_a = tyn_march_t_of_u(u_a);
  float t_b = tyn_march_t_of_u(u_b);
  float a = max(min(t_a, t_b), 0.0);
  float b = max(t_a, t_b);
  if (TYN_MARCH_LIGHT_COLOR) return tyn_local_light_segment_cut(g_local_ray, g_cuts, a, b, true);
  return frame.light_radiance * tyn_spot_ray_segment(g_medium, g_light_ray, g_cone, g_spot_ray, a, b);
}

// The light's mean colour over [a, b] of the slice's line, from the slice's prefix sums.
#define TYN_COLOR_SUM(k) imageLoad(light_color_sums, tyn_color_sums_texel(int(epipolar.tree_samples), g_slice, k)).rgb
#include "epipolar/light_color_sums.h"

#define TYN_MIN_MAX_SHADOW_TEXEL(texel) tyn_epipolar_shadow_texel(g_map, texel)
#define TYN_MIN_MAX_COLOR_MEAN(a, b) tyn_color_sums_mean(int(epipolar.tree_samples), a, b)
#define TYN_MIN_MAX_SAMPLE(k) tyn_min_max_cell_sample(g_origin_texels, g_step_texels, k)
#define TYN_MIN_MAX_FETCH(level, index) \
  imageLoad(min_max_tree, ivec2(tyn_min_max_level_offset(int(epipolar.tree_samples), level) + (index), g_tree_row)).xy
// The pipeline is specialised per light type (TYN_LIGHT_TYPE, common/medium.glsl), so that the
// compiler drops the other integral: a run-time choice here costs the directional march several
// times its time on a CPU driver, whose vectorised code evaluates both sides of the branch.

#define TYN_MIN_MAX_INTEGRATE(ray, a, b) \
  (TYN_LIGHT_TYPE != TYN_LIGHT_DIRECTIONAL ? tyn_march_local_light(a, b) : tyn_min_max_directional_integral(ray, a, b))
#include "epipolar/min_max_tree.h"
#include "epipolar/slice_ray.glsl"

layout(local_size_x = TYN_EPIPOLAR_MARCH_GROUP) in;

// Part `part` of TYN_MARCH_PARTS of the lit part along the stretch [t0, t1] of the view ray that sr
// describes (slice_ray.glsl) in map `map`, marched along the slice's line there: the march's u
// range is cut into equal parts. A directional light's: its transmittance integral, part 0 adding
// the stretch's unshadowed ends outside the map; a spot light's: its L_in.
vec3 tyn_march_along_slice(int slice, uint map, TynSliceRay sr, vec3 origin, vec3 dir, float t0, float t1, uint part) {
  g_slice = slice;
  g_map = map;
  g_tree_row = tyn_epipolar_tree_row(slice, map);
  g_origin_texels = sr.origin_texels;
  g_step_texels = sr.step_texels;
  g_u_of_t = sr.u_of_t;
  if (TYN_LIGHT_TYPE == TYN_LIGHT_SPOT) {
    g_medium = tyn_medium_from_frame();
    g_light_ray = tyn_light_ray(origin, dir, frame.light_position);
    g_cone = tyn_spot_cone_from_frame(g_light_ray, dir);
    g_spot_ray = tyn_spot_ray(g_light_ray, g_cone);
  }
  if (TYN_MARCH_LIGHT_COLOR && TYN_LIGHT_TYPE != TYN_LIGHT_DIRECTIONAL) {
    g_local_ray = tyn_local_light_ray(origin, dir);
    g_local_ray.colored = false;  // the chunk's mean colour multiplies the quadrature
    g_cuts = tyn_local_light_cuts(origin, dir);
  }
  bool directional = TYN_LIGHT_TYPE == TYN_LIGHT_DIRECTIONAL;
  vec3 unshadowed = vec3(0.0);
  if (directional && part == 0u) {
    unshadowed = sr.inside ? tyn_transmittance_integral(t0, sr.t_in, frame.extinction) +
                                 tyn_transmittance_integral(sr.t_out, t1, frame.extinction)
                           : tyn_transmittance_integral(t0, t1, frame.extinction);
  }
  vec3 lit = vec3(0.0);
  if (sr.inside) {
    int sample_count = int(epipolar.tree_samples);
    vec2 range = tyn_min_max_range(sample_count, sr.ray);
    // tyn_part_begin/end (common/texel_walk.glsl): one part is exactly the whole range.
    float part_a = tyn_part_begin(range.x, range.y, part, TYN_MARCH_PARTS);
    float part_b = tyn_part_end(range.x, range.y, part, TYN_MARCH_PARTS);
    // coloredStep, capped by the ray's optical depth.
    int colored_chunk = TYN_MARCH_LIGHT_COLOR ? tyn_min_max_colored_chunk(sr.ray, int(epipolar.colored_chunk)) : 0;
    TynMinMaxMarch march =
        epipolar.tree_enabled != 0u
            ? tyn_min_max_march_tree_range(sample_count, int(epipolar.tree_top_level), sr.ray, colored_chunk, part_a, part_b)
            : tyn_min_max_march_plain_range(sample_count, sr.ray, colored_chunk, part_a, part_b);
    lit = march.lit_integral;
  }
  return directional ? unshadowed + lit : lit;
}

// A stretch's lit part (as tyn_march_along_slice) along the slice's line in map `map` where the
// slice has one and the ray is not (nearly) along the light; the Reference's walk of the stretch
// otherwise (slice_ray.glsl, tyn_slice_ray_degenerate).
vec3 tyn_march_directional_stretch(int slice, uint map, vec3 origin, vec3 dir, vec2 stretch, uint part) {
  vec4 origin_direction = imageLoad(slice_uv, ivec2(slice, map));
  if (tyn_slice_valid(origin_direction)) {
    TynSliceRay sr = tyn_slice_ray(map, origin_direction, origin, dir, stretch.x, stretch.y);
    if (!tyn_slice_ray_degenerate(sr)) return tyn_march_along_slice(slice, map, sr, origin, dir, stretch.x, stretch.y, part);
  }
  return tyn_walk_directional_stretch(map, origin, dir, stretch, part, TYN_MARCH_PARTS);
}

// This thread's part of the entry's L_in.
vec3 tyn_march_entry(uvec2 id, uint part) {
  vec4 coordinates = imageLoad(epipolar_coordinates, ivec2(id));
  if (coordinates.w <= 0.5) return vec3(0.0);
  vec3 origin = frame.view_to_world[3].xyz;
  vec3 dir = tyn_view_direction(vec2(coordinates.x, coordinates.y));
  float s = coordinates.z;
  // A light whose maps are walked (no slice line): the Reference's texel walk.
  if (tyn_epipolar_walks_maps()) return tyn_reference_in_scattering_part(origin, dir, s, part, TYN_MARCH_PARTS);
  int slice = int(id.y);
  if (TYN_LIGHT_TYPE == TYN_LIGHT_DIRECTIONAL) {
    // Each cascade's stretch of the ray along that cascade's line (one map: the whole ray).
    vec3 lit = vec3(0.0);
    for (uint map = 0u; map < frame.shadow_map_count; ++map) {
      vec2 stretch = tyn_cascade_stretch(map, origin, dir, s);
      if (stretch.y > stretch.x) lit += tyn_march_directional_stretch(slice, map, origin, dir, stretch, part);
    }
    float cos_theta = dot(dir, -frame.light_direction);
    return frame.light_radiance * tyn_phase_weighted_scattering(cos_theta) * lit;
  }
  // A spot light: one map. Slices without a line in it and rays along the light take the
  // Reference's texel walk.
  vec4 origin_direction = imageLoad(slice_uv, ivec2(slice, 0));
  if (tyn_slice_valid(origin_direction)) {
    TynSliceRay sr = tyn_slice_ray(0u, origin_direction, origin, dir, 0.0, s);
    if (!tyn_slice_ray_degenerate(sr)) return tyn_march_along_slice(slice, 0u, sr, origin, dir, 0.0, s, part);
  }
  return tyn_reference_in_scattering_part(origin, dir, s, part, TYN_MARCH_PARTS);
}

shared vec3 g_parts[TYN_EPIPOLAR_MARCH_GROUP];

void main() {
  // TYN_MARCH_PARTS threads per entry of this round of the march list; the other samples are
  // interpolated by the unwarp. The round's groups are capped at the dispatch limit
  // (dispatch_chain.glsl), so groups stride
  // over the round (a loop whose trip count is the workgroup's, as the barriers need).
  uint per_group = TYN_EPIPOLAR_MARCH_GROUP / TYN_MARCH_PARTS;
  uint lane = gl_LocalInvocationID.x / TYN_MARCH_PARTS;
  uint part = gl_LocalInvocationID.x % TYN_MARCH_PARTS;
  for (uint first = march_first + gl_WorkGroupID.x * per_group; first < march_round_end;
       first += gl_NumWorkGroups.x * per_group) {
    uint entry = first + lane;
    bool listed = entry < march_round_end;
    uvec2 id = uvec2(0u);
    vec3 in_scattering = vec3(0.0);
    if (listed) {
      uint packed = march_samples[entry];
      id = uvec2(packed & 0xffffu, packed >> 16);  // x: sample, y: slice
      in_scattering = tyn_march_entry(id, part);
    }
    if (TYN_MARCH_PARTS > 1u) {
      g_parts[gl_LocalInvocationID.x] = in_scattering;
      barrier();
      if (part == 0u) {
        for (uint k = 1u; k < TYN_MARCH_PARTS; ++k) in_scattering += g_parts[gl_LocalInvocationID.x + k];
      }
      barrier();
    }
    if (listed && part == 0u) imageStore(epipolar_scattering, ivec2(id), vec4(in_scattering, 0.0));
  }
}
