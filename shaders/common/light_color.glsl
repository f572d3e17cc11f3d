// The light-colour texture (stained glass, FrameDesc::lightColor): a colour filter laid over shadow
// map 0's UV square. Needs `frame` and a `light_color` sampler (linear, clamp to edge) in scope.
// frame.has_light_color says whether one is bound; without one, and outside the square, the light is
// unfiltered (white).
#ifndef TYNDALL_LIGHT_COLOR_GLSL
#define TYNDALL_LIGHT_COLOR_GLSL

bool tyn_has_light_color() { return frame.has_light_color != 0u; }

vec3 tyn_light_color_uv(vec2 uv) {
  if (!tyn_has_light_color() || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return vec3(1.0);
  return textureLod(light_color, uv, 0.0).rgb;
}

// At a point given by its clip coordinates in shadow map 0.
vec3 tyn_light_color_clip(vec4 clip) {
  if (!tyn_has_light_color() || !(clip.w > 0.0)) return vec3(1.0);
  return tyn_light_color_uv(vec2(clip.x, clip.y) / clip.w * 0.5 + 0.5);
}

// At a world position, through shadow map 0's projection.
vec3 tyn_light_color_at(vec3 position) {
  if (!tyn_has_light_color()) return vec3(1.0);
  return tyn_light_color_clip(frame.world_to_shadow[0] * vec4(position, 1.0));
}

#endif
