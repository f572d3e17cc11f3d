// A view ray in a shadow map's clip space, and its clip to the map's bounds: shared by the
// Reference's texel walk (common/texel_walk.glsl), the epipolar march and the epipolar
// refinement's shadow test (epipolar/slice_ray.glsl), which must agree on the ray to the bit; the
// texel they read, and the stretch of a view ray each cascade serves. Needs `frame`
// (FrameConstants) and `shadow_maps` in scope.
#ifndef TYNDALL_SHADOW_RAY_GLSL
#define TYNDALL_SHADOW_RAY_GLSL

// Shadow-clip coordinates along the ray, h(t) = h0 + t · h1 (homogeneous, so linear in t).
struct TynShadowRay {
  vec4 h0;
  vec4 h1;
};

TynShadowRay tyn_shadow_ray(uint map, vec3 origin, vec3 dir) {
  TynShadowRay r;
  r.h0 = frame.world_to_shadow[map] * vec4(origin, 1.0);
  r.h1 = frame.world_to_shadow[map] * vec4(dir, 0.0);
  return r;
}

// Clips [t0, t1] to the map's pyramid (perspective) or slab (orthographic): |x| ≤ w, |y| ≤ w.
// Each bound is a + b t ≥ 0.
bool tyn_clip_to_shadow_map(TynShadowRay r, inout float t0, inout float t1) {
  vec4 a = vec4(r.h0.w - r.h0.x, r.h0.w + r.h0.x, r.h0.w - r.h0.y, r.h0.w + r.h0.y);
  vec4 b = vec4(r.h1.w - r.h1.x, r.h1.w + r.h1.x, r.h1.w - r.h1.y, r.h1.w + r.h1.y);
  for (int i = 0; i < 4; ++i) {
    if (b[i] == 0.0) {
      if (a[i] < 0.0) return false;
    } else if (b[i] > 0.0) {
      t0 = max(t0, -a[i] / b[i]);
    } else {
      t1 = min(t1, -a[i] / b[i]);
    }
  }
  return t0 < t1;
}

// Depth of one texel of one shadow map. Without shaderSampledImageArrayDynamicIndexing a sampler
// array may only be indexed by constants.
float tyn_shadow_texel(uint map, ivec2 texel) {
  switch (map) {
    case 0u: return texelFetch(shadow_maps[0], texel, 0).r;
    case 1u: return texelFetch(shadow_maps[1], texel, 0).r;
    case 2u: return texelFetch(shadow_maps[2], texel, 0).r;
    case 3u: return texelFetch(shadow_maps[3], texel, 0).r;
    case 4u: return texelFetch(shadow_maps[4], texel, 0).r;
    default: return texelFetch(shadow_maps[5], texel, 0).r;
  }
}

// The stretch [a, b] of [0, s] of the view ray that cascade `map` serves (of shadow_map_count;
// one map serves all of it): view depths [cascade_far[map − 1], cascade_far[map]), the first
// cascade from the camera, the last to the end. View depth is affine in t: d(t) = d0 + t · d1.
vec2 tyn_cascade_stretch(uint map, vec3 origin, vec3 dir, float s) {
  if (frame.shadow_map_count <= 1u) return vec2(0.0, s);
  float d0 = dot(frame.view_depth_axis.xyz, origin) + frame.view_depth_axis.w;
  float d1 = dot(frame.view_depth_axis.xyz, dir);
  if (d1 <= 0.0) return map == 0u ? vec2(0.0, s) : vec2(s);  // a ray that does not recede: the first cascade's
  float a = map == 0u ? 0.0 : clamp((frame.cascade_far[map - 1u] - d0) / d1, 0.0, s);
  float b = map + 1u >= frame.shadow_map_count ? s : clamp((frame.cascade_far[map] - d0) / d1, a, s);
  return vec2(a, b);
}

#endif
