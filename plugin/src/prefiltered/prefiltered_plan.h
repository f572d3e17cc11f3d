// The prefiltered technique's frame on the CPU, before any resource or command: the rectification
// (projective or non-linear, in double precision), the prefix weights' extinction sets, the
// epipole block and the per-ray options, as the constants the shaders read and the decisions the
// stats report. Pure, so every decision is unit-tested without a device.
#pragma once

#include <string>

#include "prefiltered/prefiltered_constants.h"
#include "tyndall/tuning.h"

namespace tyndall {

struct PrefilteredFramePlan {
  gpu::PrefilteredConstants constants{};
  PrefilteredStats decisions;
  std::uint32_t texelWalkSteps = 0;  ///< the walk in effect (0 without trimmed segments)
  std::string note;                  ///< the plan's part of Stats::techniqueNote, starting with "; "
};

/// The plan for a directional light's frame at an output of `extent`; fails only when the
/// camera's frustum cannot be built (a degenerate projection).
Outcome planPrefilteredFrame(const FrameDesc& frame, const PrefilteredSettings& settings, VkExtent2D extent,
                             PrefilteredFramePlan& plan);

}  // namespace tyndall
