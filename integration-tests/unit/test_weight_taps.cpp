// The re-weighting of a row's prefix sums to one view ray (shaders/prefiltered/weight_taps.h,
// compiled as C++ from the shader's source) against an independent double-precision construction:
// segment ends found by bisection on the ray's cumulative weight, segment weights by quadrature,
// the combination by summation by parts, and the ray's exact weighted average of random
// piecewise-constant visibilities.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "vulkan_projection.h"

#include "prefiltered/rectification.h"
#include "prefiltered/rectification_setup.h"
#include "prefiltered/weight_taps.h"

namespace {

using namespace tyndall::gpu;

// ∫_a^b e^{−λ t} dt in double, exact for λ = 0.
double expIntegral(double lambda, double a, double b) {
  if (lambda * (b - a) < 1e-8) return std::exp(-lambda * a) * (b - a) * (1.0 - 0.5 * lambda * (b - a));
  return (std::exp(-lambda * a) - std::exp(-lambda * b)) / lambda;
}

struct Tap {
  double fraction;
  double coefficient;
};

// The taps in double, from the definitions: segment k ends where the ray's weight reaches k/K of its
// total (bisection), g_k = ray weight / reference weight of the segment, c_k = W(τ_k)(g_k − g_{k+1})
// / total.
std::vector<Tap> tapsInDouble(double sigma, double kappa, double tauEnd, int taps) {
  const double rayRate = sigma * kappa;
  const double total = kappa * expIntegral(rayRate, 0.0, tauEnd);
  std::vector<double> ends(taps + 1, 0.0);
  for (int k = 1; k <= taps; ++k) {
    if (k == taps) {
      ends[k] = tauEnd;
      continue;
    }
    double lo = 0.0, hi = tauEnd;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (kappa * expIntegral(rayRate, 0.0, mid) < total * k / taps ? lo : hi) = mid;
    }
    ends[k] = 0.5 * (lo + hi);
  }
  std::vector<double> g(taps + 2, 0.0);
  for (int k = 1; k <= taps; ++k) {
    g[k] = kappa * expIntegral(rayRate, ends[k - 1], ends[k]) / expIntegral(sigma, ends[k - 1], ends[k]);
  }
  std::vector<Tap> out;
  for (int k = 1; k <= taps; ++k) {
    out.push_back({ends[k] / tauEnd, expIntegral(sigma, 0.0, ends[k]) * (g[k] - g[k + 1]) / total});
  }
  return out;
}

// A visibility along the ray's extent in the row: `steps` random switches between lit and shadowed.
struct Visibility {
  std::vector<double> edges;  // switch positions in [0, τ_end], ascending
  bool litFirst = true;
  double at(double tau) const {
    const auto n = std::upper_bound(edges.begin(), edges.end(), tau) - edges.begin();
    return ((n % 2 == 0) == litFirst) ? 1.0 : 0.0;
  }
  // ∫_a^b V(τ) e^{−λτ} dτ
  double weighted(double lambda, double a, double b) const {
    double sum = 0.0, lo = a;
    std::vector<double> cuts;
    for (double e : edges) {
      if (e > a && e < b) cuts.push_back(e);
    }
    cuts.push_back(b);
    for (double hi : cuts) {
      sum += at(0.5 * (lo + hi)) * expIntegral(lambda, lo, hi);
      lo = hi;
    }
    return sum;
  }
};

// The stored prefix average A(τ): visibility averaged with the reference's weights up to τ.
double prefixAverage(const Visibility& v, double sigma, double tau) {
  return v.weighted(sigma, 0.0, tau) / expIntegral(sigma, 0.0, tau);
}

