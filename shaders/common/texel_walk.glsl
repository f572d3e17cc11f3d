// The texel walk, the brute-force in-scattering integral (yusov2013's "starting point") that the
// Reference runs per pixel and the other techniques run where they fall back to brute force: the
// view ray is walked through the shadow map texel by texel. Within one texel the stored depth is
// constant and the ray's shadow-clip coordinates are linear in t (homogeneously), so the lit part
// of each texel segment is found exactly by solving one linear inequality. Lit parts are integrated
// in closed form for a directional light and by Gauss–Legendre quadrature for spot and point lights.
// Needs `frame` (FrameConstants), `shadow_maps[]` (sampler2D array) and `light_color` (sampler2D)
// in scope.
//
// Hooks. A technique changes the walk by defining any of these before including this file, and then
// defines the functions that go with it (declared below, so the walk can call them):
//   TYN_WALK_LIT_SECTIONS   vec3 tyn_point_light_lut_segment(vec3 origin, vec3 view_dir, float a, float b)
//                           integrates a point light's merged lit section [a, b] in one call.
//   TYN_WALK_SHADOW_BLOCKS  bool tyn_shadow_blocks_built() says whether this frame has block ranges;
//                           vec3 tyn_walk_shadow_blocks(map, origin, dir, t0, t1, directional) walks a
//                           map block by block where they are.
//   TYN_WALK_IN_STEPS       uint tyn_walk_steps() is the number of steps per map (0: the texel walk);
//                           vec3 tyn_step_shadow_map(map, origin, dir, t0, t1, part, parts, directional)
//                           marches in that many steps instead.
//   TYN_WALK_TRANSLUCENT    the lit parts are attenuated by the frame's translucent layers
//                           (common/translucent_layers.glsl, included before this file).
// With none defined the walk is the Reference's. The epipolar fix-up and march define them
// (epipolar/fixup.comp, epipolar/march.comp).
#ifndef TYNDALL_TEXEL_WALK_GLSL
#define TYNDALL_TEXEL_WALK_GLSL

#include "common/light_color.glsl"
#include "common/medium.glsl"
#include "common/segment_integral.h"
#include "common/shadow_ray.glsl"

const float TYN_INFINITY = 3.0e38;

// t at which the ray crosses the texel edge at NDC coordinate `edge` along one axis:
// (h0 + t h1) / (h0w + t h1w) = edge, in front of the map's projection (w > 0). In a perspective
// map the projected coordinate approaches the ray's vanishing point as t grows and never passes
// it: an edge beyond it solves the equation only on the other branch of the hyperbola, behind the
// light's plane (w < 0), which is no crossing (infinite, as along an axis without motion). Taken as
// one, it would be a crossing already passed, and the walk would skip the rest of the map.
float tyn_edge_crossing(float h0, float h1, float h0w, float h1w, float edge) {
  float denom = h1 - edge * h1w;
  if (denom == 0.0) return TYN_INFINITY;
  float t = (edge * h0w - h0) / denom;
  return h0w + t * h1w > 0.0 ? t : TYN_INFINITY;
}

// Direction (−1, 0, +1) in which the texel index moves along one axis as t grows. The projected
// coordinate is a linear-fractional function of t, monotonic wherever w > 0; a derivative
// numerator within rounding noise of zero means no motion.
int tyn_texel_step(float h0, float h1, float h0w, float h1w) {
  float numer = h1 * h0w - h0 * h1w;
  float noise = 1e-6 * (abs(h1 * h0w) + abs(h0 * h1w));
  return abs(numer) <= noise ? 0 : (numer > 0.0 ? 1 : -1);
}

// The texel (unclamped) of a map n texels wide that holds the shadow-clip point h.
ivec2 tyn_clip_texel(vec4 h, float n) { return ivec2(floor((h.xy / h.w * 0.5 + 0.5) * n)); }

// Where a walk of map `size`² from t0 starts: the texel holding the ray's point (clamped to the
// map), and the direction its texel index moves in along x and y.
void tyn_walk_start(TynShadowRay r, float t0, int size, out ivec2 texel, out ivec2 step_dir) {
  texel = clamp(tyn_clip_texel(r.h0 + t0 * r.h1, float(size)), ivec2(0), ivec2(size - 1));
  step_dir = ivec2(tyn_texel_step(r.h0.x, r.h1.x, r.h0.w, r.h1.w), tyn_texel_step(r.h0.y, r.h1.y, r.h0.w, r.h1.w));
}

