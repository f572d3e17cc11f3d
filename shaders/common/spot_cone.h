// A spot light's cone along a view ray: its falloff and the ray's interval inside a cone.
#ifndef TYNDALL_SPOT_CONE_H
#define TYNDALL_SPOT_CONE_H

#include "common/light_ray.h"

TYN_BEGIN

struct TynSpotCone {
  float along;      // dot(v, axis), axis = the direction the light travels
  float across;     // dot(normal, axis)
  float cos_outer;  // cos of the outer half-angle (falloff 0 outside), > 0 (half-angle < 90°)
  float cos_inner;  // cos of the inner half-angle (falloff 1 inside), ≥ cos_outer
};

TYN_FUNC TynSpotCone tyn_spot_cone(TynLightRay r, vec3 dir, vec3 axis, float cos_outer, float cos_inner) {
  TynSpotCone c;
  c.along = dot(dir, axis);
  c.across = dot(r.normal, axis);
  c.cos_outer = cos_outer;
  c.cos_inner = max(cos_inner, cos_outer);
  return c;
}

// cos of the angle between the axis and the direction from the light to the point at angle θ:
// x − L = s v − h n, so dot(x − L, axis) / d = −cos θ · along − sin θ · across.
TYN_FUNC float tyn_spot_cos_angle(TynSpotCone c, float cos_theta, float sin_theta) {
  return -cos_theta * c.along - sin_theta * c.across;
}

// The spot's falloff (the Reference's tyn_spot_falloff: Hermite between the cones, a hard edge
// when they coincide).
TYN_FUNC float tyn_spot_falloff_of(TynSpotCone c, float cos_angle) {
  float x = clamp((cos_angle - c.cos_outer) / max(c.cos_inner - c.cos_outer, 1e-6f), 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

// The ray's parameter interval inside the cone of half-angle acos(cos_half) around the axis,
// single nappe (in front of the light), clipped to [t0, t1]: vec2(begin, end), empty when
// end ≤ begin. With f(s) = s·along − h·across (= dot(x − L, axis)), the point is inside when
// f ≥ 0 and f² ≥ cos²·(s² + h²): a quadratic a s² + 2 b s + c ≥ 0 whose discriminant is
// h² cos² (along² + across² − cos²). A line meets a cone's solid nappe in one interval (a convex
// set), bounded or not; f cannot change sign inside {quadratic ≥ 0} (f = 0 makes it negative), so
// each of that set's pieces lies in one nappe.
TYN_FUNC vec2 tyn_spot_cone_interval(TynLightRay r, TynSpotCone cone, float cos_half, float t0, float t1) {
  vec2 empty = vec2(t1, t0);
  float c2 = cos_half * cos_half;
  float a = cone.along * cone.along - c2;
  float b = -cone.along * cone.across * r.h;
  float c = (cone.across * cone.across - c2) * r.h * r.h;
  float spread = cone.along * cone.along + cone.across * cone.across - c2;
  if (spread < 0.0f) return empty;  // the line misses both nappes (a < 0 then)
  float root = r.h * cos_half * sqrt(spread);
  float q = -(b + (b >= 0.0f ? root : -root));  // |q| ≥ root: the stable quadratic formula
  if (q == 0.0f) return empty;                   // tangent through the apex region
  const float unbounded = 3.0e38f;
  float near_root = c / q;
  // The other root q / a; a → 0 (the ray parallel to a generator) sends it to ±∞ with q's sign.
  float far_root = abs(a) * 1e30f > abs(q) ? q / a : (q >= 0.0f ? unbounded : -unbounded);
  float lo = min(near_root, far_root);
  float hi = max(near_root, far_root);
  float s_begin;
  float s_end;
  if (a >= 0.0f) {
    // Outside [lo, hi]: the unbounded piece the direction points into is in front of the light.
    if (cone.along > 0.0f) {
      s_begin = hi;
      s_end = unbounded;
    } else {
      s_begin = -unbounded;
      s_end = lo;
    }
  } else {
    float mid = 0.5f * lo + 0.5f * hi;
    if (mid * cone.along - r.h * cone.across < 0.0f) return empty;  // the back nappe
    s_begin = lo;
    s_end = hi;
  }
  float begin = s_begin <= -unbounded ? t0 : max(t0, r.t_light + s_begin);
  float end = s_end >= unbounded ? t1 : min(t1, r.t_light + s_end);
  return end > begin ? vec2(begin, end) : empty;
}
TYN_END

#endif
