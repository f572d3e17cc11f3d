// The epipolar technique's frame on the CPU, before any resource or command: its constants (the
// epipole found by the same code the shaders run), the slice arc, how it marches and which
// per-slice data it needs. Pure, so the decisions are unit-tested without a device.
#pragma once

#include <string>

#include "epipolar/epipolar_constants.h"
#include "tyndall/tuning.h"

namespace tyndall {

struct EpipolarFramePlan {
  gpu::EpipolarConstants constants{};
  EpipolarStats stats;
  std::uint32_t treeSamples = 0;   ///< 1D samples per slice of the min/max tree; 0: no tree built
  std::uint32_t colorSamples = 0;  ///< the light-colour sums' samples per slice; 0: none
  VkExtent2D shadowBlocks{};       ///< the shadow-map block image (shadowBlockExtent); 0 × 0: none
  bool walksMaps = false;          ///< walksMaps(): every sample walks the maps, no slice line or tree
  /// Maps a slice has a line (and a tree) in: a directional light's cascades, a spot light's map;
  /// 0 when the maps are walked.
  std::uint32_t lineMaps = 0;
};

/// The frame's plan for `settings` at an output of `extent` (≥ 2 × 2) with `frame`'s light, maps
/// and light-colour texture.
EpipolarFramePlan planEpipolarFrame(const FrameDesc& frame, const EpipolarSettings& settings, VkExtent2D extent);

/// The plan's part of Stats::techniqueNote ("" when the march is the tree's and the slices cover
/// the whole border), starting with "; ".
std::string epipolarNote(const EpipolarStats& stats);

}  // namespace tyndall
