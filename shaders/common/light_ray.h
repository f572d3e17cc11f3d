// A view ray as seen from a spot or point light: the foot of the light on the ray, the light's
// distance h to it, and the angle θ of each point (docs/derivations/scattering-lut.md
// "The reformulation"). Shared by the local-light quadrature, the spot cone and the scattering table.
#ifndef TYNDALL_LIGHT_RAY_H
#define TYNDALL_LIGHT_RAY_H

#include "common/precise_trig.h"

TYN_BEGIN

// Smallest distance from the light to the ray that is used (scene units): a ray through the light
// has an infinite integral; 1e-18 keeps h² (1e-36) and every angle h/d (d < 1e20) normal floats, which
// GPUs would otherwise flush to 0.
TYN_CONST float TYN_LOCAL_LIGHT_MIN_H = 1e-18f;

struct TynLightRay {
  float t_light;  // t_L = dot(L − C, v): ray parameter of the foot, the point closest to the light
  float h;        // distance from the light to the line, ≥ TYN_LOCAL_LIGHT_MIN_H
  vec3 normal;    // unit vector from the foot towards the light (some unit vector ⊥ v if h = 0)
};

// v must be unit length. h carries float's absolute error of the whole offset, ε |L − C| (the
// integral's own sensitivity to the inputs, about |L − C| / h times theirs): nothing here can
// resolve a ray passing closer to the light than ~1e-7 |L − C|.
TYN_FUNC TynLightRay tyn_light_ray(vec3 origin, vec3 dir, vec3 light_position) {
  TynLightRay r;
  vec3 to_light = light_position - origin;
  r.t_light = dot(to_light, dir);
  vec3 across = to_light - r.t_light * dir;
  float h = length(across);
  r.h = max(h, TYN_LOCAL_LIGHT_MIN_H);
  vec3 helper = abs(dir.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  r.normal = h > 0.0f ? across / h : normalize(cross(dir, helper));
  return r;
}

// A point of the ray, as the reformulation sees it.
struct TynLightPoint {
  float t;      // ray parameter (≥ 0)
  float s;      // t − t_L
  float d;      // distance to the light
  float theta;  // scattering angle θ = atan2(h, −s): cos θ = dot(v, ω_l)
  float u;      // π − θ = atan2(h, s), accurate where θ is near π
  float path;   // t + d: the light's path through the medium to the camera
  float foot;   // s + d = h tan(θ/2) (= path − t_L, without cancellation)
};

TYN_FUNC TynLightPoint tyn_light_point(TynLightRay r, float t) {
  TynLightPoint p;
  p.t = t;
  p.s = t - r.t_light;
  p.d = sqrt(p.s * p.s + r.h * r.h);
  p.theta = tyn_precise_atan2(r.h, -p.s);
  p.u = tyn_precise_atan2(r.h, p.s);
  p.path = t + p.d;
  // s + d cancels when s < 0: (d + s)(d − s) = h².
  p.foot = p.s >= 0.0f ? p.s + p.d : r.h * r.h / (p.d - p.s);
  return p;
}
TYN_END

#endif
