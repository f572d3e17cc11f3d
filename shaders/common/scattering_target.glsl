// The L_in target the approximate techniques write: RGBA16F by default. Their error is orders of
// magnitude above its rounding (2^-11 relative), and it halves the largest allocation of a frame;
// the Reference, the validation path, keeps RGBA32F (plugin/src/technique.h). The build compiles
// each pass that binds the target a second time with TYN_SCATTERING_TARGET_FULL defined, for
// RGBA32F (ContextTuning::fullFloatTargets).
#ifndef TYNDALL_SCATTERING_TARGET_GLSL
#define TYNDALL_SCATTERING_TARGET_GLSL

#ifdef TYN_SCATTERING_TARGET_FULL
#define TYN_SCATTERING_TARGET_FORMAT rgba32f
#else
#define TYN_SCATTERING_TARGET_FORMAT rgba16f
#endif

// The largest finite half float: a scaled L_in above it (2^15 times the frame's typical L_in, next
// to a local light's image) is stored as it, not as +inf.
const float TYN_HALF_MAX = 65504.0;

// What the target stores for L_in (FrameConstants::target_scale; needs `frame` in scope).
vec4 tyn_target_value(vec3 in_scattering) {
#ifdef TYN_SCATTERING_TARGET_FULL
  return vec4(in_scattering * frame.target_scale, 0.0);
#else
  return vec4(min(in_scattering * frame.target_scale, vec3(TYN_HALF_MAX)), 0.0);
#endif
}

#endif
