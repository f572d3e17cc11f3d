// Profile::Auto: the most accurate profile whose GPU time, measured by the context's own timestamp
// queries, fits the frame's budget (FrameDesc::autoBudgetMilliseconds), with hysteresis so that it
// does not oscillate. Pure bookkeeping (no Vulkan), so that the unit tests drive it with made-up
// timings; the context feeds it each completed frame's total.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>

#include "tyndall/tyndall.h"

namespace tyndall {

class AutoProfile {
 public:
  /// Accuracy order: Auto climbs towards the front while the budget allows.
  static constexpr std::array<Profile, 3> kLadder{Profile::High, Profile::Balanced, Profile::Performance};
  /// Frames to stay on a profile after a switch (its first measurement arrives a few frames later,
  /// with the frames in flight, and one frame's time is noisy).
  static constexpr std::uint64_t kHoldFrames = 8;
  /// A more accurate profile measured earlier is taken again when it used at most this share of
  /// the budget: the margin against measurement noise that keeps Auto from switching back and forth.
  static constexpr double kClimbShare = 0.8;
  /// A more accurate profile never measured, or measured longer than kStaleFrames ago (the scene
  /// may have changed), is tried when the current one uses at most this share of the budget.
  static constexpr double kProbeShare = 0.5;
  static constexpr std::uint64_t kStaleFrames = 300;
  /// A profile's estimate is the median of its last kWindow measured frames: one slow frame (a
  /// hitch of the host, of the driver) does not move it.
  static constexpr std::size_t kWindow = 5;

  /// The profile frame `frameIndex` runs under Auto with a budget of `budgetMs` milliseconds.
  Profile choose(std::uint64_t frameIndex, double budgetMs);
  /// A completed frame's GPU time; frames that ran under Auto update their profile's estimate.
  void measured(std::uint64_t frameIndex, double totalMs);
  /// The estimate for a ladder profile in milliseconds, negative while unmeasured.
  [[nodiscard]] double estimateMs(Profile profile) const;

 private:
  std::size_t current_ = 1;  // Balanced, the default profile, until measurements say otherwise
  std::uint64_t switchedAt_ = 0;
  struct Window {
    std::array<double, kWindow> ms{};
    std::size_t count = 0;  // measurements held, up to kWindow
    std::size_t next = 0;   // where the next one goes
  };
  std::array<Window, 3> windows_{};
  std::array<double, 3> estimateMs_{-1.0, -1.0, -1.0};  // median of each window
  std::array<std::uint64_t, 3> measuredAt_{};
  std::deque<std::pair<std::uint64_t, std::size_t>> pending_;  // frame → ladder step, awaiting its time
};

}  // namespace tyndall
