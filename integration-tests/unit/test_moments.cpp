// prefiltered/moments.h and prefiltered/moment_constants.h compiled as C++ from the shader
// source, against long-double computations of the same quantities done another way (Gaussian
// elimination instead of L D Lᵀ, Lagrange weights instead of divided differences, polished
// roots). Every suite prints one line with the worst error it measured.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "prefiltered/moments.h"

namespace {

using namespace tyndall::gpu;
using Real = long double;

constexpr double kFloatEps = std::numeric_limits<float>::epsilon();  // 2^-23

Real power(Real x, size_t j) { return std::pow(x, static_cast<Real>(j)); }

bool finite(vec4 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

std::array<Real, 4> toReal(vec4 v) { return {v.x, v.y, v.z, v.w}; }

// ---- Long-double references ---------------------------------------------------------------------

// Solves the n×n system a x = r in place by Gaussian elimination with partial pivoting.
std::vector<Real> solve(std::vector<std::vector<Real>> a, std::vector<Real> r) {
  const size_t n = r.size();
  for (size_t c = 0; c < n; ++c) {
    size_t pivot = c;
    for (size_t i = c + 1; i < n; ++i) {
      if (std::fabs(a[i][c]) > std::fabs(a[pivot][c])) pivot = i;
    }
    std::swap(a[c], a[pivot]);
    std::swap(r[c], r[pivot]);
    for (size_t i = c + 1; i < n; ++i) {
      const Real f = a[i][c] / a[c][c];
      for (size_t k = c; k < n; ++k) a[i][k] -= f * a[c][k];
      r[i] -= f * r[c];
    }
  }
  std::vector<Real> x(n);
  for (size_t i = n; i-- > 0;) {
    Real s = r[i];
    for (size_t k = i + 1; k < n; ++k) s -= a[i][k] * x[k];
    x[i] = s / a[i][i];
  }
  return x;
}

Real evalPoly(const std::vector<Real>& q, Real z) {
  Real s = 0;
  for (size_t j = q.size(); j-- > 0;) s = s * z + q[j];
  return s;
}

Real evalDerivative(const std::vector<Real>& q, Real z) {
  Real s = 0;
  for (size_t j = q.size(); j-- > 1;) s = s * z + static_cast<Real>(j) * q[j];
  return s;
}

// Newton steps on q in long double, kept while they reduce |q|.
Real polish(const std::vector<Real>& q, Real z) {
  for (int i = 0; i < 8; ++i) {
    const Real d = evalDerivative(q, z);
    if (d == 0) break;
    const Real next = z - evalPoly(q, z) / d;
    if (!(std::fabs(evalPoly(q, next)) < std::fabs(evalPoly(q, z)))) break;
    z = next;
  }
  return z;
}

// Real roots of q (degree 2 or 3, all roots real), finite ones only: a vanishing leading
// coefficient drops the root at infinity. Closed forms in long double, then polished.
std::vector<Real> realRoots(std::vector<Real> q) {
  while (q.size() > 1 && q.back() == 0) q.pop_back();
  std::vector<Real> roots;
  if (q.size() == 2) {
    roots.push_back(-q[0] / q[1]);
  } else if (q.size() == 3) {
    const Real disc = std::max<Real>(q[1] * q[1] - 4 * q[0] * q[2], 0);
    const Real t = -0.5L * (q[1] + std::copysign(std::sqrt(disc), q[1]));
    roots = {q[0] / t, t / q[2]};
  } else if (q.size() == 4) {
    const Real a = q[2] / q[3];
    const Real b = q[1] / q[3];
    const Real c = q[0] / q[3];
    const Real p = b - a * a / 3;
    const Real r = 2 * a * a * a / 27 - a * b / 3 + c;
    const Real m = 2 * std::sqrt(std::max<Real>(-p / 3, 0));
    Real arg = m == 0 ? 0 : 3 * r / (p * m);
    arg = std::clamp<Real>(arg, -1, 1);
    const Real phi = std::acos(arg) / 3;
    for (int k = 0; k < 3; ++k) {
      roots.push_back(m * std::cos(phi - 2 * static_cast<Real>(M_PI) * k / 3) - a / 3);
    }
  }
  for (Real& z : roots) z = polish(q, z);
  std::sort(roots.begin(), roots.end());
  return roots;
}

struct Bounds {
  Real lower;
  Real upper;
};

// Algorithm 1 done literally: solve B(b) q = v(z_f), roots of q, Vandermonde weights by Lagrange
// interpolation, sum. b = (b0, …, bm), m = 4 or 6.
Bounds referenceBounds(const std::vector<Real>& b, Real zf) {
  const size_t n = (b.size() - 1) / 2;
  std::vector<std::vector<Real>> hankel(n + 1, std::vector<Real>(n + 1));
  std::vector<Real> v(n + 1);
  for (size_t j = 0; j <= n; ++j) {
    for (size_t k = 0; k <= n; ++k) hankel[j][k] = b[j + k];
    v[j] = power(zf, j);
  }
  const std::vector<Real> q = solve(hankel, v);
  std::vector<Real> nodes = realRoots(q);
  nodes.insert(nodes.begin(), zf);
  // w_l = E_b[Π_{k≠l} (z − z_k)] / Π_{k≠l} (z_l − z_k)
  Bounds out{0, 0};
  Real w0 = 0;
  for (size_t l = 0; l < nodes.size(); ++l) {
    std::vector<Real> poly{1};
    Real denom = 1;
    for (size_t k = 0; k < nodes.size(); ++k) {
      if (k == l) continue;
      std::vector<Real> next(poly.size() + 1, 0);
      for (size_t j = 0; j < poly.size(); ++j) {
        next[j + 1] += poly[j];
        next[j] -= nodes[k] * poly[j];
      }
      poly = next;
      denom *= nodes[l] - nodes[k];
    }
    Real num = 0;
    for (size_t j = 0; j < poly.size(); ++j) num += poly[j] * b[j];
    const Real weight = num / denom;
    if (l == 0) w0 = weight;
    else if (nodes[l] < zf) out.lower += weight;
  }
  out.upper = out.lower + w0;
  out.lower = std::clamp<Real>(out.lower, 0, 1);
  out.upper = std::clamp<Real>(out.upper, 0, 1);
  return out;
}

// ---- Depth distributions ------------------------------------------------------------------------

struct Atom {
  float z;
  float w;
};

// 1–3 surfaces; depths uniform in [−1, 1], a quarter of them clamped to exactly ±1 (§2.5's worst
// case); weights uniform, normalised, rounded to float like a filter's weights.
std::vector<Atom> randomDistribution(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int count = 1 + static_cast<int>(rng() % 3);
  std::vector<double> w(static_cast<size_t>(count));
  double sum = 0;
  for (double& x : w) sum += (x = 0.02 + u(rng));
  std::vector<Atom> atoms;
  for (int i = 0; i < count; ++i) {
    double z = 2.0 * u(rng) - 1.0;
    const double pick = u(rng);
    if (pick < 0.125) z = -1.0;
    else if (pick < 0.25) z = 1.0;
    atoms.push_back({static_cast<float>(z), static_cast<float>(w[static_cast<size_t>(i)] / sum)});
  }
  return atoms;
}

// The fragment depth: uniform, or exactly on a surface, or at ±1.
float randomFragmentDepth(std::mt19937& rng, const std::vector<Atom>& atoms) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const unsigned pick = rng() % 8;
  if (pick == 0) return atoms[rng() % atoms.size()].z;
  if (pick == 1) return (rng() % 2) ? 1.0f : -1.0f;
  return u(rng);
}

// Z(z < z_f), the shadow intensity a percentage-closer filter would give.
double trueShadow(const std::vector<Atom>& atoms, float zf) {
  double sum = 0;
  double total = 0;
  for (const Atom& a : atoms) {
    total += a.w;
    if (a.z < zf) sum += a.w;
  }
  return sum / total;
}

// What a UNORM texel of `bits` bits gives back for a written value (clamp, round to nearest).
float storeUnorm(float x, int bits) {
  const double scale = std::ldexp(1.0, bits) - 1.0;
  const double k = std::nearbyint(std::clamp(static_cast<double>(x), 0.0, 1.0) * scale);
  return static_cast<float>(k / scale);
}


// Smallest eigenvalue of a small symmetric matrix (cyclic Jacobi rotations in long double).
Real smallestEigenvalue(std::vector<std::vector<Real>> a) {
  const size_t n = a.size();
  for (int sweep = 0; sweep < 64; ++sweep) {
    Real off = 0;
    for (size_t p = 0; p < n; ++p) {
      for (size_t r = p + 1; r < n; ++r) off += a[p][r] * a[p][r];
    }
    if (off < 1e-40L) break;
    for (size_t p = 0; p < n; ++p) {
      for (size_t r = p + 1; r < n; ++r) {
        if (a[p][r] == 0) continue;
        const Real theta = (a[r][r] - a[p][p]) / (2 * a[p][r]);
        const Real t =
            std::copysign(1.0L, theta) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const Real c = 1 / std::sqrt(t * t + 1);
        const Real s = t * c;
        for (size_t k = 0; k < n; ++k) {  // columns p, r
          const Real akp = a[k][p];
          const Real akr = a[k][r];
          a[k][p] = c * akp - s * akr;
          a[k][r] = s * akp + c * akr;
        }
        for (size_t k = 0; k < n; ++k) {  // rows p, r
          const Real apk = a[p][k];
          const Real ark = a[r][k];
          a[p][k] = c * apk - s * ark;
          a[r][k] = s * apk + c * ark;
        }
      }
    }
  }
  Real lowest = a[0][0];
  for (size_t k = 1; k < n; ++k) lowest = std::min(lowest, a[k][k]);
  return lowest;
}

// B(b) = (b_{j+k}) for b = (b0, …, bm).
std::vector<std::vector<Real>> hankel(const std::vector<Real>& b) {
  const size_t n = (b.size() - 1) / 2;
  std::vector<std::vector<Real>> h(n + 1, std::vector<Real>(n + 1));
  for (size_t j = 0; j <= n; ++j) {
    for (size_t k = 0; k <= n; ++k) h[j][k] = b[j + k];
  }
  return h;
}

// (b_{j+k} − b_{j+k+2}): positive semi-definite together with B(b) exactly when b is the moment
// vector of a distribution on [−1, 1] (the truncated Hausdorff moment problem).
std::vector<std::vector<Real>> localizing(const std::vector<Real>& b) {
  const size_t n = (b.size() - 1) / 2;
  std::vector<std::vector<Real>> h(n, std::vector<Real>(n));
  for (size_t j = 0; j < n; ++j) {
    for (size_t k = 0; k < n; ++k) h[j][k] = b[j + k] - b[j + k + 2];
  }
  return h;
}

std::vector<Real> withB0(vec4 b) { return {1, b.x, b.y, b.z, b.w}; }
std::vector<Real> withB0(vec3 odd, vec3 even) {
  return {1, odd.x, even.x, odd.y, even.y, odd.z, even.z};
}

// ---- Storage variants run end to end ------------------------------------------------------------

struct Variant {
  const char* name;
  int moments;     // 4 or 6
  int unorm_bits;  // 0: float32 storage, canonical moments
  float alpha;
};

const Variant kVariants4[] = {
    {"4 moments,  64 bits (RGBA16_UNORM, Theta4*)", 4, 16, TYN_MOMENTS4_64_ALPHA},
    {"4 moments, 128 bits (RGBA32F)", 4, 0, TYN_MOMENTS4_128_ALPHA},
};
const Variant kVariants6[] = {
    {"6 moments,  64 bits (2 x RGB10_UNORM, Theta6*)", 6, 10, TYN_MOMENTS6_64_ALPHA},
    {"6 moments,  96 bits (6 x UNORM16, Theta6*)", 6, 16, TYN_MOMENTS6_96_ALPHA},
    {"6 moments, 192 bits (6 x float32)", 6, 0, TYN_MOMENTS6_192_ALPHA},
};

struct Evaluated {
  std::vector<Real> biased;  // b0..bm that the bounds were computed from
  vec2 bounds;               // the header's float bounds
};

// Moments of the distribution in float (as a filter or prefix sum would sum them) → written to
// the texel(s) → read back → dequantized → biased → bounds.
Evaluated evaluate(const Variant& v, const std::vector<Atom>& atoms, float zf) {
  if (v.moments == 4) {
    vec4 b(0.0f);
    for (const Atom& a : atoms) b += a.w * tyn_moments4(a.z);
    vec4 read;
    if (v.unorm_bits != 0) {
      const vec4 stored = tyn_quantize_moments4_64(b);
      for (int c = 0; c < 4; ++c) read[c] = storeUnorm(stored[c], v.unorm_bits);
      read = tyn_dequantize_moments4_64(read);
    } else {
      read = tyn_dequantize_moments4_128(tyn_quantize_moments4_128(b));
    }
    const vec4 b_star = v.unorm_bits != 0 ? TYN_MOMENTS4_64_B_STAR : TYN_MOMENTS4_128_B_STAR;
    const vec4 biased = tyn_bias_moments(read, b_star, v.alpha);
    return {withB0(biased), tyn_moments4_bounds(biased, zf)};
  }
  vec3 odd(0.0f);
  vec3 even(0.0f);
  for (const Atom& a : atoms) {
    odd += a.w * tyn_moments6_odd(a.z);
    even += a.w * tyn_moments6_even(a.z);
  }
  if (v.unorm_bits != 0) {
    const vec3 stored_odd = tyn_quantize_moments6_odd(odd);
    const vec3 stored_even = tyn_quantize_moments6_even(even);
    for (int c = 0; c < 3; ++c) {
      odd[c] = storeUnorm(stored_odd[c], v.unorm_bits);
      even[c] = storeUnorm(stored_even[c], v.unorm_bits);
    }
    odd = tyn_dequantize_moments6_odd(odd);
    even = tyn_dequantize_moments6_even(even);
  }
  odd = tyn_bias_moments(odd, TYN_MOMENTS6_B_STAR_ODD, v.alpha);
  even = tyn_bias_moments(even, TYN_MOMENTS6_B_STAR_EVEN, v.alpha);
  return {withB0(odd, even), tyn_moments6_bounds(odd, even, zf)};
}

// How much the exact bounds move when every moment b_j moves by up to half an ulp of its size,
// u · E|z|^j (u = 2⁻²⁴): the float32 rounding that computing or storing the moments incurs
// anyway. Near the boundary of the moment domain the bounds are ill-conditioned functions of b,
// and no float32 pipeline can resolve them better than this. 32 random perturbations.
double roundingSensitivity(const std::vector<Real>& b, const std::vector<Atom>& atoms, float zf,
                           const Bounds& at) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> size(b.size(), 0.0);
  for (size_t j = 1; j < b.size(); ++j) {
    for (const Atom& a : atoms) size[j] += a.w * std::pow(std::fabs(static_cast<double>(a.z)), j);
  }
  double s = 0;
  for (int k = 0; k < 32; ++k) {
    std::vector<Real> p = b;
    for (size_t j = 1; j < p.size(); ++j) p[j] += 0.5 * kFloatEps * size[j] * u(rng);
    const Bounds moved = referenceBounds(p, zf);
    s = std::max({s, static_cast<double>(std::fabs(moved.lower - at.lower)),
                  static_cast<double>(std::fabs(moved.upper - at.upper))});
  }
  return s;
}

