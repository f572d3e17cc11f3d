// Profile::Auto's choice (plugin/src/auto_profile.h) driven by made-up GPU times: it reaches the
// most accurate profile that fits, steps down when over budget, and does not oscillate.
#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "auto_profile.h"

namespace tyndall {
namespace {

// Renders `frames` frames under Auto with two frames in flight: frame f's time arrives when frame
// f + 2 is recorded, as the context's timestamps do. `cost` gives a profile's time for a frame.
template <class Cost>
std::vector<Profile> run(AutoProfile& autoProfile, std::uint64_t first, std::uint64_t frames, double budgetMs,
                         Cost cost) {
  std::vector<Profile> chosen;
  std::map<std::uint64_t, Profile> inFlight;
  for (std::uint64_t f = first; f < first + frames; ++f) {
    if (f >= 2 && inFlight.count(f - 2) != 0) {
      autoProfile.measured(f - 2, cost(inFlight[f - 2], f - 2));
      inFlight.erase(f - 2);
    }
    const Profile p = autoProfile.choose(f, budgetMs);
    inFlight[f] = p;
    chosen.push_back(p);
  }
  return chosen;
}

double fixedCost(Profile p, std::uint64_t) {
  return p == Profile::High ? 30.0 : p == Profile::Balanced ? 10.0 : 4.0;
}

int switches(const std::vector<Profile>& chosen, std::size_t from = 0) {
  int n = 0;
  for (std::size_t i = from + 1; i < chosen.size(); ++i) n += chosen[i] != chosen[i - 1] ? 1 : 0;
  return n;
}

TEST(AutoProfile, StartsBalancedAndWaitsForAMeasurement) {
  AutoProfile a;
  for (std::uint64_t f = 0; f < 50; ++f) EXPECT_EQ(a.choose(f, 1.0), Profile::Balanced);
  EXPECT_LT(a.estimateMs(Profile::Balanced), 0.0);
}

TEST(AutoProfile, BudgetsForceEachProfile) {
  {  // everything fits: High
    AutoProfile a;
    const std::vector<Profile> chosen = run(a, 0, 100, 1000.0, fixedCost);
    EXPECT_EQ(chosen.back(), Profile::High);
    EXPECT_EQ(switches(chosen), 1);
    EXPECT_DOUBLE_EQ(a.estimateMs(Profile::High), 30.0);
  }
  {  // only Performance fits (and even it does not: the cheapest is the floor)
    AutoProfile a;
    const std::vector<Profile> chosen = run(a, 0, 100, 1.0, fixedCost);
    EXPECT_EQ(chosen.back(), Profile::Performance);
    EXPECT_EQ(switches(chosen), 1);
  }
  {  // Balanced fits, High does not: High is tried once (Balanced uses half the budget), then left
    AutoProfile a;
    const std::vector<Profile> chosen = run(a, 0, 200, 20.0, fixedCost);
    EXPECT_EQ(chosen.back(), Profile::Balanced);
    EXPECT_EQ(switches(chosen), 2);
    EXPECT_EQ(switches(chosen, 50), 0);
  }
  {  // Performance fits, Balanced does not
    AutoProfile a;
    const std::vector<Profile> chosen = run(a, 0, 200, 8.0, fixedCost);
    EXPECT_EQ(chosen.back(), Profile::Performance);
    EXPECT_EQ(switches(chosen, 50), 0);
  }
}

TEST(AutoProfile, HoldsEachChoiceAndIgnoresNoiseNearTheBudget) {
  // Balanced measures 9.5–10.5 ms against a 10 ms budget, High 3× that: Auto settles on
  // Performance or Balanced and does not flip back and forth with the noise.
  AutoProfile a;
  auto noisy = [](Profile p, std::uint64_t f) { return fixedCost(p, f) * (f % 2 == 0 ? 0.95 : 1.05); };
  const std::vector<Profile> chosen = run(a, 0, 290, 10.0, noisy);
  for (std::size_t i = 1; i < chosen.size(); ++i) {
    if (chosen[i] == chosen[i - 1]) continue;
    for (std::size_t j = i + 1; j < std::min(chosen.size(), i + AutoProfile::kHoldFrames); ++j) {
      EXPECT_EQ(chosen[j], chosen[i]) << "switched again at frame " << j << " after a switch at " << i;
    }
  }
  EXPECT_LE(switches(chosen), 2);
  EXPECT_EQ(switches(chosen, 100), 0);
}

TEST(AutoProfile, OneSlowFrameDoesNotMoveIt) {
  // Balanced fits a 15 ms budget (10 ms) but not with room for High; one 100 ms frame (a hitch)
  // is outvoted by the median of the last frames, twice.
  AutoProfile a;
  auto hitches = [](Profile p, std::uint64_t f) { return f == 20 || f == 41 ? 100.0 : fixedCost(p, f); };
  const std::vector<Profile> chosen = run(a, 0, 100, 15.0, hitches);
  EXPECT_EQ(switches(chosen), 0);
  EXPECT_EQ(chosen.back(), Profile::Balanced);
  EXPECT_DOUBLE_EQ(a.estimateMs(Profile::Balanced), 10.0);
}

TEST(AutoProfile, StepsDownWhenTheSceneGetsExpensiveAndRetriesAfterStaleFrames) {
  AutoProfile a;
  // High fits a 40 ms budget...
  std::vector<Profile> chosen = run(a, 0, 60, 40.0, fixedCost);
  EXPECT_EQ(chosen.back(), Profile::High);
  // ...until every profile costs 3× as much: Auto steps down to Balanced (30 ms).
  auto expensive = [](Profile p, std::uint64_t f) { return 3.0 * fixedCost(p, f); };
  chosen = run(a, 60, 100, 40.0, expensive);
  EXPECT_EQ(chosen.back(), Profile::Balanced);
  // When costs fall back, High's old 90 ms estimate keeps Auto on Balanced until it is stale
  // (kStaleFrames), and Balanced uses at most half the budget: then High is tried, and kept.
  chosen = run(a, 160, 400, 40.0, fixedCost);
  EXPECT_EQ(chosen[100], Profile::Balanced);
  EXPECT_EQ(chosen.back(), Profile::High);
  EXPECT_EQ(switches(chosen), 1);
}

TEST(AutoProfile, IgnoresTimesOfFramesThatDidNotRunUnderAuto) {
  AutoProfile a;
  a.measured(5, 123.0);  // a frame another profile ran
  EXPECT_LT(a.estimateMs(Profile::Balanced), 0.0);
  EXPECT_EQ(a.choose(6, 10.0), Profile::Balanced);
  a.measured(6, 7.0);
  EXPECT_DOUBLE_EQ(a.estimateMs(Profile::Balanced), 7.0);
}

}  // namespace
}  // namespace tyndall
