#include "profiles.h"

#include <array>

namespace tyndall {

namespace {

// The rows are docs/TRADEOFFS.md's choice (scripts/tradeoffs.sh: tyndall-bench's sweep of slices,
// samples, intensity refinement and the fix-up's steps against the Reference at 640×360 with 2048²
// maps), which TradeoffsDocument.AgreesWithTheProfileTable keeps equal to this table: per profile, among the
// configurations that meet its per-scene bar (High 3%, Balanced 6%, Performance 16%), the most
// accurate one that meets its speed goal, else the fastest; a configuration other than the row's
// must clear the speed goal by 25% to replace it, so that a run's noise does not move the table
// (kChallengerSpeedMargin in samples/bench/report.h). Every profile runs the epipolar
// technique: the prefiltered one meets the bars but is slower than every profile's speed goal in
// that sweep (6.0x the Reference's speed with its defaults; docs/PREFILTERED.md "Cost on lavapipe").
constexpr EpipolarSettings epipolarSettings(std::uint32_t slices, std::uint32_t samples, std::uint32_t initialStep,
                                            float intensityRefinement, std::uint32_t fixupSteps = 0) {
  EpipolarSettings s;
  s.slices = slices;
  s.samplesPerSlice = samples;
  s.initialSampleStep = initialStep;
  s.intensityRefinementThreshold = intensityRefinement;
  s.fixupSteps = fixupSteps;
  return s;
}

constexpr std::array<ProfileChoice, 5> kProfileTable{{
    {Profile::Reference, Technique::Reference, "profile table: Reference -> brute force", {}},
    {Profile::High, Technique::Epipolar, "profile table: High -> epipolar, 1024 slices x 512 samples",
     epipolarSettings(1024, 512, 16, 0.15f)},
    {Profile::Balanced, Technique::Epipolar, "profile table: Balanced -> epipolar, 512 slices x 256 samples",
     epipolarSettings(512, 256, 16, 0.15f)},
    {Profile::Performance, Technique::Epipolar,
     "profile table: Performance -> epipolar, 128 slices x 128 samples, fix-up in 64 steps (the prefiltered technique "
     "misses the speed goal: not chosen)",
     epipolarSettings(128, 128, 16, 0.15f, 64)},
    // Never looked up for a frame: the context resolves Auto to one of the rows above
    // (auto_profile.h). Kept so that every Profile has a row.
    {Profile::Auto, Technique::Epipolar, "profile table: Auto -> Balanced's settings",
     epipolarSettings(512, 256, 16, 0.15f)},
}};

}  // namespace

const ProfileChoice& profileChoice(Profile profile) {
  for (const ProfileChoice& choice : kProfileTable) {
    if (choice.profile == profile) return choice;
  }
  return kProfileTable[0];
}

}  // namespace tyndall