// The bounds property, per variant. With P = Z(z < z_f) of the true distribution:
//   - bias: the biased moments are those of (1 − α) Z + α Z_e, where Z_e has the moments
//     b* + (rounding)/α, a valid distribution as long as the rounding stays within α times the
//     distance of b* to the domain boundary (what α_b is chosen for). Bounds hold for every
//     distribution with these moments, so lower ≤ (1 − α) P + α · 1 and upper ≥ (1 − α) P:
//     lower − P ≤ α (1 − P) and P − upper ≤ α P. Checked on the exact bounds of the moments
//     the shader sees (long double).
//   - float32: moments computed or stored in float are only known to their rounding; where the
//     bounds are ill-conditioned this moves them by the sensitivity s (roundingSensitivity),
//     and the float evaluation adds a few ε. So the exact bounds get K s of slack and the
//     header's float bounds K (s + ε). K = 8: the worst |float − exact| / (s + ε) printed below
//     is 2.2 (up to 4.1 with other seeds while developing), i.e. the header is as accurate as
//     float32 data allow; the worst excess beyond the α terms is 0.94 (s + ε).
//   Only the float-storage variants need the s terms: their α_b is at float32 resolution (see
//   moment_constants.h); the quantized ones stay within α_b outright.
constexpr double kConditioningSlack = 8.0;

