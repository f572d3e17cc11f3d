#include "profiles.h"

#include <array>

namespace tyndall {

namespace {

// The epipolar rows, measured against the Reference at 640×360 with 2048² shadow maps on the sample
// scenes (docs/EPIPOLAR.md, "Profiles"): more slices resolve shaft edges across the slices
// (window-room: 3.5% relative RMSE with 512, 1.7% with 1024), more samples and a shorter initial
// step resolve them along; cost grows with the ray-marched samples.
constexpr EpipolarSettings epipolarSettings(std::uint32_t slices, std::uint32_t samples, std::uint32_t initialStep) {
  EpipolarSettings s;
  s.slices = slices;
  s.samplesPerSlice = samples;
  s.initialSampleStep = initialStep;
  return s;
}

constexpr std::array<ProfileChoice, 5> kProfileTable{{
    {Profile::Reference, Technique::Reference, "profile table: Reference -> brute force", {}},
    {Profile::High, Technique::Epipolar, "profile table: High -> epipolar, 1024 slices x 512 samples",
     epipolarSettings(1024, 512, 16)},
    {Profile::Balanced, Technique::Epipolar, "profile table: Balanced -> epipolar, 512 slices x 256 samples",
     epipolarSettings(512, 256, 16)},
    {Profile::Performance, Technique::Epipolar,
     "profile table: Performance -> epipolar, 256 slices x 256 samples (prefiltered technique not implemented yet)",
     epipolarSettings(256, 256, 16)},
    {Profile::Auto, Technique::Epipolar,
     "profile table: Auto -> Balanced's epipolar settings (no time budget choice yet)",
     epipolarSettings(512, 256, 16)},
}};

}  // namespace

const ProfileChoice& profileChoice(Profile profile) {
  for (const ProfileChoice& choice : kProfileTable) {
    if (choice.profile == profile) return choice;
  }
  return kProfileTable[0];
}

}  // namespace tyndall
