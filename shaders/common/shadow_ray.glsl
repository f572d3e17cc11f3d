// A view ray in a shadow map's clip space, and its clip to the map's bounds: shared by the
// Reference's texel walk (common/texel_walk.glsl), the epipolar march and the epipolar
// refinement's shadow test (epipolar/slice_ray.glsl), which must agree on the ray to the bit.
// Needs `frame` (FrameConstants) in scope.
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

#endif
