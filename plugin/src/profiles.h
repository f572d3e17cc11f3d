// The profile table: which technique and parameters each quality profile uses. Data, not code
// paths (FidelityFX's quality-mode tables); docs/TRADEOFFS.md will justify each row by
// measurement once there is more than one technique to choose from.
#pragma once

#include "tyndall/tyndall.h"

namespace tyndall {

struct ProfileChoice {
  Profile profile;
  Technique technique;
  /// Why, in one line, for the stats.
  const char* note;
  /// Parameters when the technique is Epipolar.
  EpipolarSettings epipolar;
  /// Parameters when the technique is Prefiltered.
  PrefilteredSettings prefiltered{};
};

/// The row for a profile (the context resolves Auto to High, Balanced or Performance first).
const ProfileChoice& profileChoice(Profile profile);

}  // namespace tyndall
