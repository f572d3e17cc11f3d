// The shaders' shared maths (shaders/common/*.h), compiled as C++ from the same source, against
// double-precision computations of the same quantities.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/gauss_legendre.h"
#include "common/phase.h"
#include "common/segment_integral.h"

namespace {

using namespace tyndall::gpu;

// ∫_sphere p dω = 2π ∫_{-1}^{1} p(μ) dμ, by composite Simpson in double on a fine grid.
double sphereIntegral(uint type, float g) {
  const int n = 200000;
  const double h = 2.0 / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double mu = -1.0 + i * h;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += w * tyn_phase(type, g, static_cast<float>(mu));
  }
  return 2.0 * M_PI * sum * h / 3.0;
}

TEST(PhaseFunctions, NormalisedOverTheSphere) {
  for (uint type : {TYN_PHASE_ISOTROPIC, TYN_PHASE_RAYLEIGH}) {
    EXPECT_NEAR(sphereIntegral(type, 0.0f), 1.0, 1e-5) << "type " << type;
  }
  for (uint type : {TYN_PHASE_HENYEY_GREENSTEIN, TYN_PHASE_CORNETTE_SHANKS}) {
    for (float g : {-0.9f, -0.5f, 0.0f, 0.3f, 0.76f, 0.9f}) {
      EXPECT_NEAR(sphereIntegral(type, g), 1.0, 2e-4) << "type " << type << " g " << g;
    }
  }
}

TEST(PhaseFunctions, MatchDoublePrecisionFormulas) {
  for (double g : {-0.7, 0.0, 0.5, 0.95}) {
    for (double mu = -1.0; mu <= 1.0; mu += 0.125) {
      const double denom = std::pow(1.0 + g * g - 2.0 * g * mu, 1.5);
      const double hg = (1.0 - g * g) / (4.0 * M_PI * denom);
      const double cs = 3.0 * (1.0 - g * g) / (8.0 * M_PI * (2.0 + g * g)) * (1.0 + mu * mu) / denom;
      const double rayleigh = 3.0 / (16.0 * M_PI) * (1.0 + mu * mu);
      const float fg = static_cast<float>(g);
      const float fmu = static_cast<float>(mu);
      EXPECT_NEAR(tyn_phase_henyey_greenstein(fmu, fg), hg, 2e-6 * hg + 1e-9);
      EXPECT_NEAR(tyn_phase_cornette_shanks(fmu, fg), cs, 2e-6 * cs + 1e-9);
      EXPECT_NEAR(tyn_phase_rayleigh(fmu), rayleigh, 1e-6 * rayleigh);
    }
  }
  // Forward scattering peaks when looking into the light (cos θ = 1).
  EXPECT_GT(tyn_phase_henyey_greenstein(1.0f, 0.7f), tyn_phase_henyey_greenstein(-1.0f, 0.7f));
  // Henyey–Greenstein with g = 0 is isotropic.
  EXPECT_NEAR(tyn_phase_henyey_greenstein(0.3f, 0.0f), tyn_phase_isotropic(), 1e-9);
}

// ∫_a^b e^{−σt} dt in double: e^{−σa} (1 − e^{−σ(b−a)}) / σ via expm1.
double exactIntegral(double a, double b, double sigma) {
  if (sigma == 0.0) return b - a;
  return std::exp(-sigma * a) * -std::expm1(-sigma * (b - a)) / sigma;
}

TEST(SegmentIntegral, MatchesDoublePrecisionAcrossScales) {
  const float sigmas[] = {0.0f, 1e-9f, 1e-6f, 1e-3f, 0.1f, 1.0f, 10.0f, 1000.0f};
  const float lengths[] = {1e-6f, 1e-3f, 0.5f, 3.0f, 100.0f};
  for (float sigma : sigmas) {
    for (float a : {0.0f, 0.25f, 7.0f}) {
      for (float len : lengths) {
        const float b = a + len;
        const double exact = exactIntegral(a, b, sigma);
        const vec3 got = tyn_transmittance_integral(a, b, vec3(sigma));
        if (exact < 1e-30) continue;  // underflows in float as well
        EXPECT_NEAR(got.x / exact, 1.0, 2e-5) << "sigma " << sigma << " a " << a << " len " << len;
      }
    }
  }
}