struct VariantSummary {
  double exact_over_alpha = 0;     // worst max(lower − P, P − upper) / α of the exact bounds
  double float_over_alpha = 0;     // the same for the header's float bounds
  double float_vs_exact = 0;       // worst |float − exact|
  double float_vs_exact_cond = 0;  // worst |float − exact| / (s + ε) where it exceeded 8 ε
  double excess_cond = 0;          // worst excess beyond the α terms / (s + ε)
  int failures = 0;
};

VariantSummary checkVariant(const Variant& v, int trials, unsigned seed) {
  std::mt19937 rng(seed);
  VariantSummary out;
  for (int trial = 0; trial < trials; ++trial) {
    const std::vector<Atom> atoms = randomDistribution(rng);
    const float zf = randomFragmentDepth(rng, atoms);
    const double p = trueShadow(atoms, zf);
    const Evaluated e = evaluate(v, atoms, zf);
    const Bounds exact = referenceBounds(e.biased, zf);
    const double lower = e.bounds.x;
    const double upper = e.bounds.y;
    const bool finite = std::isfinite(lower) && std::isfinite(upper);
    const double exact_excess = std::max(static_cast<double>(exact.lower) - p - v.alpha * (1 - p),
                                         p - static_cast<double>(exact.upper) - v.alpha * p);
    const double float_excess =
        std::max(lower - p - v.alpha * (1 - p), p - upper - v.alpha * p);
    const double deviation = std::max(std::fabs(lower - static_cast<double>(exact.lower)),
                                      std::fabs(upper - static_cast<double>(exact.upper)));
    out.exact_over_alpha =
        std::max({out.exact_over_alpha, (static_cast<double>(exact.lower) - p) / v.alpha,
                  (p - static_cast<double>(exact.upper)) / v.alpha});
    out.float_over_alpha =
        std::max({out.float_over_alpha, (lower - p) / v.alpha, (p - upper) / v.alpha});
    out.float_vs_exact = std::max(out.float_vs_exact, deviation);
    // The sensitivity costs 32 reference solves: only where a check could need it.
    double s = 0;
    if (exact_excess > 0 || float_excess > 0 || deviation > kConditioningSlack * kFloatEps) {
      s = roundingSensitivity(e.biased, atoms, zf, exact);
    }
    if (s > 0) {
      out.float_vs_exact_cond = std::max(out.float_vs_exact_cond, deviation / (s + kFloatEps));
      out.excess_cond = std::max(
          {out.excess_cond, exact_excess / (s + kFloatEps), float_excess / (s + kFloatEps)});
    }
    const bool ok = finite && exact_excess <= kConditioningSlack * s &&
                    float_excess <= kConditioningSlack * (s + kFloatEps) &&
                    deviation <= kConditioningSlack * (s + kFloatEps);
    if (!ok && ++out.failures <= 5) {
      std::string depths;
      for (const Atom& a : atoms) {
        depths += " (" + std::to_string(a.z) + ", " + std::to_string(a.w) + ")";
      }
      ADD_FAILURE() << v.name << ": z_f " << zf << " P " << p << " float [" << lower << ", "
                    << upper << "] exact [" << static_cast<double>(exact.lower) << ", "
                    << static_cast<double>(exact.upper) << "] s " << s << " alpha " << v.alpha
                    << " depths (z, w):" << depths;
    }
  }
  return out;
}

void printSummary(const Variant& v, const VariantSummary& s) {
  std::printf("[ moments  ] %s, alpha_b %.0e: bounds beyond P by at most %.3g alpha_b (exact "
              "maths on the stored moments), %.3g alpha_b (header, float); |float - exact| "
              "%.3g, at most %.3g (s + eps); beyond alpha_b at most %.3g (s + eps)\n",
              v.name, static_cast<double>(v.alpha), s.exact_over_alpha, s.float_over_alpha,
              s.float_vs_exact, s.float_vs_exact_cond, s.excess_cond);
}

// ---- Constants ----------------------------------------------------------------------------------

// Long-double copies of a GLM matrix's entries, row-major.
template <int N>
std::vector<std::vector<Real>> rows(const mat<N, N, float, defaultp>& m) {
  std::vector<std::vector<Real>> r(N, std::vector<Real>(N));
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) r[static_cast<size_t>(i)][static_cast<size_t>(j)] = m[j][i];
  }
  return r;
}

Real infNorm(const std::vector<std::vector<Real>>& m) {
  Real n = 0;
  for (const auto& row : m) {
    Real s = 0;
    for (Real x : row) s += std::fabs(x);
    n = std::max(n, s);
  }
  return n;
}

// |M · M⁻¹ − I| with both as stored (float), in long double, and the condition number ‖M‖‖M⁻¹‖.
template <int N>
void checkInverse(const char* name, const mat<N, N, float, defaultp>& m,
                  const mat<N, N, float, defaultp>& inverse, double& worst) {
  const auto a = rows(m);
  const auto b = rows(inverse);
  const Real condition = infNorm(a) * infNorm(b);
  Real error = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t j = 0; j < a.size(); ++j) {
      Real s = i == j ? -1 : 0;
      for (size_t k = 0; k < a.size(); ++k) s += a[i][k] * b[k][j];
      error = std::max(error, std::fabs(s));
    }
  }
  // Rounding each entry of M⁻¹ to float (relative u) gives |M M⁻¹ − I| ≤ u ‖M‖ ‖M⁻¹‖.
  EXPECT_LE(error, 0.5 * kFloatEps * condition) << name;
  worst = std::max(worst, static_cast<double>(error / (0.5 * kFloatEps * condition)));
}

