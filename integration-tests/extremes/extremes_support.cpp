#include "extremes_support.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

namespace tyndall::test {

namespace {

// The profile issue's accuracy goals (relative RMSE of L_in), doubled by the check.
double budget(Profile profile) {
  switch (profile) {
    case Profile::High: return 0.02;
    case Profile::Balanced: return 0.04;
    case Profile::Performance: return 0.08;
    default: return 0.0;
  }
}

double largestRgb(const host::ImageRgba32f& image) {
  double largest = 0.0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (i % 4 != 3) largest = std::max(largest, double(std::abs(image.pixels[i])));
  }
  return largest;
}

}  // namespace

void expectEveryProfileWithinTwiceItsBudget(const host::Scene& scene, samples::RenderOptions options,
                                            const std::string& caseName) {
  options.profile = Profile::Reference;
  options.technique = Technique::None;
  const samples::RenderResult reference = renderWithSharedContext(scene, options);
  EXPECT_EQ(compareRgb(reference.scattering, reference.scattering).nonFinite, 0u) << "the Reference itself";
  const bool zero = largestRgb(reference.scattering) == 0.0;
  for (Profile profile : {Profile::High, Profile::Balanced, Profile::Performance, Profile::Auto}) {
    SCOPED_TRACE(caseName + ", " + to_string(profile));
    options.profile = profile;
    const samples::RenderResult r = renderWithSharedContext(scene, options);
    const ErrorStats s = compareRgb(r.scattering, reference.scattering);
    const ErrorStats t = compareRgb(r.transmittance, reference.transmittance);
    const Profile ran = profile == Profile::Auto ? r.stats.profileUsed : profile;
    std::printf("[ extremes ] %s :: %s :: L_in %s :: T relative RMSE %.3g%%, NaN/Inf %zu\n", caseName.c_str(),
                to_string(profile), zero ? "zero expected" : describe(s).c_str(), 100.0 * t.relativeRmse,
                t.nonFinite);
    EXPECT_EQ(s.nonFinite, 0u);
    EXPECT_EQ(t.nonFinite, 0u);
    EXPECT_LE(t.relativeRmse, 1e-5) << "T is exact per pixel in every technique";
    if (zero) {
      EXPECT_EQ(largestRgb(r.scattering), 0.0);
    } else {
      EXPECT_LE(s.relativeRmse, 2.0 * budget(ran)) << describe(s) << "; " << r.stats.techniqueNote;
    }
  }
  expectNoValidationMessages();
}

}  // namespace tyndall::test
