// Every constant of the moment shadow maps used by prefiltered single scattering with moments,
// from peters2017 (../shared/papers/peters2017-improved-moment-shadow-maps.md), in one place.
// The functions that use them are in prefiltered/moments.h; the properties that define them are
// checked in integration-tests/unit/test_moments.cpp (ranges, exact inverses, b* inside the valid
// moment domain).
//
// ## Storage variants (moments of the signed depth z ∈ [−1, 1], §2.3; b0 = 1 is never stored)
// | variant                 | texels                         | transform | b*            | α_b   |
// |-------------------------|--------------------------------|-----------|---------------|-------|
// | 4 moments,  64 bits     | RGBA16_UNORM                   | Θ4*       | 4_64_B_STAR   | 6e-5  |
// | 4 moments, 128 bits     | RGBA32F                        | none      | 4_128_B_STAR  | 3e-7  |
// | 6 moments,  64 bits     | 2 × A2B10G10R10_UNORM (rgb)    | Θ6*       | 6_B_STAR      | 4e-3  |
// | 6 moments,  96 bits     | RGBA16_UNORM + RG16_UNORM      | Θ6*       | 6_B_STAR      | 8e-5  |
// | 6 moments, 192 bits     | 2 × three float32 channels     | none      | 6_B_STAR      | 5e-6  |
// Float storage keeps canonical moments: a transform cannot add precision there because it has to
// be undone in single precision before Algorithm 1 (§2.3). The 192-bit row is our reading of
// §5.4.3, which gives its α_b but not whether Θ6* is applied; the unit test checks the bounds
// with this choice.
// IMPORTANT (float storage): for 4 moments in 128 bits, α_b = 3e-7 is at float32 resolution:
// α_b times the smallest eigenvalue of B(b*) (0.2) is 6e-8, one ulp of a moment just below 1, so
// the bias cannot absorb the rounding of the moments themselves (and the blend toward b* itself
// rounds away for such moments). The unit test MomentBounds.* measures bounds up to ~350 α_b
// (1e-4) beyond the true shadow where B(b) is near singular, as far as that rounding lets the
// exact bounds move. For 6 moments in 192 bits the bias does absorb the rounding (0.8 α_b in
// exact arithmetic), but evaluating the bounds in float32 adds up to 16 α_b (8e-5). The
// quantized variants stay within α_b. The values here are the paper's (chosen by eye).
// IMPORTANT: b* and α_b belong to their variant (b* for Θ4* storage is measured in the transformed
// metric, §2.5); mixing them across variants voids the worst-case guarantee.
#ifndef TYNDALL_MOMENT_CONSTANTS_H
#define TYNDALL_MOMENT_CONSTANTS_H

#include "common/cpp_glsl.h"

TYN_BEGIN

// ---- Θ4*, the sparse quantization transform for 4 moments in 64 bits (§2.4, Equation 3) -------
// Θ4*(b1, b2, b3, b4) = M · (b1, b2, b3, b4) + (½, 0, ½, 0) with
//   M = [ 3/2    0    −2      0 ]
//       [ 0      4     0     −4 ]
//       [ √3/2   0   −2√3/9   0 ]
//       [ 0      ½     0      ½ ]
// Half of M is zero: odd moments (b1, b3) give channels (x, z), even ones (b2, b4) give (y, w), so
// it is stored as two 2×2 blocks (GLSL/GLM constructors take columns). For one depth the channels
// are (1 − T3(z))/2, (1 − T4(z))/2, ½ + (√3/2) z (1 − (4/9) z²) and (z² + z⁴)/2, each in [0, 1].
TYN_CONST mat2 TYN_THETA4_ODD = mat2(1.5f, 0.8660254037844386f,      // column b1: 3/2, √3/2
                                     -2.0f, -0.3849001794597505f);   // column b3: −2, −2√3/9
TYN_CONST vec2 TYN_THETA4_ODD_OFFSET = vec2(0.5f, 0.5f);
TYN_CONST mat2 TYN_THETA4_EVEN = mat2(4.0f, 0.5f,                     // column b2
                                      -4.0f, 0.5f);                   // column b4
// Exact inverses (det of the odd block = 2√3/3, of the even block = 4):
//   (b1, b3) = [ −1/3  √3 ; −3/4  3√3/4 ] · ((x, z) − ½),   (b2, b4) = [ 1/8  1 ; −1/8  1 ] · (y, w)
TYN_CONST mat2 TYN_THETA4_ODD_INVERSE = mat2(-1.0f / 3.0f, -0.75f,
                                             1.7320508075688772f, 1.2990381056766579f);
TYN_CONST mat2 TYN_THETA4_EVEN_INVERSE = mat2(0.125f, -0.125f,
                                              1.0f, 1.0f);