TEST(MomentConstants, QuantizationInversesAreExactToFloatPrecision) {
  double worst = 0;
  checkInverse("Theta4* odd", TYN_THETA4_ODD, TYN_THETA4_ODD_INVERSE, worst);
  checkInverse("Theta4* even", TYN_THETA4_EVEN, TYN_THETA4_EVEN_INVERSE, worst);
  checkInverse("Theta6* odd", TYN_THETA6_ODD, TYN_THETA6_ODD_INVERSE, worst);
  checkInverse("Theta6* even", TYN_THETA6_EVEN, TYN_THETA6_EVEN_INVERSE, worst);
  std::printf("[ moments  ] |Theta Theta^-1 - I| worst %.3g of u cond(Theta)\n", worst);
}

// The orientation of Θ6* (printed transposed in the paper's text): for one depth the channels are
// Chebyshev polynomials shifted into [0, 1]. Likewise for Θ4*. Evaluated in long double from the
// stored float constants, so the tolerance is the rounding of the constants (u · Σ|coefficients|).
TEST(MomentConstants, ChannelsOfOneDepthAreShiftedChebyshevPolynomials) {
  double worst = 0;
  for (int i = 0; i <= 2000; ++i) {
    const Real z = -1 + static_cast<Real>(i) / 1000;
    const Real t3 = 4 * z * z * z - 3 * z;
    const Real t4 = 8 * z * z * z * z - 8 * z * z + 1;
    const Real t5 = 16 * std::pow(z, 5.0L) - 20 * z * z * z + 5 * z;
    const Real t6 = 2 * t3 * t3 - 1;
    const auto a = rows(TYN_THETA6_ODD);
    const auto c = rows(TYN_THETA6_EVEN);
    const auto p = rows(TYN_THETA4_ODD);
    const auto e = rows(TYN_THETA4_EVEN);
    const Real odd6 = a[0][0] * z + a[0][1] * z * z * z + a[0][2] * std::pow(z, 5.0L) + 0.5L;
    const Real even6x = c[0][0] * z * z + c[0][1] * std::pow(z, 4.0L) + c[0][2] * std::pow(z, 6.0L);
    const Real even6y = c[1][0] * z * z + c[1][1] * std::pow(z, 4.0L) + c[1][2] * std::pow(z, 6.0L);
    const Real odd4 = p[0][0] * z + p[0][1] * z * z * z + 0.5L;
    const Real even4 = e[0][0] * z * z + e[0][1] * std::pow(z, 4.0L);
    const Real errors[] = {odd6 - (t5 + 1) / 2, even6x - (1 - t4) / 2, even6y - (1 + t6) / 2,
                           odd4 - (1 - t3) / 2, even4 - (1 - t4) / 2};
    for (Real err : errors) {
      EXPECT_LE(std::fabs(err), 0.5 * kFloatEps * 49) << "z " << static_cast<double>(z);
      worst = std::max(worst, static_cast<double>(std::fabs(err)));
    }
  }
  std::printf("[ moments  ] quantized channels vs (T5+1)/2, (1-T4)/2, (1+T6)/2, (1-T3)/2: "
              "worst %.3g\n", worst);
}

// Every channel of Θ4* and Θ6* of one depth in [−1, 1] lies in [0, 1] (hence so does any convex
// combination: the transforms are affine). Two evaluations:
//   - long double from the float constants: within u · Σ_j |M_kj| (the constants' rounding to
//     float) plus 1e-8 (the paper prints Θ6* to 8 decimals: channel z of the even block peaks at
//     1 + 5.7e-9);
//   - the header in float: within 5 u · Σ_j |M_kj| more, the error bound of a 3-term dot product
//     of rounded inputs. A UNORM store clamps either excess.
TEST(MomentConstants, QuantizedChannelsStayInUnitRange) {
  struct Block {
    const char* name;
    std::vector<std::vector<Real>> m;
    std::array<Real, 3> offset;
  };
  const Block blocks[] = {
      {"Theta4* odd", rows(TYN_THETA4_ODD), {0.5L, 0.5L, 0}},
      {"Theta4* even", rows(TYN_THETA4_EVEN), {0, 0, 0}},
      {"Theta6* odd", rows(TYN_THETA6_ODD), {0.5L, 0.5L, 0.5L}},
      {"Theta6* even", rows(TYN_THETA6_EVEN), {0, 0, TYN_THETA6_EVEN_OFFSET.z}},
  };
  double worst_exact = 0;
  double worst_float = 0;
  const int n = 200000;
  for (int i = 0; i <= n; ++i) {
    const float z = i == n ? 1.0f : -1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(n);
    const vec4 q4 = tyn_quantize_moments4_64(tyn_moments4(z));
    const vec3 q6o = tyn_quantize_moments6_odd(tyn_moments6_odd(z));
    const vec3 q6e = tyn_quantize_moments6_even(tyn_moments6_even(z));
    const float got[4][3] = {{q4.x, q4.z, 0}, {q4.y, q4.w, 0}, {q6o.x, q6o.y, q6o.z},
                             {q6e.x, q6e.y, q6e.z}};
    for (int blk = 0; blk < 4; ++blk) {
      const Block& b = blocks[blk];
      const bool odd = blk % 2 == 0;
      for (size_t k = 0; k < b.m.size(); ++k) {
        Real exact = b.offset[k];
        Real size = 0;
        for (size_t j = 0; j < b.m.size(); ++j) {
          exact += b.m[k][j] * power(z, odd ? 2 * j + 1 : 2 * j + 2);
          size += std::fabs(b.m[k][j]);
        }
        const Real tol_exact = 0.5L * kFloatEps * size + 1e-8L;
        const Real tol_float = tol_exact + 2.5L * kFloatEps * size;
        const Real out_exact = std::max(-exact, exact - 1);
        const Real out_float = std::max<Real>(-got[blk][k], got[blk][k] - 1.0L);
        EXPECT_LE(out_exact, tol_exact) << b.name << " channel " << k << " z " << z;
        EXPECT_LE(out_float, tol_float) << b.name << " channel " << k << " z " << z;
        worst_exact = std::max(worst_exact, static_cast<double>(out_exact));
        worst_float = std::max(worst_float, static_cast<double>(out_float));
      }
    }
  }
  // Convex combinations of 1–3 depths, through the header.
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::vector<Atom> atoms = randomDistribution(rng);
    vec4 b4(0.0f);
    vec3 odd(0.0f);
    vec3 even(0.0f);
    for (const Atom& a : atoms) {
      b4 += a.w * tyn_moments4(a.z);
      odd += a.w * tyn_moments6_odd(a.z);
      even += a.w * tyn_moments6_even(a.z);
    }
    const vec4 q4 = tyn_quantize_moments4_64(b4);
    const vec3 qo = tyn_quantize_moments6_odd(odd);
    const vec3 qe = tyn_quantize_moments6_even(even);
    const float all[] = {q4.x, q4.y, q4.z, q4.w, qo.x, qo.y, qo.z, qe.x, qe.y, qe.z};
    for (float x : all) {
      // Largest Σ|M_kj| is 49 (Θ6* even, channel y).
      EXPECT_GE(x, -3.0 * kFloatEps * 49);
      EXPECT_LE(x, 1.0 + 3.0 * kFloatEps * 49);
      worst_float = std::max({worst_float, static_cast<double>(-x), static_cast<double>(x) - 1.0});
    }
  }
  std::printf("[ moments  ] quantized channels outside [0, 1]: exact %.3g, float %.3g\n",
              worst_exact, worst_float);
}

