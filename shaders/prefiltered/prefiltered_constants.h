// The constant block of the prefiltered passes (shared by C++ and GLSL) and the numbers the passes
// and the C++ side must agree on. The maths is in rectification.h and
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

// Bindings of the prefiltered passes' one descriptor set (prefiltered_common.glsl and
// storage_variants.glsl declare them; PrefilteredTechnique writes descriptor i at binding i). The
// moment map, rectified map and prefix sums are bound twice: sampled, and as storage images.
TYN_CONST uint TYN_PF_BINDING_FRAME = 0u;
TYN_CONST uint TYN_PF_BINDING_DEPTH = 1u;
TYN_CONST uint TYN_PF_BINDING_SHADOW_MAPS = 2u;
TYN_CONST uint TYN_PF_BINDING_CONSTANTS = 3u;
TYN_CONST uint TYN_PF_BINDING_OUT_SCATTERING = 4u;
TYN_CONST uint TYN_PF_BINDING_LIGHT_COLOR = 5u;
TYN_CONST uint TYN_PF_BINDING_MOMENT_MAP = 6u;
TYN_CONST uint TYN_PF_BINDING_MOMENT_MAP_STORAGE = 7u;
TYN_CONST uint TYN_PF_BINDING_RECTIFIED_A = 8u;
TYN_CONST uint TYN_PF_BINDING_RECTIFIED_B = 9u;
TYN_CONST uint TYN_PF_BINDING_RECTIFIED_A_STORAGE = 10u;
TYN_CONST uint TYN_PF_BINDING_RECTIFIED_B_STORAGE = 11u;
TYN_CONST uint TYN_PF_BINDING_PREFIX_A = 12u;
TYN_CONST uint TYN_PF_BINDING_PREFIX_B = 13u;
TYN_CONST uint TYN_PF_BINDING_PREFIX_A_STORAGE = 14u;
TYN_CONST uint TYN_PF_BINDING_PREFIX_B_STORAGE = 15u;
TYN_CONST uint TYN_PF_BINDING_FIXUP_ARGS = 16u;
TYN_CONST uint TYN_PF_BINDING_DEPTH_BOUNDS_TEXELS = 17u;
TYN_CONST uint TYN_PF_BINDING_DEPTH_BOUNDS_PREFIX = 18u;
TYN_CONST uint TYN_PF_BINDING_TEXEL_DEPTHS = 19u;
TYN_CONST uint TYN_PF_BINDING_COUNT = 20u;

// The constant block of the prefiltered passes (std140): scalars grouped in 16-byte rows, at the
// same offsets in C++ (prefiltered_technique.cpp static_asserts them).
struct PrefilteredConstants {
  NonLinearRectificationParams nonlinear;    // also the light frame of the projective map
  ProjectiveRectificationParams projective;
  uint map_columns;           // the rectified map's columns
  uint map_rows;              // and rows
  uint projective_map;        // 1: projective rectification; 0: non-linear
  uint rows_wrap;             // 1: rows wrap around (non-linear over the full circle of φ)
  uint filtered_resampling;   // 1: the rectification filters the moment map
  uint spacing;               // TYN_PF_SPACING_*
  uint prefix_sum_sets;       // prefix-sum sets (one per distinct extinction, ≤ TYN_PF_MAX_SETS)
  uint host_map_size;         // the host's shadow-map side (texels)
  vec3 set_extinction;        // σ_t of the prefix weights of set 0, 1, 2 (per scene unit)
  float pad0;
  uvec3 channel_set;          // the set that R, G, B read
  uint pad1;
  vec4 epipole;               // the light's homogeneous epipole and its side (tyn_epipole)
  uint epipole_block_pixels;  // side of the ray-marched block around the epipole (0: no block)
  uint ray_weight_taps;       // lookups per pixel re-weighting the row to its ray (weight_taps.h;
                              // 1: one lookup)
  uint segmented;             // 1: segmented reconstruction
  uint trimmed;               // 1: trimmed segments (the row depth bounds decide their ends)
  float overestimation;       // β between the moment bounds (peters2017 §5.3); negative: adaptive
                              // (§5.3.1)
  uint depth_bounds;          // 1: the row depth bounds are built and read
  uint pad2;
  uint pad3;
  uint short_ray_columns;     // a ray ending within this many columns of its row's start is
                              // ray-marched (0: none)
  uint texel_walk_steps;      // steps of the texel walk per trimmed segment (0: none)
  uint pad4;
  uint pad5;
};

// The epipole block's dispatch, written on the GPU by epipole_fixup_args.comp.
struct PrefilteredFixupArgs {
  uvec3 groups;   // VkDispatchIndirectCommand
  uint pad0;
  ivec2 rect_lo;  // pixels [rect_lo, rect_hi) of the block clipped to the screen
  ivec2 rect_hi;
};

TYN_END

#endif