TEST(WeightTaps, SingleTapAndExactReferenceNeedOneLookupAtTheEnd) {
  for (std::uint32_t k = 1; k <= 4; ++k) {
    const vec2 one = tyn_weight_tap(0.05f, 3.0f, 40.0f, 1, 1);
    EXPECT_EQ(one.x, 1.0f);
    EXPECT_EQ(one.y, 1.0f);
    // κ = 1: the reference's weights are the ray's; σ = 0: both are uniform.
    for (float sigma : {0.0f, 0.05f}) {
      const float kappa = sigma == 0.0f ? 7.0f : 1.0f;
      const vec2 tap = tyn_weight_tap(sigma, kappa, 40.0f, k, 4);
      EXPECT_NEAR(tap.y, k == 4 ? 1.0f : 0.0f, 2e-5f) << "k " << k << " sigma " << sigma;
    }
  }
  // A zero-length ray: one lookup.
  EXPECT_EQ(tyn_weight_tap(0.05f, 3.0f, 0.0f, 4, 4).y, 1.0f);
  EXPECT_EQ(tyn_weight_tap(0.05f, 3.0f, 0.0f, 2, 4).y, 0.0f);
}

TEST(WeightTaps, MatchTheDoublePrecisionConstructionAndFormAConvexCombination) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worstFraction = 0.0, worstCoefficient = 0.0, worstSum = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double sigma = std::pow(10.0, -4.0 + 4.0 * unit(rng));      // 1e-4 .. 1 per unit
    const double kappa = std::pow(10.0, 3.0 * unit(rng));             // 1 .. 1000
    const double tauEnd = std::pow(10.0, -1.0 + 3.5 * unit(rng));     // 0.1 .. 300 units
    const int taps = 2 + static_cast<int>(unit(rng) * 7.0);           // 2 .. 8
    const std::vector<Tap> reference = tapsInDouble(sigma, kappa, tauEnd, taps);
    double sum = 0.0, previous = 0.0;
    for (int k = 1; k <= taps; ++k) {
      const vec2 tap = tyn_weight_tap(float(sigma), float(kappa), float(tauEnd), std::uint32_t(k), std::uint32_t(taps));
      ASSERT_TRUE(std::isfinite(tap.x) && std::isfinite(tap.y));
      EXPECT_GE(tap.y, 0.0f);
      EXPECT_GT(tap.x, previous);
      EXPECT_LE(tap.x, 1.0f);
      previous = tap.x;
      sum += tap.y;
      worstFraction = std::max(worstFraction, std::abs(tap.x - reference[k - 1].fraction));
      worstCoefficient = std::max(worstCoefficient, std::abs(tap.y - reference[k - 1].coefficient));
      EXPECT_GE(reference[k - 1].coefficient, -1e-12) << "g decreases for kappa >= 1";
    }
    EXPECT_EQ(previous, 1.0f) << "the last tap is the ray's end";
    worstSum = std::max(worstSum, std::abs(sum - 1.0));
  }
  std::printf("[ WeightTaps ] worst vs double: fraction %.1e, coefficient %.1e, |sum - 1| %.1e\n", worstFraction,
              worstCoefficient, worstSum);
  // Measured 2.4e-6, 1.9e-5 and 2.6e-6: float's rounding of segment weights that differ by less
  // than a percent (tiny optical depths), where the coefficients of all but the last tap are small.
  EXPECT_LT(worstFraction, 1e-5);
  EXPECT_LT(worstCoefficient, 5e-5);
  EXPECT_LT(worstSum, 1e-5);
}