// t at which the ray crosses the texel edge `edges.x` (a column of edges, in texels of a map
// n texels wide) and `edges.y` (a row); infinite along an axis it does not move along.
vec2 tyn_edge_crossings(TynShadowRay r, ivec2 step_dir, ivec2 edges, float n) {
  return vec2(step_dir.x == 0 ? TYN_INFINITY
                              : tyn_edge_crossing(r.h0.x, r.h1.x, r.h0.w, r.h1.w, float(edges.x) / n * 2.0 - 1.0),
              step_dir.y == 0 ? TYN_INFINITY
                              : tyn_edge_crossing(r.h0.y, r.h1.y, r.h0.w, r.h1.w, float(edges.y) / n * 2.0 - 1.0));
}

// Whether `texel` lies in a map of `size`² texels.
bool tyn_texel_in_map(ivec2 texel, int size) {
  return all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, ivec2(size)));
}

// Steps to the next texel across the edge crossed first (`crossing` from tyn_edge_crossings);
// false once the walk has left the map.
bool tyn_next_texel(inout ivec2 texel, ivec2 step_dir, vec2 crossing, int size) {
  if (crossing.x <= crossing.y) {
    texel.x += step_dir.x;
  } else {
    texel.y += step_dir.y;
  }
  return tyn_texel_in_map(texel, size);
}

// The lit part [x, y] of the texel segment [t, t_next] of ray `r` in a texel of depth z_texel (empty
// when y ≤ x): lit where z(t) ≤ z_texel · w(t), i.e. A t ≤ B. A texel at the clear value (1) has no
// occluder: everything in it is lit, also beyond the map's far plane.
vec2 tyn_texel_lit_part(TynShadowRay r, float z_texel, float t, float t_next) {
  vec2 lit = vec2(t, t_next);
  if (z_texel < 1.0) {
    float A = r.h1.z - z_texel * r.h1.w;
    float B = z_texel * r.h0.w - r.h0.z;
    if (A > 0.0) {
      lit.y = min(lit.y, B / A);
    } else if (A < 0.0) {
      lit.x = max(lit.x, B / A);
    } else if (B < 0.0) {
      lit.y = lit.x;
    }
  }
  return lit;
}

#ifdef TYN_WALK_IN_STEPS
// Hook: a march in tyn_walk_steps() steps per map instead of the texel walk (0: the texel walk).
uint tyn_walk_steps();
vec3 tyn_step_shadow_map(uint map, vec3 origin, vec3 dir, float t0, float t1, uint part, uint parts, bool directional);
#endif

#ifdef TYN_WALK_LIT_SECTIONS
// Hook: a point light's lit parts that follow on from one another are merged into lit sections,
// each integrated in one call (the epipolar passes use yusov2013's semi-analytic table: two lookups
// instead of a quadrature per lit texel). Not with a light-colour texture, whose colour varies
// along a section (the quadrature takes it at every node), nor for a spot light, whose penumbra
// quadrature per section costs a CPU driver more than it saves. The Reference keeps the per-part
// quadrature: it is the brute force the table is checked against.
vec3 tyn_point_light_lut_segment(vec3 origin, vec3 view_dir, float a, float b);
#endif

// Whether the walk merges a point light's lit parts into sections (TYN_WALK_LIT_SECTIONS above).
bool tyn_walk_merges_sections(bool directional) {
#ifdef TYN_WALK_LIT_SECTIONS
  return !directional && TYN_LIGHT_TYPE == TYN_LIGHT_POINT && !tyn_has_light_color();
#else
  return false;
#endif
}

