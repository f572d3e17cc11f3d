#include "profiles.h"

#include <array>

namespace tyndall {

namespace {

// The rows are docs/TRADEOFFS-H200.md's choice: tyndall-bench's sweep of slices, samples, intensity
// refinement, the fix-up's steps and the L_in resolution against the Reference at 1920×1080 with
// 2048² maps on a GPU (scripts/measure-gpu.sh; docs/TRADEOFFS.md has the same sweep on lavapipe), which
// TradeoffsDocument.AgreesWithTheProfileTable keeps equal to this table: per profile and kind of
// light, over that kind's scenes, among the configurations that meet its per-scene bar (High 3%,
// Balanced 6%, Performance 16%), the most accurate one that meets its speed goal, else the fastest;
// a configuration other than the row's must clear the speed goal by 25% to replace it, so that a
// run's noise does not move the table, and be 10% more accurate where the row meets the same goals
// (kChallengerSpeedMargin, kChallengerErrorMargin in samples/bench/report.h). Every profile runs the
// epipolar technique: the prefiltered one meets the bars but is slower than every profile's speed
// goal in both sweeps (docs/PREFILTERED.md "Cost on lavapipe", docs/TRADEOFFS-H200.md).
// A reduced resolution keeps at least the L_in rows it was chosen with (minimumRows: 540 at half,
// 270 at quarter of 1080 rows): its error grows as a block covers more of the scene (forest at
// 640×360: Balanced's row at half 11.7% against 5.1% at 1920×1080), so a smaller output runs it finer.
constexpr EpipolarSettings epipolarSettings(std::uint32_t slices, std::uint32_t samples, std::uint32_t initialStep,
                                            float intensityRefinement, std::uint32_t fixupSteps = 0,
                                            ScatteringResolution resolution = ScatteringResolution::Full,
                                            std::uint32_t minimumRows = 0) {
  EpipolarSettings s;
  s.resolution = resolution;
  s.minimumRows = minimumRows;
  s.slices = slices;
  s.samplesPerSlice = samples;
  s.initialSampleStep = initialStep;
  s.intensityRefinementThreshold = intensityRefinement;
  s.fixupSteps = fixupSteps;
  return s;
}

constexpr std::array<ProfileChoice, 10> kProfileTable{{
    {Profile::Reference, LightClass::Directional, Technique::Reference, "profile table: Reference -> brute force", {}},
    {Profile::Reference, LightClass::Local, Technique::Reference, "profile table: Reference -> brute force", {}},
    // Directional lights: chosen over pillars, fence, forest and window-room.
    {Profile::High, LightClass::Directional, Technique::Epipolar,
     "profile table: High, directional light -> epipolar, 1024 slices x 512 samples",
     epipolarSettings(1024, 512, 16, 0.15f)},
    {Profile::Balanced, LightClass::Directional, Technique::Epipolar,
     "profile table: Balanced, directional light -> epipolar, 256 slices x 256 samples, L_in at half resolution "
     "(at least 540 rows)",
     epipolarSettings(256, 256, 16, 0.15f, 0, ScatteringResolution::Half, 540)},
    {Profile::Performance, LightClass::Directional, Technique::Epipolar,
     "profile table: Performance, directional light -> epipolar, 128 slices x 128 samples, fix-up in 64 steps, L_in "
     "at quarter resolution (at least 270 rows; the prefiltered technique misses the speed goal: not chosen)",
     epipolarSettings(128, 128, 16, 0.15f, 64, ScatteringResolution::Quarter, 270)},
    // Spot and point lights: chosen over spot-lamp, stained-glass, point-lamp, spot-fan, spot-grille,
    // spot-lattice, spot-foliage and spot-street.
    // A spot light's slices cover only the wedge of the screen that can see its cone (slice_arc.h), so
    // fewer slices reach the same accuracy there.
    {Profile::High, LightClass::Local, Technique::Epipolar,
     "profile table: High, local light -> epipolar, 512 slices x 256 samples", epipolarSettings(512, 256, 16, 0.15f)},
    {Profile::Balanced, LightClass::Local, Technique::Epipolar,
     "profile table: Balanced, local light -> epipolar, 256 slices x 256 samples, fix-up in 64 steps",
     epipolarSettings(256, 256, 16, 0.15f, 64)},
    {Profile::Performance, LightClass::Local, Technique::Epipolar,
     "profile table: Performance, local light -> epipolar, 128 slices x 128 samples, fix-up in 64 steps",
     epipolarSettings(128, 128, 16, 0.15f, 64)},
    // Never looked up for a frame: the context resolves Auto to one of the rows above
    // (auto_profile.h). Kept so that every Profile has a row.
    {Profile::Auto, LightClass::Directional, Technique::Epipolar, "profile table: Auto -> Balanced's settings",
     epipolarSettings(256, 256, 16, 0.15f, 0, ScatteringResolution::Half, 540)},
    {Profile::Auto, LightClass::Local, Technique::Epipolar, "profile table: Auto -> Balanced's settings",
     epipolarSettings(256, 256, 16, 0.15f, 64)},
}};

}  // namespace

const char* to_string(LightClass lights) { return lights == LightClass::Directional ? "directional" : "local"; }

const ProfileChoice& profileChoice(Profile profile, LightClass lights) {
  for (const ProfileChoice& choice : kProfileTable) {
    if (choice.profile == profile && choice.lights == lights) return choice;
  }
  return kProfileTable[0];
}

}  // namespace tyndall