// ---- Θ6*, the quantization transform for 6 moments in 64 and 96 bits (§5.4.3) -----------------
// Θ6* acts on odd and even moments separately, by the blocks A and C below. The paper prints the
// transposes of A and C, each followed by ᵀ; read without the ᵀ they are wrong (the papers'
// README). Orientation derived from the ranges: each channel of one depth must stay in [0, 1];
// with A as below channel x = 2.5 z − 10 z³ + 8 z⁵ + ½ = (T5(z) + 1)/2, while the other
// orientation gives 2.5 z − 1.875 z³ + 1.266 z⁵ + ½, which reaches 2.39 at z = 1. The even
// channels are then x = 4 z² − 4 z⁴ = (1 − T4(z))/2 and y = 9 z² − 24 z⁴ + 16 z⁶ = T3(z)² =
// (1 + T6(z))/2. GLSL/GLM constructors take columns, so they list the paper's printed rows.
//   odd channels  = A · (b1, b3, b5) + (½, ½, ½)            even channels = C · (b2, b4, b6)
//                                                                            + (0, 0, 0.018888946)
//   A = [  2.5         −10           8          ]       C = [  4            −4           0          ]
//       [ −1.87499864    4.20757543 −1.83257679 ]           [  9           −24          16          ]
//       [  1.26583039   −1.47644883  0.71061660 ]           [ −0.57759806    4.61936648 −3.07953907 ]
// With the coefficients rounded to 8 decimals as printed, only even channel z leaves [0, 1]: it
// peaks at 1 + 5.7e-9 (z ≈ 0.966), which a UNORM store clamps (4e-4 of a 16-bit step).
TYN_CONST mat3 TYN_THETA6_ODD = mat3(2.5f, -1.87499864f, 1.26583039f,     // column b1
                                     -10.0f, 4.20757543f, -1.47644883f,   // column b3
                                     8.0f, -1.83257679f, 0.71061660f);    // column b5
TYN_CONST vec3 TYN_THETA6_ODD_OFFSET = vec3(0.5f, 0.5f, 0.5f);
TYN_CONST mat3 TYN_THETA6_EVEN = mat3(4.0f, 9.0f, -0.57759806f,           // column b2
                                      -4.0f, -24.0f, 4.61936648f,         // column b4
                                      0.0f, 16.0f, -3.07953907f);         // column b6
TYN_CONST vec3 TYN_THETA6_EVEN_OFFSET = vec3(0.0f, 0.0f, 0.018888946f);
// Inverses of A and C, from the printed decimals taken as exact rationals (double-checked against
// a double-precision inversion by the unit test MomentConstants.ThetaInversesAreExact).
TYN_CONST mat3 TYN_THETA6_ODD_INVERSE = mat3(
    -0.028777890285483478f, 0.099952358753959802f, 0.25893353915666334f,  // column x
    0.47635550986261954f, 0.84532581412243912f, 0.9077961708209803f,       // column y
    1.5524280933582475f, 1.0547257085142083f, 0.83327335646830814f);      // column z
TYN_CONST mat3 TYN_THETA6_EVEN_INVERSE = mat3(
    1.2530305023071764e-05f, -0.24998746969497693f, -0.37498825283904086f,  // column x
    0.16668494115579588f, 0.16668494115579588f, 0.21876713233355866f,        // column y
    0.86602540116262727f, 0.86602540116262727f, 0.81189881358996308f);      // column z

// ---- Worst-case biasing b' = (1 − α_b) · b + α_b · b* (§2.5, §5.4.3) ---------------------------
// b* is the moment vector of a depth distribution on [−1, 1] that lies farthest from the boundary
// of the valid moment domain (where its Hankel matrix B(b*) stops being positive definite), so
// that rounding errors up to α_b times that distance cannot leave the domain. Stored without b0
// (b*_0 = 1 like every b0); the odd entries are 0 by the mirror symmetry of the domain.
// 4 moments with Θ4* (64 bits): distance measured after Θ4*, where the rounding happens (§2.5).
TYN_CONST vec4 TYN_MOMENTS4_64_B_STAR = vec4(0.0f, 0.628f, 0.0f, 0.628f);
TYN_CONST float TYN_MOMENTS4_64_ALPHA = 6.0e-5f;    // §2.5: "eliminates artifacts reliably"
// 4 moments in float32 (128 bits), no transform (§2.5).
TYN_CONST vec4 TYN_MOMENTS4_128_B_STAR = vec4(0.0f, 0.375f, 0.0f, 0.375f);
TYN_CONST float TYN_MOMENTS4_128_ALPHA = 3.0e-7f;   // §2.5
// 6 moments (§5.4.3), one b* for all three storage variants: (b1, b3, b5) and (b2, b4, b6).
TYN_CONST vec3 TYN_MOMENTS6_B_STAR_ODD = vec3(0.0f, 0.0f, 0.0f);
TYN_CONST vec3 TYN_MOMENTS6_B_STAR_EVEN = vec3(0.5566f, 0.489f, 0.47869382f);
TYN_CONST float TYN_MOMENTS6_64_ALPHA = 4.0e-3f;    // two 3 × 10-bit UNORM textures
TYN_CONST float TYN_MOMENTS6_96_ALPHA = 8.0e-5f;    // six 16-bit UNORM channels
TYN_CONST float TYN_MOMENTS6_192_ALPHA = 5.0e-6f;   // six float32 channels

TYN_END

#endif