// Adds the lit part [a, b] (b > a) of a walk's ray: a directional light's Σ ∫ e^{−σ_t t} dt, its
// light colour taken at the part's middle (the fine step); a local light's in-scattered radiance
// by quadrature (which takes the colour at every node), or, where the walk merges sections, into
// the lit section being merged (`section`: [x, y), empty while y ≤ x): a part that begins where the
// section ends extends it (t is carried from one texel, or block, to the next exactly); any other
// closes it, integrated from the table, and starts the next.
void tyn_walk_add_lit_part(inout vec3 sum, inout vec2 section, bool directional, bool sections,
                           TynLocalLightRay local_ray, vec3 origin, vec3 dir, float a, float b) {
  if (directional) {
    sum += tyn_light_color_at(origin + dir * (0.5 * (a + b))) * tyn_transmittance_integral(a, b, frame.extinction);
  }
#ifdef TYN_WALK_LIT_SECTIONS
  else if (sections) {
    if (a != section.y) {
      if (section.y > section.x) sum += tyn_point_light_lut_segment(origin, dir, section.x, section.y);
      section.x = a;
    }
    section.y = b;
  }
#endif
  else {
    sum += tyn_local_light_piece(local_ray, a, b, false);
  }
}

#ifdef TYN_WALK_TRANSLUCENT
// The part [a, b] of [x, y] behind a surface at depth z_layer (empty when b ≤ a): where the texel's
// lit part (tyn_texel_lit_part, a half-line cut to [x, y]) is not.
vec2 tyn_texel_behind_part(TynShadowRay r, float z_layer, float x, float y) {
  vec2 lit = tyn_texel_lit_part(r, z_layer, x, y);
  if (lit.y <= lit.x) return vec2(x, y);
  return lit.x > x ? vec2(x, lit.x) : vec2(lit.y, y);
}

// A lit part's integral (tyn_walk_add_lit_part's, without sections).
vec3 tyn_walk_piece(bool directional, TynLocalLightRay local_ray, vec3 origin, vec3 dir, float a, float b) {
  if (directional) {
    return tyn_light_color_at(origin + dir * (0.5 * (a + b))) * tyn_transmittance_integral(a, b, frame.extinction);
  }
  return tyn_local_light_piece(local_ray, a, b, false);
}

// Adds the lit part [a, b] of texel `texel` of map `map` through its translucent layers, exactly.
// The light reaching t keeps T(t) = Π (1 − α_k) over the layers t lies behind. Peeled layers are
// sorted by depth, and the ray's depth is monotonic in t within a texel, so the sets "behind layer
// k" are nested: T = P_n where n layers are behind, P_n = Π_{k<n} (1 − α_k), and since
// P_{k+1} − P_k = −α_k P_k,  ∫ T g = ∫ g − Σ_k α_k P_k ∫_{behind k} g.
// The loop stops at the texel's first empty layer (layers are packed), so a texel without any
// costs one iteration: a CPU driver runs both sides of every branch, masked, but leaves a loop as
// soon as no lane goes on (docs/REFERENCE.md "Loop budget on lavapipe").
void tyn_walk_add_translucent_part(inout vec3 sum, uint map, ivec2 texel, TynShadowRay r, bool directional,
                                   TynLocalLightRay local_ray, vec3 origin, vec3 dir, float a, float b) {
  vec3 part = tyn_walk_piece(directional, local_ray, origin, dir, a, b);
  float kept = 1.0;  // P_k
  for (uint k = 0u; k <= frame.translucent_layer_count; ++k) {
    vec2 layer = tyn_translucent_layer(map, texel, k);
    if (layer.x >= 1.0) break;
    vec2 behind = tyn_texel_behind_part(r, layer.x, a, b);
    if (behind.y > behind.x) {
      // The layer after the count is the overflow layer: only tested.
      if (k == frame.translucent_layer_count) {
        tyn_translucent_overflowed = true;
      } else {
        part -= (layer.y * kept) * tyn_walk_piece(directional, local_ray, origin, dir, behind.x, behind.y);
      }
    }
    kept *= 1.0 - layer.y;
  }
  sum += max(part, vec3(0.0));  // rounding only: the exact value is ≥ 0
}
#endif

// Closes a walk's last lit section (tyn_walk_add_lit_part).
void tyn_walk_close_section(inout vec3 sum, vec2 section, bool sections, vec3 origin, vec3 dir) {
#ifdef TYN_WALK_LIT_SECTIONS
  if (sections && section.y > section.x) sum += tyn_point_light_lut_segment(origin, dir, section.x, section.y);
#endif
}