// The re-weighted average of random visibilities against the ray's exact weighted average. Each
// segment holds 1/K of the ray's weight and only the shape of the weights inside it is the
// reference's, so the error is at most the mean over segments of tyn_weighted_average_max_error for
// the segment's optical depths under the two rates; it falls as K grows.
TEST(WeightTaps, ConvergeToTheRaysWeightedAverage) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int tapCounts[] = {1, 2, 4, 8};
  double meanError[4] = {0, 0, 0, 0};
  const int trials = 3000;
  for (int trial = 0; trial < trials; ++trial) {
    const double sigma = std::pow(10.0, -3.0 + 3.0 * unit(rng));
    const double kappa = std::pow(10.0, 2.0 * unit(rng));
    const double tauEnd = std::pow(10.0, 0.0 + 2.5 * unit(rng));
    Visibility v;
    v.litFirst = unit(rng) < 0.5;
    const int steps = static_cast<int>(unit(rng) * 6.0);
    for (int i = 0; i < steps; ++i) v.edges.push_back(unit(rng) * tauEnd);
    std::sort(v.edges.begin(), v.edges.end());
    const double truth = v.weighted(sigma * kappa, 0.0, tauEnd) / expIntegral(sigma * kappa, 0.0, tauEnd);
    for (int t = 0; t < 4; ++t) {
      const int taps = tapCounts[t];
      double estimate = 0.0, bound = 0.0, lo = 0.0;
      for (int k = 1; k <= taps; ++k) {
        const vec2 tap = tyn_weight_tap(float(sigma), float(kappa), float(tauEnd), std::uint32_t(k), std::uint32_t(taps));
        const double tau = tap.x * tauEnd;
        estimate += tap.y * prefixAverage(v, sigma, tau);
        bound += double(tyn_weighted_average_max_error(float(sigma * (tau - lo)), float(sigma * kappa * (tau - lo)))) / taps;
        lo = tau;
      }
      const double error = std::abs(estimate - truth);
      meanError[t] += error / trials;
      EXPECT_LE(error, bound + 1e-3) << "taps " << taps << " sigma " << sigma << " kappa " << kappa;
    }
  }
  std::printf("[ WeightTaps ] mean |error| of the ray's visibility average, 1/2/4/8 taps: %.4f/%.4f/%.4f/%.4f\n",
              meanError[0], meanError[1], meanError[2], meanError[3]);
  EXPECT_LT(meanError[1], meanError[0]);
  EXPECT_LT(meanError[2], meanError[1]);
  EXPECT_LT(meanError[3], meanError[2]);
}

// Segmented reconstruction: the difference of two lookups with tyn_segment_coefficients is the
// reference-weighted average of the segment between them alone (double-precision quadrature of
// random visibilities), and the K segments' mean is the combined lookup Σ c_k A(τ_k): the same linear
// average, so segmenting changes only where the non-linear reconstruction runs.
TEST(WeightTaps, SegmentsAreTheirOwnAveragesAndAverageToTheCombinedLookup) {
  EXPECT_EQ(tyn_segment_coefficients(0.0f, 3.0f), vec2(1.0f, 0.0f)) << "the first segment is a lookup";
  EXPECT_EQ(tyn_segment_coefficients(3.0f, 3.0f), vec2(1.0f, 0.0f)) << "a segment of no weight";
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worstSegment = 0.0, worstMean = 0.0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double sigma = std::pow(10.0, -3.0 + 3.0 * unit(rng));
    const double kappa = std::pow(10.0, 2.0 * unit(rng));
    const double tauEnd = std::pow(10.0, 0.0 + 2.5 * unit(rng));
    const int taps = 2 + static_cast<int>(unit(rng) * 7.0);
    Visibility v;
    v.litFirst = unit(rng) < 0.5;
    const int steps = static_cast<int>(unit(rng) * 6.0);
    for (int i = 0; i < steps; ++i) v.edges.push_back(unit(rng) * tauEnd);
    std::sort(v.edges.begin(), v.edges.end());
    double combined = 0.0, segmented = 0.0, lo = 0.0, previousAverage = 0.0;
    float previousWeight = 0.0f;
    for (int k = 1; k <= taps; ++k) {
      const vec2 tap = tyn_weight_tap(float(sigma), float(kappa), float(tauEnd), std::uint32_t(k), std::uint32_t(taps));
      const double tau = tap.x * tauEnd;
      const double average = prefixAverage(v, sigma, tau);
      combined += tap.y * average;
      const float weight = tyn_prefix_weight(float(sigma), float(tau));
      const vec2 c = tyn_segment_coefficients(previousWeight, weight);
      EXPECT_NEAR(double(c.x) + double(c.y), 1.0, 1e-6 * c.x) << "the rounding of w_hi / (w_hi - w_lo) only";
      const double segment = c.x * average + c.y * previousAverage;
      segmented += segment / taps;
      if (tau > lo) {
        const double truth = v.weighted(sigma, lo, tau) / expIntegral(sigma, lo, tau);
        worstSegment = std::max(worstSegment, std::abs(segment - truth));
      }
      lo = tau;
      previousAverage = average;
      previousWeight = weight;
    }
    worstMean = std::max(worstMean, std::abs(segmented - combined));
  }
  std::printf("[ WeightTaps ] segments: worst |segment - its exact average| %.1e, |mean - combined| %.1e\n",
              worstSegment, worstMean);
  EXPECT_LT(worstSegment, 1e-3);
  EXPECT_LT(worstMean, 1e-4);
}