// dequantize(quantize(b)) = b up to float rounding amplified by the transforms' condition number.
TEST(MomentConstants, QuantizationRoundTrip) {
  const double cond4 = static_cast<double>(
      std::max(infNorm(rows(TYN_THETA4_ODD)) * infNorm(rows(TYN_THETA4_ODD_INVERSE)),
               infNorm(rows(TYN_THETA4_EVEN)) * infNorm(rows(TYN_THETA4_EVEN_INVERSE))));
  const double cond6 = static_cast<double>(
      std::max(infNorm(rows(TYN_THETA6_ODD)) * infNorm(rows(TYN_THETA6_ODD_INVERSE)),
               infNorm(rows(TYN_THETA6_EVEN)) * infNorm(rows(TYN_THETA6_EVEN_INVERSE))));
  std::mt19937 rng(4);
  double worst4 = 0;
  double worst6 = 0;
  for (int trial = 0; trial < 50000; ++trial) {
    const std::vector<Atom> atoms = randomDistribution(rng);
    vec4 b4(0.0f);
    vec3 odd(0.0f);
    vec3 even(0.0f);
    for (const Atom& a : atoms) {
      b4 += a.w * tyn_moments4(a.z);
      odd += a.w * tyn_moments6_odd(a.z);
      even += a.w * tyn_moments6_even(a.z);
    }
    const vec4 r4 = tyn_dequantize_moments4_64(tyn_quantize_moments4_64(b4));
    const vec3 ro = tyn_dequantize_moments6_odd(tyn_quantize_moments6_odd(odd));
    const vec3 re = tyn_dequantize_moments6_even(tyn_quantize_moments6_even(even));
    EXPECT_EQ(tyn_dequantize_moments4_128(tyn_quantize_moments4_128(b4)), b4);
    for (int c = 0; c < 4; ++c) worst4 = std::max(worst4, std::fabs(double{r4[c]} - b4[c]));
    for (int c = 0; c < 3; ++c) {
      worst6 = std::max({worst6, static_cast<double>(std::fabs(ro[c] - odd[c])),
                         static_cast<double>(std::fabs(re[c] - even[c]))});
    }
  }
  // Forward and inverse each add at most ~3 u per term (3-term dot products of rounded inputs,
  // all moments ≤ 1), amplified by cond(Θ): 4 ε cond bounds the round trip.
  EXPECT_LE(worst4, 4 * kFloatEps * cond4);
  EXPECT_LE(worst6, 4 * kFloatEps * cond6);
  std::printf("[ moments  ] round trip worst: 4 moments %.3g (%.2f eps, cond %.1f), "
              "6 moments %.3g (%.2f eps, cond %.1f)\n",
              worst4, worst4 / kFloatEps, cond4, worst6, worst6 / kFloatEps, cond6);
}

// The defining property of b*: a moment vector of a distribution on [−1, 1] (B(b*) and the
// localizing matrix positive semi-definite) that is strictly inside the valid domain (B(b*)
// positive definite). The original b* = (1, 0, 1, 0, 1) of Peters and Klein 2015 fails the
// second: δ_{−1}/2 + δ_{1}/2 lies on the boundary (§2.5).
TEST(MomentConstants, BiasVectorsLieInsideTheValidMomentDomain) {
  struct Case {
    const char* name;
    std::vector<Real> b;
  };
  const Case cases[] = {
      {"4 moments, 64 bits", withB0(TYN_MOMENTS4_64_B_STAR)},
      {"4 moments, 128 bits", withB0(TYN_MOMENTS4_128_B_STAR)},
      {"6 moments", withB0(TYN_MOMENTS6_B_STAR_ODD, TYN_MOMENTS6_B_STAR_EVEN)},
  };
  for (const Case& c : cases) {
    const Real inside = smallestEigenvalue(hankel(c.b));
    const Real on_interval = smallestEigenvalue(localizing(c.b));
    // Positive definite with a margin well above float resolution.
    EXPECT_GT(inside, 1e-2L) << c.name;
    // b* rounded to float moves the localizing matrix's entries by u (|b_j| + |b_{j+2}|) each;
    // the 6-moment b* sits exactly on the [−1, 1] boundary (b6 = 0.47869382 makes the
    // localizing matrix singular), so only that rounding may show.
    EXPECT_GE(on_interval, -3 * kFloatEps) << c.name;
    std::printf("[ moments  ] b* %s: smallest eigenvalue of B(b*) %.4g, of the [-1,1] "
                "localizing matrix %.3g\n",
                c.name, static_cast<double>(inside), static_cast<double>(on_interval));
  }
  EXPECT_LT(smallestEigenvalue(hankel({1, 0, 1, 0, 1})), 1e-12L);
}

// ---- Signed depth, moments, bias ----------------------------------------------------------------

TEST(MomentBasics, SignedDepthAndMomentsOfOneDepth) {
  EXPECT_EQ(tyn_signed_depth(0.0f), -1.0f);
  EXPECT_EQ(tyn_signed_depth(0.5f), 0.0f);
  EXPECT_EQ(tyn_signed_depth(1.0f), 1.0f);
  double worst = 0;
  for (int i = 0; i <= 1000; ++i) {
    const float z = -1.0f + 0.002f * static_cast<float>(i);
    const vec4 b4 = tyn_moments4(z);
    const vec3 odd = tyn_moments6_odd(z);
    const vec3 even = tyn_moments6_even(z);
    const float got[] = {b4.x, b4.y, b4.z, b4.w, odd.x, even.x, odd.y, even.y, odd.z, even.z};
    const int exponent[] = {1, 2, 3, 4, 1, 2, 3, 4, 5, 6};
    for (int k = 0; k < 10; ++k) {
      const double exact = std::pow(static_cast<double>(z), exponent[k]);
      // Each multiplication rounds once: at most (j − 1) u relative for z^j.
      EXPECT_LE(std::fabs(got[k] - exact), 0.5 * kFloatEps * (exponent[k] - 1) * std::fabs(exact));
      worst = std::max(worst, std::fabs(got[k] - exact));
    }
  }
  // Biasing is the affine blend toward b*: α = 1 gives b*, α = 0 leaves b.
  const vec4 b = tyn_moments4(0.3f);
  EXPECT_EQ(tyn_bias_moments(b, TYN_MOMENTS4_64_B_STAR, 1.0f), TYN_MOMENTS4_64_B_STAR);
  EXPECT_EQ(tyn_bias_moments(b, TYN_MOMENTS4_64_B_STAR, 0.0f), b);
  const vec4 biased = tyn_bias_moments(b, TYN_MOMENTS4_64_B_STAR, 0.25f);
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(biased[c], 0.75 * b[c] + 0.25 * TYN_MOMENTS4_64_B_STAR[c], 1e-7);
  }
  std::printf("[ moments  ] moments of one depth vs double: worst %.3g\n", worst);
}

// ---- Bounds (Algorithm 1) -----------------------------------------------------------------------

TEST(MomentBounds, FourMomentsEveryStorageVariant) {
  for (const Variant& v : kVariants4) printSummary(v, checkVariant(v, 50000, 11));
}

TEST(MomentBounds, SixMomentsEveryStorageVariant) {
  for (const Variant& v : kVariants6) printSummary(v, checkVariant(v, 50000, 12));
}