TEST(SegmentIntegral, AgreesWithQuadrature) {
  const double sigma = 0.37;
  const double a = 1.5;
  const double b = 9.25;
  const int n = 100000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += std::exp(-sigma * (a + (i + 0.5) * (b - a) / n));
  sum *= (b - a) / n;
  EXPECT_NEAR(tyn_transmittance_integral(1.5f, 9.25f, vec3(0.37f)).y, sum, 1e-5 * sum);
}

TEST(SegmentIntegral, PerChannelAndEmptySegments) {
  const vec3 r = tyn_transmittance_integral(2.0f, 3.0f, vec3(0.0f, 0.5f, 2.0f));
  EXPECT_NEAR(r.x, 1.0, 1e-6);
  EXPECT_NEAR(r.y, exactIntegral(2.0, 3.0, 0.5), 1e-6);
  EXPECT_NEAR(r.z, exactIntegral(2.0, 3.0, 2.0), 1e-6);
  EXPECT_EQ(tyn_transmittance_integral(4.0f, 4.0f, vec3(1.0f)).x, 0.0f);
  EXPECT_EQ(tyn_transmittance_integral(4.0f, 3.0f, vec3(1.0f)).x, 0.0f);
}

// The local lights' quadrature (common/gauss_legendre.h): along a ray passing the light at
// distance 1, 1/d² = 1/(1 + s²), whose integral is atan. Segments across the peak, before it and
// after it, cut by tyn_local_light_pieces; the rule with the shaders' float nodes against atan in
// double. The bound is the one gauss_legendre.h and medium.glsl quote.
TEST(LocalLightQuadrature, RuleErrorOnThePeak) {
  const auto f = [](double s) { return 1.0 / (1.0 + s * s); };
  const auto rule = [&](double a, double b) {
    const double m = 0.5 * (a + b);
    const double r = 0.5 * (b - a);
    return r * (TYN_GAUSS4_W0 * (f(m - r * TYN_GAUSS4_X0) + f(m + r * TYN_GAUSS4_X0)) +
                TYN_GAUSS4_W1 * (f(m - r * TYN_GAUSS4_X1) + f(m + r * TYN_GAUSS4_X1)));
  };
  double worst = 0.0;         // on tyn_local_light_pieces' pieces
  double worst_double = 0.0;  // on pieces twice as long
  for (double a = -6.0; a <= 6.0; a += 0.01) {
    for (double length : {0.05, 0.3, 0.5, 1.0, 2.7, 8.0, 15.9}) {
      const double b = a + length;
      // The closest point of [a, b] to the light, as tyn_local_light_piece finds it.
      const double s_near = std::clamp(0.0, a, b);
      const double d_near = std::sqrt(1.0 + s_near * s_near);
      const int pieces = tyn_local_light_pieces(static_cast<float>(length), static_cast<float>(d_near));
      ASSERT_GE(pieces, 1);
      ASSERT_LE(length / pieces, 0.5 * d_near * (1.0 + 1e-6)) << "a piece longer than half the distance";
      const double exact = std::atan(b) - std::atan(a);
      for (int split : {pieces, (pieces + 1) / 2}) {
        double sum = 0.0;
        for (int i = 0; i < split; ++i) sum += rule(a + i * length / split, a + (i + 1) * length / split);
        double& w = split == pieces ? worst : worst_double;
        w = std::max(w, std::abs(sum / exact - 1.0));
      }
    }
  }
  std::printf("[ quadrature ] worst relative error on 1/d^2: %.2e (%.2e with pieces twice as long)\n", worst,
              worst_double);
  EXPECT_LT(worst, 1.2e-7);
  // The pieces' length matters: twice as long, the rule is over an order of magnitude worse.
  EXPECT_GT(worst_double, 10.0 * worst);
}

}  // namespace
