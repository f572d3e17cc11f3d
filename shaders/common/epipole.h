// The epipole, the light projected onto the screen, shared by the epipolar technique (its slices
// run from it) and the prefiltered one (its block of ray-marched pixels is centred on it).
// It is kept homogeneous, vec4(x, y, w, side) with |(x, y, w)| = 1 and w ≥ 0, so that an epipole
// at (or near) infinity needs no special case: the line through the epipole and a screen point p
// runs along w·p − (x, y), which stays well-defined as w → 0. side = 1: light in front of the
// camera; −1: behind (the epipole is mirrored and light shafts converge to it on screen); 0:
// degenerate (light at the camera position, or a directional light along an orthographic camera's
// axis): the epipole is then taken at the screen centre (engelhardt2010 §4.1).
#ifndef TYNDALL_EPIPOLE_H
#define TYNDALL_EPIPOLE_H

#include "common/cpp_glsl.h"

TYN_BEGIN

// A directional light is the point at infinity in the direction it comes from (−light_dir).
TYN_FUNC vec4 tyn_epipole_clip_directional(mat4 view_proj, vec3 light_dir) {
  return view_proj * vec4(-light_dir, 0.0f);
}

TYN_FUNC vec4 tyn_epipole_clip_local(mat4 view_proj, vec3 light_pos) {
  return view_proj * vec4(light_pos, 1.0f);
}

// The epipole from the light's clip position (either function above). Only x, y, w matter: the
// depth row differs between standard, reverse-Z and infinite projections but not where a point
// lands on screen. Negating (x, y, w) names the same screen point, so a light behind the camera
// (w < 0) is stored with w ≥ 0: its mirrored epipole, where the shafts converge. Scaling by the
// largest component before normalising keeps far lights (huge components) and lights near the
// camera (tiny ones) in float range.
TYN_FUNC vec4 tyn_epipole(vec4 light_clip) {
  vec3 h = vec3(light_clip.x, light_clip.y, light_clip.w);
  float largest = max(max(abs(h.x), abs(h.y)), abs(h.z));
  if (!(largest > 0.0f)) return vec4(0.0f, 0.0f, 1.0f, 0.0f);  // degenerate: screen centre
  float side = light_clip.w < 0.0f ? -1.0f : 1.0f;
  return vec4(normalize(h * (side / largest)), side);
}

TYN_FUNC bool tyn_epipole_behind(vec4 epipole) { return epipole.w < 0.0f; }

// The epipole in NDC. Only meaningful when epipole.z > 0; at infinity (z = 0) it returns a huge
// but finite point in the right direction.
TYN_FUNC vec2 tyn_epipole_ndc(vec4 epipole) {
  return vec2(epipole.x, epipole.y) / max(epipole.z, 1.0e-30f);
}

TYN_END

#endif