// The boundary of the valid domain before biasing: one depth (zero variance), two depths, depths
// at ±1, fragment depth on a surface and at ±1. No NaN/Inf, and the bounds property as above.
TEST(MomentBounds, BoundaryOfTheMomentDomain) {
  const float depths[] = {-1.0f, -0.999f, -0.5f, 0.0f, 1e-3f, 0.25f, 0.7071f, 0.999f, 1.0f};
  const float weights[] = {0.5f, 0.01f, 0.99f};
  std::vector<std::vector<Atom>> cases;
  for (float a : depths) {
    cases.push_back({{a, 1.0f}});
    for (float b : depths) {
      for (float w : weights) {
        if (a < b) cases.push_back({{a, w}, {b, 1.0f - w}});
      }
    }
  }
  for (const Variant* variants : {kVariants4, kVariants6}) {
    const size_t n = variants == kVariants4 ? std::size(kVariants4) : std::size(kVariants6);
    for (size_t vi = 0; vi < n; ++vi) {
      const Variant& v = variants[vi];
      double worst = 0;
      int count = 0;
      for (const std::vector<Atom>& atoms : cases) {
        std::vector<float> fragments = {-1.0f, -0.3f, 0.0f, 0.6f, 1.0f};
        for (const Atom& a : atoms) {
          fragments.push_back(a.z);
          fragments.push_back(std::nextafter(a.z, 2.0f));
          fragments.push_back(std::nextafter(a.z, -2.0f));
        }
        for (float zf : fragments) {
          const Evaluated e = evaluate(v, atoms, zf);
          ASSERT_TRUE(std::isfinite(e.bounds.x) && std::isfinite(e.bounds.y))
              << v.name << " z_f " << zf << " first depth " << atoms[0].z;
          const double p = trueShadow(atoms, zf);
          const Bounds exact = referenceBounds(e.biased, zf);
          const double excess = std::max(e.bounds.x - p - v.alpha * (1 - p),
                                         p - e.bounds.y - v.alpha * p);
          if (excess > 0) {
            const double s = roundingSensitivity(e.biased, atoms, zf, exact);
            EXPECT_LE(excess, kConditioningSlack * (s + kFloatEps))
                << v.name << " z_f " << zf << " P " << p << " bounds " << e.bounds.x << " "
                << e.bounds.y;
          }
          worst = std::max({worst, (e.bounds.x - p) / v.alpha, (p - e.bounds.y) / v.alpha});
          ++count;
        }
      }
      std::printf("[ moments  ] %s: %d boundary cases, all finite, bounds beyond P by at most "
                  "%.3g alpha_b\n", v.name, count, worst);
    }
  }
}

// ---- Adaptive overestimation (§5.3.1) -----------------------------------------------------------

TEST(MomentBounds, AdaptiveOverestimationBlendsTheBounds) {
  const vec3 to_light = normalize(vec3(0.3f, 0.8f, -0.52f));
  EXPECT_NEAR(tyn_adaptive_overestimation(to_light, -to_light), 0.0, 1e-7);  // into the light
  EXPECT_NEAR(tyn_adaptive_overestimation(to_light, to_light), 1.0, 1e-7);   // away from it
  const vec3 across = normalize(cross(to_light, vec3(0.0f, 0.0f, 1.0f)));
  EXPECT_NEAR(tyn_adaptive_overestimation(to_light, across), 0.5, 1e-7);
  const vec2 bounds(0.2f, 0.7f);
  EXPECT_EQ(tyn_shadow_intensity(bounds, 0.0f), 0.7f);  // scattering underestimated
  EXPECT_EQ(tyn_shadow_intensity(bounds, 1.0f), 0.2f);  // scattering overestimated
  EXPECT_NEAR(tyn_shadow_intensity(bounds, 0.25f), 0.575, 1e-7);
  // §5.4.2's form: visibility Σ_{z_l ≥ z_f} w_l + β w0 = 1 − shadow, with w0 = upper − lower.
  const float beta = 0.3f;
  EXPECT_NEAR(1.0f - tyn_shadow_intensity(bounds, beta), (1.0f - 0.7f) + beta * (0.7f - 0.2f),
              1e-7);
}

// ---- Roots --------------------------------------------------------------------------------------

// Smallest relative perturbation of the coefficients that makes x / w an exact root of q (the
// backward error; homogeneous, so a root at infinity is measured like any other).
Real backwardError(const std::vector<Real>& q, Real x, Real w) {
  const size_t n = q.size() - 1;
  Real value = 0;
  Real size = 0;
  for (size_t j = 0; j <= n; ++j) {
    const Real term = q[j] * power(x, j) * power(w, n - j);
    value += term;
    size += std::fabs(term);
  }
  return size == 0 ? 0 : std::fabs(value) / size;
}

// How far a root r of q may move when the coefficients move by η relatively: η S / |q'(r)| for a
// simple root, √(2 η S / |q''(r)|) for a double one (S = Σ|q_j r^j|); the smaller applies.
Real rootTolerance(const std::vector<Real>& q, Real r, Real eta) {
  Real size = 0;
  Real d1 = 0;
  Real d2 = 0;
  for (size_t j = 0; j < q.size(); ++j) {
    size += std::fabs(q[j] * power(r, j));
    if (j >= 1) d1 += static_cast<Real>(j) * q[j] * power(r, j - 1);
    if (j >= 2) d2 += static_cast<Real>(j * (j - 1)) * q[j] * power(r, j - 2);
  }
  const Real simple = d1 == 0 ? INFINITY : eta * size / std::fabs(d1);
  const Real twofold = d2 == 0 ? INFINITY : std::sqrt(2 * eta * size / std::fabs(d2));
  return std::min(simple, twofold);
}

struct RootCheck {
  double backward = 0;  // worst backward error / ε
  double forward = 0;   // worst forward error / its tolerance at η = ε
};

// Compares computed homogeneous roots with the true ones (a root at infinity as ±INFINITY).
// Roots are matched in order of value; a root beyond ±1 is compared as its reciprocal, a root of
// the reversed polynomial, so that large and infinite roots are measured on the same footing.
void checkRoots(const char* name, const std::vector<Real>& q, const std::vector<Real>& x,
                const std::vector<Real>& w, std::vector<Real> truth, Real k_backward,
                Real k_forward, RootCheck& out) {
  std::vector<Real> reversed(q.rbegin(), q.rend());
  std::vector<std::pair<Real, size_t>> order;  // by value, a root at infinity last
  for (size_t i = 0; i < x.size(); ++i) {
    const Real b = backwardError(q, x[i], w[i]);
    EXPECT_LE(b, k_backward * kFloatEps) << name << " root " << static_cast<double>(x[i] / w[i]);
    out.backward = std::max(out.backward, static_cast<double>(b / kFloatEps));
    order.push_back({w[i] == 0 ? INFINITY : x[i] / w[i], i});
  }
  std::sort(order.begin(), order.end());
  for (Real& t : truth) {
    if (std::isinf(t)) t = INFINITY;
  }
  std::sort(truth.begin(), truth.end());
  ASSERT_EQ(truth.size(), order.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    const size_t k = order[i].second;
    const Real r = truth[i];
    Real error;
    Real tol;
    if (std::fabs(r) <= 1) {
      error = std::fabs(x[k] / w[k] - r);
      tol = rootTolerance(q, r, kFloatEps);
    } else {
      error = std::fabs(w[k] / x[k] - 1 / r);
      tol = rootTolerance(reversed, 1 / r, kFloatEps);
    }
    EXPECT_LE(error, k_forward * tol) << name << " root " << static_cast<double>(r) << " got "
                                      << static_cast<double>(x[k] / w[k]);
    out.forward = std::max(out.forward, static_cast<double>(error / tol));
  }
}