#ifdef TYN_WALK_SHADOW_BLOCKS
// Hook: a walk that crosses a block of texels in one step where the block's depth range decides
// them all, used where tyn_shadow_blocks_built() says the frame has the blocks.
vec3 tyn_walk_shadow_blocks(uint map, vec3 origin, vec3 dir, float t0, float t1, bool directional);
bool tyn_shadow_blocks_built();
#endif

// The walk's loop. `translucent` is a constant at each call site, so the compiler builds two
// loops: the one without translucent layers holds none of their code, which lavapipe would
// otherwise run (masked) at every step and count against its loop budget.
vec3 tyn_walk_shadow_map_loop(uint map, vec3 origin, vec3 dir, float t0, float t1, bool directional,
                              const bool translucent) {
  bool sections = tyn_walk_merges_sections(directional);
  vec2 section = vec2(t0);  // the lit section being merged (tyn_walk_add_lit_part)
  TynShadowRay r = tyn_shadow_ray(map, origin, dir);
  TynLocalLightRay local_ray = tyn_local_light_ray(origin, dir);
  int size = int(frame.shadow_map_size);
  float n = float(size);

  ivec2 texel;
  ivec2 step_dir;
  tyn_walk_start(r, t0, size, texel, step_dir);

  vec3 sum = vec3(0.0);
  float t = t0;
  // Every step crosses one texel edge, so 2·size steps cross the whole map; the margin covers
  // rounding at the start. No loop inside the step: on lavapipe every iteration of every loop of
  // an invocation counts against one budget (docs/REFERENCE.md "Loop budget on lavapipe").
  int max_steps = 2 * size + 8;
  for (int i = 0; i < max_steps && t < t1; ++i) {
    vec2 crossing = tyn_edge_crossings(r, step_dir, texel + max(step_dir, ivec2(0)), n);
    float t_next = clamp(min(crossing.x, crossing.y), t, t1);

    if (t_next > t) {
      vec2 lit = tyn_texel_lit_part(r, tyn_shadow_texel(map, texel), t, t_next);
      if (lit.y > lit.x) {
#ifdef TYN_WALK_TRANSLUCENT
        if (translucent) {
          tyn_walk_add_translucent_part(sum, map, texel, r, directional, local_ray, origin, dir, lit.x, lit.y);
        } else
#endif
        {
          tyn_walk_add_lit_part(sum, section, directional, sections, local_ray, origin, dir, lit.x, lit.y);
        }
      }
    }
    t = t_next;
    if (!tyn_next_texel(texel, step_dir, crossing, size)) break;
  }
  tyn_walk_close_section(sum, section, sections, origin, dir);
  return sum;
}

// Walks [t0, t1] (already inside the map) texel by texel. A directional light returns
// Σ_lit ∫ e^{−σ_t t} dt; a spot or point light returns the in-scattered radiance of the lit parts.
vec3 tyn_walk_shadow_map(uint map, vec3 origin, vec3 dir, float t0, float t1, bool directional) {
#ifdef TYN_WALK_TRANSLUCENT
  if (frame.translucent_layer_count != 0u) return tyn_walk_shadow_map_loop(map, origin, dir, t0, t1, directional, true);
#endif
  return tyn_walk_shadow_map_loop(map, origin, dir, t0, t1, directional, false);
}

// Ends of part `part` of `parts` equal lengths of [t0, t1]; the first part begins exactly at t0 and
// the last ends exactly at t1, so that one part is the whole stretch.
float tyn_part_begin(float t0, float t1, uint part, uint parts) {
  return part == 0u ? t0 : t0 + (t1 - t0) * (float(part) / float(parts));
}
float tyn_part_end(float t0, float t1, uint part, uint parts) {
  return part + 1u == parts ? t1 : t0 + (t1 - t0) * (float(part + 1u) / float(parts));
}

