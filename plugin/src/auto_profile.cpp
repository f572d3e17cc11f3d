#include "auto_profile.h"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace tyndall {

Profile AutoProfile::choose(std::uint64_t frameIndex, double budgetMs) {
  const double current = estimateMs_[current_];
  // Act only on a measurement of the current profile taken since the last switch.
  const bool settled = frameIndex >= switchedAt_ + kHoldFrames && current >= 0.0 && measuredAt_[current_] >= switchedAt_;
  if (settled) {
    if (current > budgetMs && current_ + 1 < kLadder.size()) {
      ++current_;
      switchedAt_ = frameIndex;
    } else if (current_ > 0) {
      const std::size_t better = current_ - 1;
      const bool known = estimateMs_[better] >= 0.0 && frameIndex < measuredAt_[better] + kStaleFrames;
      if (known ? estimateMs_[better] <= kClimbShare * budgetMs : current <= kProbeShare * budgetMs) {
        current_ = better;
        switchedAt_ = frameIndex;
      }
    }
  }
  // Frames in flight: a few are pending at a time; an entry whose time never came (a frame the
  // timer dropped) is forgotten once newer frames are pending.
  if (pending_.size() >= 16) pending_.pop_front();
  pending_.emplace_back(frameIndex, current_);
  return kLadder[current_];
}

void AutoProfile::measured(std::uint64_t frameIndex, double totalMs) {
  while (!pending_.empty() && pending_.front().first < frameIndex) pending_.pop_front();
  if (pending_.empty() || pending_.front().first != frameIndex) return;  // not an Auto frame
  const std::size_t step = pending_.front().second;
  pending_.pop_front();
  Window& window = windows_[step];
  // Measurements older than kStaleFrames are dropped: the scene may have changed since.
  if (window.count > 0 && frameIndex >= measuredAt_[step] + kStaleFrames) window = Window{};
  window.ms[window.next] = totalMs;
  window.next = (window.next + 1) % kWindow;
  window.count = std::min(window.count + 1, kWindow);
  // Median of at most kWindow values: an insertion sort (std::sort on a 5-element array trips
  // GCC 12's -Warray-bounds under the sanitizer build).
  std::array<double, kWindow> sorted = window.ms;
  for (std::size_t i = 1; i < window.count; ++i) {
    for (std::size_t j = i; j > 0 && sorted[j - 1] > sorted[j]; --j) std::swap(sorted[j - 1], sorted[j]);
  }
  estimateMs_[step] = sorted[window.count / 2];
  measuredAt_[step] = frameIndex;
}

double AutoProfile::estimateMs(Profile profile) const {
  for (std::size_t i = 0; i < kLadder.size(); ++i) {
    if (kLadder[i] == profile) return estimateMs_[i];
  }
  return -1.0;
}

}  // namespace tyndall
