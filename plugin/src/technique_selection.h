// Which technique runs a frame: the profile's (or the frame's) request, changed only by the
// design fallbacks that Stats::techniqueChange names. Pure, so that every rule is unit-tested.
#pragma once

#include <cstddef>

#include "tyndall/tyndall.h"

namespace tyndall {

/// Whether a light's maps are cascades: a directional light's, when it hands more than one.
inline bool hasCascades(LightType light, std::size_t mapCount) {
  return light == LightType::Directional && mapCount > 1;
}

struct TechniqueRequest {
  Technique requested = Technique::None;  ///< the frame's override, else the profile row's
  LightType light = LightType::Directional;
  bool hasLightColor = false;
  VkExtent2D extent{};
  bool scatters = true;  ///< σ_s > 0 and the light on (FrameSetup::scatters)
  bool cascades = false;  ///< hasCascades
  bool translucentLayers = false;  ///< the light's maps come with translucent layers (ShadowMapDesc)
};

struct TechniqueSelection {
  Technique technique = Technique::None;
  TechniqueChange change = TechniqueChange::None;
};

TechniqueSelection selectTechnique(const TechniqueRequest& request);

/// Whether a light's texel walk (the Reference's, and the epipolar passes' that walk) can exceed a
/// CPU driver's loop budget of 65,535 iterations per shader invocation (docs/REFERENCE.md "Loop
/// budget on lavapipe"), for `mapCount` maps of `mapSize`² texels with `translucentLayers` layers each
/// (ShadowMapDesc::translucentLayerCount; at texels that hold them all).
bool walkCanOverrunCpuLoopBudget(LightType light, std::size_t mapCount, std::uint32_t mapSize,
                                 std::uint32_t translucentLayers = 0);

/// The note's words for a change ("" for None).
const char* techniqueChangeNote(TechniqueChange change);

}  // namespace tyndall