std::vector<Real> fromRoots(Real scale, const std::vector<Real>& roots) {
  std::vector<Real> q{scale};
  for (Real r : roots) {
    std::vector<Real> next(q.size() + 1, 0);
    for (size_t j = 0; j < q.size(); ++j) {
      if (std::isinf(r)) {
        next[j] += q[j];  // factor 1: the degree drops, a root at infinity
      } else {
        next[j + 1] += q[j];
        next[j] -= r * q[j];
      }
    }
    q = next;
  }
  return q;
}

// Coefficients rounded to float, and back to long double: the polynomial the header solves.
std::vector<Real> toFloat(const std::vector<Real>& q) {
  std::vector<Real> r;
  for (Real c : q) r.push_back(static_cast<float>(c));
  return r;
}

// Solver tolerances, from the worst values the cases below print: backward error ≤ 8 ε (worst
// 5.5 ε, cubic with a double root; 1.0 ε for the quadratic); forward error ≤ 16 × the
// conditioning estimate at η = ε (worst 5.3, same case). The coefficients' rounding to float
// alone is η = u = ε/2.
constexpr Real kBackward = 8;
constexpr Real kForward = 16;

TEST(MomentRoots, CubicAgainstLongDouble) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const char* names[] = {"distinct", "tiny q3", "q3 = 0", "double root", "root near 0"};
  RootCheck check[5];
  for (int trial = 0; trial < 40000; ++trial) {
    const int kind = trial % 5;
    std::vector<Real> roots;
    const auto separated = [&](Real r) {
      for (Real o : roots) {
        if (std::fabs(o - r) < 0.05L) return false;
      }
      return true;
    };
    while (roots.size() < 3) {
      Real r = 1.5L * u(rng);
      if (kind == 1 && roots.size() == 2) r = std::copysign(std::pow(10.0L, 6 + 4 * u(rng)), r);
      if (kind == 2 && roots.size() == 2) r = INFINITY;
      if (kind == 3 && roots.size() == 1) r = roots[0];
      if (kind == 4 && roots.size() == 0) r = std::copysign(std::pow(10.0L, -4 + 2 * u(rng)), r);
      if (kind == 3 && roots.size() == 1) {
        roots.push_back(r);
      } else if (separated(r) || std::isinf(r)) {
        roots.push_back(r);
      }
    }
    const std::vector<Real> q = toFloat(fromRoots(std::pow(10.0L, 3 * u(rng)), roots));
    const vec4 qf(static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2]),
                  static_cast<float>(q[3]));
    vec3 x;
    vec3 w;
    tyn_solve_cubic(qf, x, w);
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(x[c]) && std::isfinite(w[c])) << names[kind];
    }
    checkRoots(names[kind], q, {x.x, x.y, x.z}, {w.x, w.y, w.z}, roots, kBackward, kForward,
               check[kind]);
  }
  for (int k = 0; k < 5; ++k) {
    std::printf("[ moments  ] cubic, %-11s: worst backward error %.3g eps, forward error %.3g of "
                "its conditioning\n", names[k], check[k].backward, check[k].forward);
  }
}

// The cubics Algorithm 1 actually solves: kernel polynomials q = B(b)⁻¹ v(z_f) of biased
// 6-moment vectors (long double, then rounded to float), roots from the long-double solver.
TEST(MomentRoots, CubicKernelPolynomials) {
  std::mt19937 rng(22);
  RootCheck check;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::vector<Atom> atoms = randomDistribution(rng);
    const float zf = randomFragmentDepth(rng, atoms);
    vec3 odd(0.0f);
    vec3 even(0.0f);
    for (const Atom& a : atoms) {
      odd += a.w * tyn_moments6_odd(a.z);
      even += a.w * tyn_moments6_even(a.z);
    }
    odd = tyn_bias_moments(odd, TYN_MOMENTS6_B_STAR_ODD, TYN_MOMENTS6_96_ALPHA);
    even = tyn_bias_moments(even, TYN_MOMENTS6_B_STAR_EVEN, TYN_MOMENTS6_96_ALPHA);
    const std::vector<Real> b = withB0(odd, even);
    std::vector<Real> v(4);
    for (size_t j = 0; j < 4; ++j) v[j] = power(zf, j);
    const std::vector<Real> q = toFloat(solve(hankel(b), v));
    std::vector<Real> roots = realRoots(q);
    if (roots.size() != 3) continue;  // q3 rounded to 0: covered by CubicAgainstLongDouble
    vec3 x;
    vec3 w;
    tyn_solve_cubic(vec4(static_cast<float>(q[0]), static_cast<float>(q[1]),
                         static_cast<float>(q[2]), static_cast<float>(q[3])),
                    x, w);
    checkRoots("kernel", q, {x.x, x.y, x.z}, {w.x, w.y, w.z}, roots, kBackward, kForward, check);
  }
  std::printf("[ moments  ] cubic, kernel polynomials: worst backward error %.3g eps, forward "
              "error %.3g of its conditioning\n", check.backward, check.forward);
}

TEST(MomentRoots, QuadraticAgainstLongDouble) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const char* names[] = {"distinct", "tiny q2", "q2 = 0", "double root", "root near 0"};
  RootCheck check[5];
  for (int trial = 0; trial < 40000; ++trial) {
    const int kind = trial % 5;
    std::vector<Real> roots{1.5L * u(rng)};
    Real second = 1.5L * u(rng);
    while (std::fabs(second - roots[0]) < 0.05L) second = 1.5L * u(rng);
    if (kind == 1) second = std::copysign(std::pow(10.0L, 6 + 4 * u(rng)), u(rng));
    if (kind == 2) second = INFINITY;
    if (kind == 3) second = roots[0];
    if (kind == 4) roots[0] = std::copysign(std::pow(10.0L, -4 + 2 * u(rng)), u(rng));
    roots.push_back(second);
    const std::vector<Real> q = toFloat(fromRoots(std::pow(10.0L, 3 * u(rng)), roots));
    vec2 x;
    vec2 w;
    tyn_solve_quadratic(vec3(static_cast<float>(q[0]), static_cast<float>(q[1]),
                             static_cast<float>(q[2])),
                        x, w);
    checkRoots(names[kind], q, {x.x, x.y}, {w.x, w.y}, roots, kBackward, kForward, check[kind]);
  }
  for (int k = 0; k < 5; ++k) {
    std::printf("[ moments  ] quadratic, %-11s: worst backward error %.3g eps, forward error "
                "%.3g of its conditioning\n", names[k], check[k].backward, check[k].forward);
  }
}

// ---- Algorithm 2 --------------------------------------------------------------------------------

// |E[z^j] − b_j| of the returned distribution, in long double, relative to the size of the terms
// (Σ |w_l| |z_l|^j + |b_j|): the float evaluation can do no better than a few ε of that.
double reproductionError(vec4 r, vec3 b) {
  double worst = 0;
  for (int j = 0; j <= 3; ++j) {
    const Real e1 = power(r.x, static_cast<size_t>(j));
    const Real e2 = power(r.y, static_cast<size_t>(j));
    const Real bj = j == 0 ? 1 : b[j - 1];
    const Real m = r.z * e1 + r.w * e2;
    const Real size = std::fabs(r.z * e1) + std::fabs(r.w * e2) + std::fabs(bj);
    worst = std::max(worst, static_cast<double>(std::fabs(m - bj) / size));
  }
  return worst;
}

