// Push constants of the epipolar passes (shared by C++ and GLSL; 16-byte members).
#ifndef TYNDALL_EPIPOLAR_CONSTANTS_H
#define TYNDALL_EPIPOLAR_CONSTANTS_H

#include "common/cpp_glsl.h"

TYN_BEGIN

// Workgroup sizes: one thread per slice, per (sample, slice), per pixel, per fixed-up pixel.
TYN_CONST uint TYN_EPIPOLAR_SLICE_GROUP = 64u;
TYN_CONST uint TYN_EPIPOLAR_FIXUP_GROUP = 64u;
// Interpolation source of a sample past the slice's sample count.
TYN_CONST uint TYN_EPIPOLAR_NO_SOURCE = 0xffffffffu;

struct EpipolarConstants {
  vec4 epipole;      // homogeneous epipole (tyn_epipole): x, y, w, side
  uvec4 counts;      // x: slices; y: samples per slice; z: 1 = improved sample placement;
                     // w: initial sample step (every w-th sample is ray-marched)
  vec4 params;       // x: epipole density; y: bilateral depth threshold (relative);
                     // z: minimum bilateral weight before a pixel is fixed up;
                     // w: radius in pixels around an on-screen epipole that is always fixed up
  vec4 refinement;   // x: relative depth break between neighbouring samples that makes both
                     // of them ray-marched samples
};

TYN_END

#endif
