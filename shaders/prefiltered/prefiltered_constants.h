// The constant block of the prefiltered passes (shared by C++ and GLSL, std140: 16-byte members)
// and the numbers the passes and the C++ side must agree on. The maths is in rectification.h and
// moments.h; plugin/src/prefiltered/prefiltered_technique.cpp fills the block each frame.
#ifndef TYNDALL_PREFILTERED_CONSTANTS_H
#define TYNDALL_PREFILTERED_CONSTANTS_H

#include "common/cpp_glsl.h"
#include "prefiltered/rectification.h"

TYN_BEGIN

// Storage variants, in the order of tyndall::PrefilteredBasis (static_asserted in C++). Their
// formats and layers: prefiltered/storage_variants.glsl and kStorage in prefiltered_technique.cpp.
TYN_CONST uint TYN_PF_MOMENTS4_64 = 0u;
TYN_CONST uint TYN_PF_MOMENTS4_128 = 1u;
TYN_CONST uint TYN_PF_MOMENTS6_64 = 2u;
TYN_CONST uint TYN_PF_MOMENTS6_96 = 3u;
TYN_CONST uint TYN_PF_MOMENTS6_192 = 4u;
TYN_CONST uint TYN_PF_FOURIER32 = 5u;

TYN_CONST uint TYN_PF_SPACING_MEAN_THETA = 0u;
TYN_CONST uint TYN_PF_SPACING_REFERENCE_RAY = 1u;
TYN_CONST uint TYN_PF_SPACING_FASTEST_RAY = 2u;

// peters2017 Appendix C: 8 × 8 thread groups, eight threads per row, each writing every eighth
// texel of its row (one 8-texel block per step, coalesced). One thread per row runs 64 rows per
// group (klehm2014 §3.3).
TYN_CONST uint TYN_PF_ROW_THREADS = 8u;
TYN_CONST uint TYN_PF_ROWS_PER_GROUP = 8u;
TYN_CONST uint TYN_PF_THREAD_PER_ROW_GROUP = 64u;
// The workgroup scan: one row per group of 128 threads (Vulkan's guaranteed minimum of
// maxComputeWorkGroupInvocations), a run of columns / 128 texels each (16 at the default 2048).
TYN_CONST uint TYN_PF_SCAN_THREADS = 128u;
// Texel passes (moment map, rectification) and the epipole block run 8 × 8 groups.
TYN_CONST uint TYN_PF_TEXEL_GROUP = 8u;

// Up to one prefix-sum set per distinct extinction channel (choosePrefixSumExtinction).
TYN_CONST uint TYN_PF_MAX_SETS = 3u;

// A depth the filtered resampling reconstructs within this of the host map's clear value 1 is
// "no occluder" (the clear value itself is exact in the unfiltered path): an allowance for the
// rounding of the 16-bit moments Algorithm 2 starts from. A real occluder this close to the host's
// far plane could only shadow points behind it, below the geometry the map was fitted to
// (DESIGN.md: the host fits the map around every occluder).
TYN_CONST float TYN_PF_CLEAR_DEPTH_TOLERANCE = 1.0e-3f;

struct PrefilteredConstants {
  NonLinearRectificationParams nonlinear;    // also the light frame of the projective map
  ProjectiveRectificationParams projective;
  uvec4 map;            // x: columns, y: rows; z: 1 = projective rectification;
                        // w: 1 = rows wrap around (non-linear over the full circle of φ)
  uvec4 options;        // x: 1 = filtered resampling; y: TYN_PF_SPACING_*; z: prefix-sum sets;
                        // w: host shadow-map size (texels)
  vec4 set_extinction;  // xyz: σ_t of the prefix weights of sets 0, 1, 2 (per scene unit)
  uvec4 channel_set;    // xyz: the set that R, G, B read
  vec4 epipole;         // tyn_epipole of the light (x, y, w homogeneous NDC; side)
  uvec4 fixup;          // x: epipole block side in pixels (0: no block); y: ray-weight taps per
                        // pixel (weight_taps.h; 1: one lookup); z: 1 = segmented reconstruction
  vec4 bounds;          // x: β between the moment bounds (peters2017 §5.3), negative: adaptive (§5.3.1)
  uvec4 walks;          // x: a ray ending within this many columns of its row's start is ray-marched
                        // (0: none); y: steps of the texel walk per trimmed segment (0: none); zw: unused
};

// The epipole block's dispatch, written on the GPU by epipole_fixup_args.comp.
struct PrefilteredFixupArgs {
  uvec4 groups;  // xyz: VkDispatchIndirectCommand; w: unused
  ivec4 rect;    // pixels [x0, x1) × [y0, y1) of the block clipped to the screen
};

TYN_END

#endif