// Algorithm 2 as printed (with its minus signs), in long double: (z1, z2, w1, w2).
std::array<Real, 4> referenceTwoDepths(const std::array<Real, 3>& b) {
  const Real q2 = b[1] - b[0] * b[0];
  const Real q1 = b[0] * b[1] - b[2];
  const Real q0 = -b[0] * q1 - b[1] * q2;
  const Real disc = q1 * q1 - 4 * q2 * q0;
  const Real t = -0.5L * (q1 + std::copysign(std::sqrt(disc), q1));
  const Real z1 = q0 / t;
  const Real z2 = t / q2;
  const Real w2 = (b[0] - z1) / (z2 - z1);
  return {z1, z2, 1 - w2, w2};
}

// Largest difference between two (z1, z2, w1, w2), matching the atoms either way round.
Real twoDepthsDistance(const std::array<Real, 4>& a, const std::array<Real, 4>& b) {
  const Real same = std::max({std::fabs(a[0] - b[0]), std::fabs(a[1] - b[1]),
                              std::fabs(a[2] - b[2]), std::fabs(a[3] - b[3])});
  const Real swapped = std::max({std::fabs(a[0] - b[1]), std::fabs(a[1] - b[0]),
                                 std::fabs(a[2] - b[3]), std::fabs(a[3] - b[2])});
  return std::min(same, swapped);
}

// How far the exact answer moves when b1, b2, b3 move by half an ulp (as the bounds' test does).
Real twoDepthsSensitivity(const std::array<Real, 3>& b) {
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::array<Real, 4> at = referenceTwoDepths(b);
  Real s = 0;
  for (int k = 0; k < 16; ++k) {
    std::array<Real, 3> p = b;
    for (Real& x : p) x += 0.5L * kFloatEps * std::fabs(x) * u(rng);
    if (!(p[1] - p[0] * p[0] > 0)) continue;
    s = std::max(s, twoDepthsDistance(referenceTwoDepths(p), at));
  }
  return s;
}

// Moments from float depths, and the same read back from a 64-bit moment map (the input of
// filtered resampling, §5.2, which need not even be a valid moment vector):
//   - the returned distribution reproduces b0..b3 (long double): within 16 ε of the size of the
//     terms (Σ |w_l| |z_l|^j + |b_j|); measured worst 3.6 ε. The raw-moment form of the paper's
//     steps in float missed this by up to 1e-2 for tiny variances (see the header);
//   - depths and weights agree with the paper's steps done in long double on the same input, to
//     8 (s + ε) with s their sensitivity to half-ulp input rounding (measured worst 4.3);
//   - exactly two surfaces: the paper's steps give them back from their exact moments.
TEST(MomentTwoDepths, ReproducesTheFirstFourMoments) {
  std::mt19937 rng(31);
  double worst[2] = {0, 0};
  double worst_forward = 0;
  double worst_surfaces = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const std::vector<Atom> atoms = randomDistribution(rng);
    vec4 b(0.0f);
    for (const Atom& a : atoms) b += a.w * tyn_moments4(a.z);
    vec4 stored = tyn_quantize_moments4_64(b);
    for (int c = 0; c < 4; ++c) stored[c] = storeUnorm(stored[c], 16);
    const vec4 inputs[2] = {b, tyn_dequantize_moments4_64(stored)};
    for (int i = 0; i < 2; ++i) {
      const vec3 b3(inputs[i].x, inputs[i].y, inputs[i].z);
      const vec4 r = tyn_two_depths_from_moments(b3);
      ASSERT_TRUE(finite(r));
      if (!(b3.y - b3.x * b3.x > 0.0f)) {
        EXPECT_EQ(r, vec4(b3.x, b3.x, 1.0f, 0.0f));
        continue;
      }
      const double e = reproductionError(r, b3);
      EXPECT_LE(e, 16 * kFloatEps) << "b " << b3.x << " " << b3.y << " " << b3.z;
      worst[i] = std::max(worst[i], e);
      const std::array<Real, 3> exact_input{b3.x, b3.y, b3.z};
      const Real distance = twoDepthsDistance(toReal(r), referenceTwoDepths(exact_input));
      if (distance > kConditioningSlack * kFloatEps) {
        const Real s = twoDepthsSensitivity(exact_input);
        EXPECT_LE(distance, kConditioningSlack * (s + kFloatEps))
            << "b " << b3.x << " " << b3.y << " " << b3.z;
        worst_forward = std::max(worst_forward, static_cast<double>(distance / (s + kFloatEps)));
      }
      if (i == 0 && atoms.size() == 2 && std::fabs(atoms[0].z - atoms[1].z) > 0.05f &&
          std::min(atoms[0].w, atoms[1].w) > 0.05f) {
        // The paper's steps recover two surfaces from their exact moments (this checks the
        // restored minus signs). Raw moments lose about 1/σ³ of long double's 5e-20; σ > 0.01
        // here, hence 1e-12. From the float moments the header's answer also carries the
        // moments' rounding (printed; the bound on it is the check against long double above).
        std::array<Real, 3> moments{0, 0, 0};
        Real total = 0;
        for (const Atom& a : atoms) total += a.w;
        for (const Atom& a : atoms) {
          for (size_t j = 0; j < 3; ++j) moments[j] += a.w / total * power(a.z, j + 1);
        }
        const std::array<Real, 4> truth{atoms[0].z, atoms[1].z, atoms[0].w / total,
                                        atoms[1].w / total};
        EXPECT_LE(twoDepthsDistance(referenceTwoDepths(moments), truth), 1e-12L)
            << atoms[0].z << " " << atoms[1].z;
        worst_surfaces =
            std::max(worst_surfaces, static_cast<double>(twoDepthsDistance(toReal(r), truth)));
      }
    }
  }
  std::printf("[ moments  ] Algorithm 2: moments reproduced to %.3g eps (float input), %.3g eps "
              "(64-bit read-back); vs long double at most %.3g (s + eps); two separated "
              "surfaces recovered from float moments to %.3g\n",
              worst[0] / kFloatEps, worst[1] / kFloatEps, worst_forward, worst_surfaces);
}

TEST(MomentTwoDepths, FallsBackToOneDepthWithoutVariance) {
  // Exactly one depth: b2 − b1² is exactly 0 in float for these.
  for (float z : {-1.0f, -0.5f, 0.0f, 0.25f, 1.0f}) {
    const vec4 b = tyn_moments4(z);
    EXPECT_EQ(tyn_two_depths_from_moments(vec3(b.x, b.y, b.z)), vec4(z, z, 1.0f, 0.0f)) << z;
  }
  // Negative variance (invalid input from rounding) and NaN-prone all-zero input.
  EXPECT_EQ(tyn_two_depths_from_moments(vec3(0.5f, 0.2f, 0.1f)), vec4(0.5f, 0.5f, 1.0f, 0.0f));
  EXPECT_EQ(tyn_two_depths_from_moments(vec3(0.0f)), vec4(0.0f, 0.0f, 1.0f, 0.0f));
  // Tiny positive variance: two depths, finite, still reproducing the moments.
  const vec3 b(0.5f, 0.25f + 1e-7f, 0.125f + 3e-7f);
  const vec4 r = tyn_two_depths_from_moments(b);
  EXPECT_TRUE(std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z) && std::isfinite(r.w));
  EXPECT_NE(r.w, 0.0f);
  EXPECT_LE(reproductionError(r, b), 16 * kFloatEps);
}

}  // namespace
