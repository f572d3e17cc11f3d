// How each storage variant lays its representation out in images. A shader that writes the
// rectified map or the prefix sums defines TYN_PF_BASIS (the number of a TYN_PF_* variant: the
// preprocessor cannot read TYN_CONST values) before including this file; storage format qualifiers
// are compile-time, so each variant is its own SPIR-V (rectify_*.comp, prefix_sums_*.comp).
// The C++ side keeps the same table (kStorage in plugin/src/prefiltered/prefiltered_technique.cpp).
//
// A representation is TYN_PF_SLOTS vec4 "slots". Slots [0, TYN_PF_LAYERS_A) are layers of image A,
// the rest layers of image B; with several prefix-sum sets, set s owns layers [s·L, (s + 1)·L) of
// each image of the prefix sums (the rectified map has one set).
//   variant        A (format, layers)                    B
//   moments4_64    RGBA16_UNORM  1: Θ4*(b1..b4)          -
//   moments4_128   RGBA32F       1: b1..b4               -
//   moments6_64    A2B10G10R10   2: Θ6* odd, Θ6* even    -
//   moments6_96    RGBA16_UNORM  1: Θ6* odd, even.x      RG16_UNORM 1: Θ6* even.yz
//   moments6_192   RGBA32F       1: b1, b3, b5, b2       RG32F 1: b4, b6
//   fourier32      RGBA8_UNORM   8: ½ + ½·B(z), 4 coefficients per layer
// Every stored channel is an affine function of the canonical representation, so a weighted
// average (the prefix sums, bilinear filtering) of stored values is the stored value of the
// average: the prefix-sum pass never converts.
#ifndef TYNDALL_PREFILTERED_STORAGE_VARIANTS_GLSL
#define TYNDALL_PREFILTERED_STORAGE_VARIANTS_GLSL

#include "prefiltered/moments.h"

#if TYN_PF_BASIS == 0
#define TYN_PF_FORMAT_A rgba16
#define TYN_PF_LAYERS_A 1u
#elif TYN_PF_BASIS == 1
#define TYN_PF_FORMAT_A rgba32f
#define TYN_PF_LAYERS_A 1u
#elif TYN_PF_BASIS == 2
#define TYN_PF_FORMAT_A rgb10_a2
#define TYN_PF_LAYERS_A 2u
#elif TYN_PF_BASIS == 3
#define TYN_PF_FORMAT_A rgba16
#define TYN_PF_LAYERS_A 1u
#define TYN_PF_FORMAT_B rg16
#elif TYN_PF_BASIS == 4
#define TYN_PF_FORMAT_A rgba32f
#define TYN_PF_LAYERS_A 1u
#define TYN_PF_FORMAT_B rg32f
#elif TYN_PF_BASIS == 5
#define TYN_PF_FORMAT_A rgba8
#define TYN_PF_LAYERS_A 8u
#else
#error "TYN_PF_BASIS must name a storage variant (0..5)"
#endif

#ifdef TYN_PF_FORMAT_B
#define TYN_PF_SLOTS (TYN_PF_LAYERS_A + 1u)
#else
#define TYN_PF_SLOTS TYN_PF_LAYERS_A
#endif

layout(set = 0, binding = TYN_PF_BINDING_RECTIFIED_A_STORAGE, TYN_PF_FORMAT_A) uniform writeonly image2DArray rectified_out_a;
layout(set = 0, binding = TYN_PF_BINDING_PREFIX_A_STORAGE, TYN_PF_FORMAT_A) uniform writeonly image2DArray prefix_out_a;
#ifdef TYN_PF_FORMAT_B
layout(set = 0, binding = TYN_PF_BINDING_RECTIFIED_B_STORAGE, TYN_PF_FORMAT_B) uniform writeonly image2DArray rectified_out_b;
layout(set = 0, binding = TYN_PF_BINDING_PREFIX_B_STORAGE, TYN_PF_FORMAT_B) uniform writeonly image2DArray prefix_out_b;
#endif

// Slot `slot` of the representation of a light ray whose occluders are at normalised rectified
// depths `depths` (in [0, 1]) with weights `weights` (summing to 1).
vec4 tyn_pf_slot(uint slot, vec2 depths, vec2 weights) {
#if TYN_PF_BASIS == 5
  return tyn_fourier_pack(weights.x * tyn_fourier_basis(depths.x, slot) +
                          weights.y * tyn_fourier_basis(depths.y, slot));
#else
  // Signed depth in [−1, 1] (peters2017 §2.3).
  vec2 z = 2.0 * depths - 1.0;
#if TYN_PF_BASIS <= 1
  vec4 b = weights.x * tyn_moments4(z.x) + weights.y * tyn_moments4(z.y);
#if TYN_PF_BASIS == 0
  return tyn_quantize_moments4_64(b);
#else
  return tyn_quantize_moments4_128(b);
#endif
#else
  vec3 odd = weights.x * tyn_moments6_odd(z.x) + weights.y * tyn_moments6_odd(z.y);
  vec3 even = weights.x * tyn_moments6_even(z.x) + weights.y * tyn_moments6_even(z.y);
#if TYN_PF_BASIS != 4
  odd = tyn_quantize_moments6_odd(odd);
  even = tyn_quantize_moments6_even(even);
#endif
#if TYN_PF_BASIS == 2
  return slot == 0u ? vec4(odd, 0.0) : vec4(even, 0.0);
#else
  return slot == 0u ? vec4(odd, even.x) : vec4(even.y, even.z, 0.0, 0.0);
#endif
#endif
#endif
}

void tyn_pf_store_rectified(ivec2 texel, uint slot, vec4 value) {
#ifdef TYN_PF_FORMAT_B
  if (slot >= TYN_PF_LAYERS_A) {
    imageStore(rectified_out_b, ivec3(texel, int(slot - TYN_PF_LAYERS_A)), value);
    return;
  }
#endif
  imageStore(rectified_out_a, ivec3(texel, int(slot)), value);
}

vec4 tyn_pf_load_rectified(ivec2 texel, uint slot) {
#ifdef TYN_PF_FORMAT_B
  if (slot >= TYN_PF_LAYERS_A) return texelFetch(rectified_b, ivec3(texel, int(slot - TYN_PF_LAYERS_A)), 0);
#endif
  return texelFetch(rectified_a, ivec3(texel, int(slot)), 0);
}

void tyn_pf_store_prefix(ivec2 texel, uint set, uint slot, vec4 value) {
#ifdef TYN_PF_FORMAT_B
  if (slot >= TYN_PF_LAYERS_A) {
    imageStore(prefix_out_b, ivec3(texel, int(set + slot - TYN_PF_LAYERS_A)), value);
    return;
  }
#endif
  imageStore(prefix_out_a, ivec3(texel, int(set * TYN_PF_LAYERS_A + slot)), value);
}

#endif