// A tap at reference distance τ = t / κ reads the texel where the ray is at distance t: for both
// rectifications, the tap coordinates of the ray's own distance are its end's texture coordinate
// (tyn_rectified_texcoord, tyn_projective_texcoord_from_offset), for any reference no slower than
// the ray. Light beside the view (the projective map can be built), float arithmetic.
TEST(WeightTaps, TapCoordinatesFollowTheRayInBothRectifications) {
  using namespace tyndall::prefiltered;
  const glm::dvec3 position(3.0, 2.0, 5.0);
  const glm::dmat4 view = glm::lookAt(position, glm::dvec3(-4.0, 0.5, -7.0), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 projection = tyndall::test::vulkanPerspective(glm::radians(60.0), 16.0 / 9.0, 0.1, 200.0, false);
  ViewFrustum frustum;
  ASSERT_TRUE(buildViewFrustum(view, projection, 0.0, frustum).ok());
  const glm::dmat4 toWorld = glm::inverse(view);
  const glm::dvec3 right = glm::normalize(glm::dvec3(toWorld[0])), up = glm::normalize(glm::dvec3(toWorld[1]));
  const glm::dvec3 light = glm::normalize(right - 0.3 * up);  // travels across the view
  const NonLinearRectification rect = computeNonLinearRectification(frustum, light);
  const ProjectiveRectification proj = computeProjectiveRectification(frustum, rect);
  ASSERT_TRUE(proj.constructible);
  const NonLinearRectificationParams rectGpu = toGpu(rect);
  const ProjectiveRectificationParams projGpu = toGpu(proj);
  const glm::dmat4 inverseViewProj = glm::inverse(projection * view);

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worstNonLinear = 0.0, worstProjective = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec4 farPoint = inverseViewProj * glm::dvec4(2.0 * unit(rng) - 1.0, 2.0 * unit(rng) - 1.0, 1.0, 1.0);
    const glm::dvec3 d = glm::normalize(glm::dvec3(farPoint) / farPoint.w - position);
    const double t = 150.0 * unit(rng) + 0.5;
    const vec3 dir(d);
    const vec2 slice = tyn_view_ray_slice(rectGpu, dir);
    const float rayTau = float(t);  // with κ = 1
    // Any reference at least as fast as the ray: sin θ_ref ≥ sin θ.
    const float sinTheta = std::sin(slice.y);
    const float referenceSin = std::min(1.0f, sinTheta * float(1.0 + 3.0 * unit(rng)));
    const float tau = rayTau * sinTheta / referenceSin;

    const vec3 nonLinear = tyn_rectified_texcoord(rectGpu, tyn_rectified_from_view_ray(rectGpu, dir, float(t)));
    worstNonLinear = std::max(worstNonLinear, double(std::abs(tyn_weight_tap_u_nonlinear(tau, referenceSin, rectGpu.r_max) - nonLinear.x)));

    const vec3 projective = tyn_projective_texcoord_from_offset(projGpu, dir * float(t));
    const float eta = tyn_projective_eta(projGpu, projective.y);
    worstProjective = std::max(worstProjective, double(std::abs(tyn_weight_tap_u_projective(projGpu, tau, referenceSin, eta) - projective.x)));
  }
  std::printf("[ WeightTaps ] tap coordinate vs the ray's texcoord: non-linear %.1e, projective %.1e\n", worstNonLinear,
              worstProjective);
  // Measured 3.0e-8 and 2.4e-7 (the projective map's Möbius column in float).
  EXPECT_LT(worstNonLinear, 1e-6);
  EXPECT_LT(worstProjective, 1e-6);
}

}  // namespace
