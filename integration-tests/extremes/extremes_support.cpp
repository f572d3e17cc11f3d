#include "extremes_support.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "report.h"

namespace tyndall::test {

namespace {

// The profile issue's accuracy goals (relative RMSE of L_in; samples/bench/report.cpp
// profileGoals), doubled by the check.
double budget(Profile profile) {
  const samples::bench::ProfileGoal* goal = samples::bench::profileGoal(profile);
  return goal != nullptr ? goal->maxRelativeRmse : 0.0;
}

std::size_t nonFiniteRgb(const host::ImageRgba32f& image) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (i % 4 != 3 && !std::isfinite(image.pixels[i])) ++count;
  }
  return count;
}

double largestRgb(const host::ImageRgba32f& image) {
  double largest = 0.0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (i % 4 != 3) largest = std::max(largest, double(std::abs(image.pixels[i])));
  }
  return largest;
}

// The checks every subject of a case shares: its "[ extremes ]" line (scripts/measure.sh extremes
// reads it), no NaN/Inf in L_in or T, T exact, and L_in zero where the Reference's is (`zero`).
// Returns L_in's error against the Reference, for the subject's own bound.
ErrorStats expectFiniteWithExactT(const samples::RenderResult& r, const samples::RenderResult& reference, bool zero,
                                  const std::string& caseName, const std::string& label) {
  const ErrorStats s = compareRgb(r.scattering, reference.scattering);
  const ErrorStats t = compareRgb(r.transmittance, reference.transmittance);
  std::printf("[ extremes ] %s :: %s :: L_in %s :: T relative RMSE %.3g%%, NaN/Inf %zu\n", caseName.c_str(),
              label.c_str(), zero ? "zero expected" : describe(s).c_str(), 100.0 * t.relativeRmse, t.nonFinite);
  EXPECT_EQ(s.nonFinite, 0u);
  EXPECT_EQ(t.nonFinite, 0u);
  EXPECT_LE(t.relativeRmse, 1e-5) << "T is exact per pixel in every technique";
  if (zero) {
    EXPECT_EQ(largestRgb(r.scattering), 0.0);
  }
  return s;
}

}  // namespace

void expectEveryProfileWithinTwiceItsBudget(const host::Scene& scene, samples::RenderOptions options,
                                            const std::string& caseName, const std::vector<KnownMiss>& knownMisses) {
  options.profile = Profile::Reference;
  options.technique = Technique::None;
  const samples::RenderResult reference = renderWithSharedContext(scene, options);
  EXPECT_EQ(nonFiniteRgb(reference.scattering), 0u) << "the Reference itself";
  const bool zero = largestRgb(reference.scattering) == 0.0;
  for (Profile profile : {Profile::High, Profile::Balanced, Profile::Performance, Profile::Auto}) {
    SCOPED_TRACE(caseName + ", " + to_string(profile));
    options.profile = profile;
    const samples::RenderResult r = renderWithSharedContext(scene, options);
    const Profile ran = profile == Profile::Auto ? r.stats.profileUsed : profile;
    const auto miss = std::find_if(knownMisses.begin(), knownMisses.end(),
                                   [ran](const KnownMiss& m) { return m.profile == ran; });
    const bool knownMiss = miss != knownMisses.end();
    const ErrorStats s = expectFiniteWithExactT(r, reference, zero, caseName,
                                                std::string(to_string(profile)) + (knownMiss ? " (known miss)" : ""));
    if (zero) continue;
    if (!knownMiss) {
      EXPECT_LE(s.relativeRmse, 2.0 * budget(ran)) << describe(s) << "; " << r.stats.techniqueNote;
    } else {
      EXPECT_LE(s.relativeRmse, miss->ceiling) << "known miss: " << miss->why << "; " << describe(s);
      if (s.relativeRmse <= 2.0 * budget(ran)) {
        std::printf("[ extremes note ] %s, %s is within its bound now (%s): drop the known miss \"%s\"\n",
                    caseName.c_str(), to_string(profile), describe(s).c_str(), miss->why.c_str());
      }
    }
  }
  // The prefiltered technique with its defaults, which no profile picks but an engine may ask for:
  // directional lights only (a spot or point light runs the epipolar technique, tested above).
  if (scene.light.type == host::LightType::Directional) {
    const PrefilteredSettings defaults;
    const std::string label = std::string("prefiltered (") + to_string(defaults.basis) + ")";
    SCOPED_TRACE(caseName + ", " + label);
    options.profile = Profile::High;
    options.technique = Technique::Prefiltered;
    options.prefiltered = defaults;
    const samples::RenderResult r = renderWithSharedContext(scene, options);
    const ErrorStats s = expectFiniteWithExactT(r, reference, zero, caseName, label);
    if (!zero) {
      EXPECT_EQ(r.stats.technique, Technique::Prefiltered) << r.stats.techniqueNote;
      EXPECT_LE(s.relativeRmse, prefilteredBar(defaults.basis)) << describe(s) << "; " << r.stats.techniqueNote;
    }
  }
  expectNoValidationMessages();
}

}  // namespace tyndall::test
