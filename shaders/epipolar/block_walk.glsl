// The epipolar passes' walk of a shadow map: the Reference's texel walk
// (common/texel_walk.glsl, tyn_walk_shadow_map; this is its TYN_WALK_SHADOW_BLOCKS hook) that crosses a block of
// tyn_shadow_block_size()² texels in one step where the block's depth range (shadow_blocks.comp)
// decides every texel the same way — the ray at or in front of the nearest occluder (all lit) or
// behind the farthest (all shadowed, skipped) — and walks it texel by texel otherwise. A
// directional light's fix-up walks its map so: a fixed-up pixel sits at a depth break and its ray
// crosses the whole map; over open ground or inside a shadow its texels all agree, so most of the
// walk becomes block steps. A point light's march and fix-up walk its six maps so (its samples
// have no single slice line: every one is walked): a lit block extends the lit section being
// merged (TYN_WALK_LIT_SECTIONS), integrated from the semi-analytic table when it closes.
// Each texel that is walked is tested exactly as in the Reference; a block step changes the sum
// only by rounding (one integral instead of the texels' several), and per texel the verdict is
// the same, because the ray's clip depth z/w is monotonic in t where w > 0 (inside the map's
// frustum, orthographic or perspective), so its extremes over a block are at the block's ends.
// Lit blocks are walked texel by texel where the lit parts take a colour per texel or node (a
// light-colour texture) or a quadrature per part (a spot light, whose fix-up keeps the
// Reference's per-part quadrature, and which builds no blocks). Needs `shadow_blocks` (binding 7:
// map m's blocks in rows [m · side, (m + 1) · side)) in scope.
#ifndef TYNDALL_BLOCK_WALK_GLSL
#define TYNDALL_BLOCK_WALK_GLSL

#include "common/texel_walk.glsl"

vec3 tyn_walk_shadow_blocks(uint map, vec3 origin, vec3 dir, float t0, float t1, bool directional) {
  bool sections = tyn_walk_merges_sections(directional);
  vec2 section = vec2(t0);  // the lit section being merged (tyn_walk_add_lit_part)
  bool lit_steps = (directional && !tyn_has_light_color()) || sections;
  TynShadowRay r = tyn_shadow_ray(map, origin, dir);
  TynLocalLightRay local_ray = tyn_local_light_ray(origin, dir);
  int size = int(frame.shadow_map_size);
  float n = float(size);
  int block_size = tyn_shadow_block_size();
  int block_row = int(map) * ((size + block_size - 1) / block_size);  // this map's first row of blocks

  ivec2 texel;
  ivec2 step_dir;
  tyn_walk_start(r, t0, size, texel, step_dir);

  vec3 sum = vec3(0.0);
  float t = t0;
  bool coarse = true;  // at a block's first texel: try the block step
  // At most every texel edge and every block edge once (the loop budget of tyn_walk_shadow_map).
  int max_steps = 2 * size + 2 * (size / block_size + 1) + 8;
  for (int i = 0; i < max_steps && t < t1; ++i) {
    ivec2 block = texel / block_size;
    if (coarse) {
      ivec2 lo = block * block_size;
      ivec2 hi = min(lo + block_size, ivec2(size));  // exclusive
      ivec2 exit_edges = ivec2(step_dir.x > 0 ? hi.x : lo.x, step_dir.y > 0 ? hi.y : lo.y);
      vec2 crossing = tyn_edge_crossings(r, step_dir, exit_edges, n);
      float tx = crossing.x;
      float ty = crossing.y;
      float t_exit = clamp(min(tx, ty), t, t1);
      vec2 range = imageLoad(shadow_blocks, ivec2(block.x, block_row + block.y)).rg;  // nearest, farthest occluder
      vec4 h_begin = r.h0 + t * r.h1;
      vec4 h_exit = r.h0 + t_exit * r.h1;  // the ray's clip point where it leaves the block
      float z_begin = h_begin.z / h_begin.w;
      float z_end = h_exit.z / h_exit.w;
      bool lit = lit_steps && (range.x >= 1.0 || max(z_begin, z_end) <= range.x);
      bool shadowed = range.y < 1.0 && min(z_begin, z_end) > range.y;
      if (lit || shadowed) {
        if (lit && t_exit > t) tyn_walk_add_lit_part(sum, section, directional, sections, local_ray, origin, dir, t, t_exit);
        t = t_exit;
        // Into the next block across the edge crossed; along the other axis, the texel of the
        // exit point, kept inside this block's span against rounding.
        ivec2 exit_texel = tyn_clip_texel(h_exit, n);
        if (tx <= ty) {
          texel.x = step_dir.x > 0 ? hi.x : lo.x - 1;
          texel.y = clamp(exit_texel.y, lo.y, hi.y - 1);
        } else {
          texel.y = step_dir.y > 0 ? hi.y : lo.y - 1;
          texel.x = clamp(exit_texel.x, lo.x, hi.x - 1);
        }
        if (!tyn_texel_in_map(texel, size)) break;
        continue;
      }
      coarse = false;
    }

    // One texel, as tyn_walk_shadow_map.
    vec2 crossing = tyn_edge_crossings(r, step_dir, texel + max(step_dir, ivec2(0)), n);
    float t_next = clamp(min(crossing.x, crossing.y), t, t1);
    if (t_next > t) {
      vec2 part = tyn_texel_lit_part(r, tyn_shadow_texel(map, texel), t, t_next);
      if (part.y > part.x) tyn_walk_add_lit_part(sum, section, directional, sections, local_ray, origin, dir, part.x, part.y);
    }
    t = t_next;
    if (!tyn_next_texel(texel, step_dir, crossing, size)) break;
    coarse = any(notEqual(texel / block_size, block));
  }
  tyn_walk_close_section(sum, section, sections, origin, dir);
  return sum;
}

#endif