// Part `part` of `parts` of a directional light's transmittance integral (L_in before the light's
// radiance and the phase) along the stretch [stretch.x, stretch.y] of the view ray that map `map`
// serves (tyn_cascade_stretch): walked inside the map's square, lit outside it, where there is no
// occluder information. The epipolar march walks so the stretches it cannot march along a line.
vec3 tyn_walk_directional_stretch(uint map, vec3 origin, vec3 dir, vec2 stretch, uint part, uint parts) {
  vec3 lit = vec3(0.0);
  float t_in = stretch.x;
  float t_out = stretch.y;
  TynShadowRay r = tyn_shadow_ray(map, origin, dir);
  if (tyn_clip_to_shadow_map(r, t_in, t_out)) {
    if (part == 0u) lit += tyn_transmittance_integral(stretch.x, t_in, frame.extinction);
    float begin = tyn_part_begin(t_in, t_out, part, parts);
    float end = tyn_part_end(t_in, t_out, part, parts);
#ifdef TYN_WALK_IN_STEPS
    if (tyn_walk_steps() != 0u) {
      lit += tyn_step_shadow_map(map, origin, dir, t_in, t_out, part, parts, true);
    } else
#endif
#ifdef TYN_WALK_SHADOW_BLOCKS
    if (tyn_shadow_blocks_built()) {
      lit += tyn_walk_shadow_blocks(map, origin, dir, begin, end, true);
    } else
#endif
    {
      lit += tyn_walk_shadow_map(map, origin, dir, begin, end, true);
    }
    if (part == 0u) lit += tyn_transmittance_integral(t_out, stretch.y, frame.extinction);
  } else if (part == 0u) {
    lit += tyn_transmittance_integral(stretch.x, stretch.y, frame.extinction);
  }
  return lit;
}

// Part `part` of `parts` of L_in along [0, s] of the view ray (DESIGN.md "Radiometry"): the
// stretch of the ray inside each shadow map is cut into `parts` equal lengths and this walks one of
// them, so that several threads can share one ray (common/split_march.glsl); the parts sum to the whole.
// A directional light's stretches outside the map (lit, closed form) belong to part 0.
vec3 tyn_reference_in_scattering_part(vec3 origin, vec3 dir, float s, uint part, uint parts) {
  if (TYN_LIGHT_TYPE == TYN_LIGHT_DIRECTIONAL) {
    // Each cascade walks its own stretch of the ray (one map: the whole ray). Outside the map's
    // square there is no occluder information: lit.
    vec3 lit = vec3(0.0);
    for (uint map = 0u; map < frame.shadow_map_count; ++map) {
      vec2 stretch = tyn_cascade_stretch(map, origin, dir, s);
      if (stretch.y > stretch.x) lit += tyn_walk_directional_stretch(map, origin, dir, stretch, part, parts);
    }
    float cos_theta = dot(dir, -frame.light_direction);
    return frame.light_radiance * tyn_phase_weighted_scattering(cos_theta) * lit;
  }

  // Spot: one frustum around the cone; point: six 90° frusta that tile all directions. Outside
  // the frusta the light does not reach.
  vec3 sum = vec3(0.0);
  for (uint map = 0u; map < frame.shadow_map_count; ++map) {
    float t_in = 0.0;
    float t_out = s;
    if (tyn_clip_to_shadow_map(tyn_shadow_ray(map, origin, dir), t_in, t_out)) {
#ifdef TYN_WALK_IN_STEPS
      if (tyn_walk_steps() != 0u) {
        sum += tyn_step_shadow_map(map, origin, dir, t_in, t_out, part, parts, false);
        continue;
      }
#endif
      float begin = tyn_part_begin(t_in, t_out, part, parts);
      float end = tyn_part_end(t_in, t_out, part, parts);
#ifdef TYN_WALK_SHADOW_BLOCKS
      if (tyn_shadow_blocks_built()) {
        sum += tyn_walk_shadow_blocks(map, origin, dir, begin, end, false);
        continue;
      }
#endif
      sum += tyn_walk_shadow_map(map, origin, dir, begin, end, false);
    }
  }
  return sum;
}

// L_in along [0, s] of the view ray, walked by one thread.
vec3 tyn_reference_in_scattering(vec3 origin, vec3 dir, float s) {
  return tyn_reference_in_scattering_part(origin, dir, s, 0u, 1u);
}

#endif
