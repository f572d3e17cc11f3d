#include "technique_selection.h"

namespace tyndall {

TechniqueSelection selectTechnique(const TechniqueRequest& request) {
  // Nothing scatters: no technique runs, L_in is cleared and the composite attenuates the back
  // buffer (DESIGN.md "Model only what the scene requires").
  if (!request.scatters) return {Technique::None, TechniqueChange::NothingScatters};
  TechniqueSelection s{request.requested, TechniqueChange::None};
  // Translucent layers are integrated exactly by the texel walk; the epipolar trees and the
  // prefiltered moments do not read them yet.
  if (request.translucentLayers && s.technique != Technique::Reference) {
    return {Technique::Reference, TechniqueChange::TranslucentNeedsReference};
  }
  // Rectified shadow maps are built for directional lights only, from one map, and a light-colour
  // texture varies along the light rays a rectified texel averages over.
  if (s.technique == Technique::Prefiltered && request.light != LightType::Directional) {
    s = {Technique::Epipolar, TechniqueChange::PrefilteredNeedsDirectionalLight};
  } else if (s.technique == Technique::Prefiltered && request.hasLightColor) {
    s = {Technique::Epipolar, TechniqueChange::PrefilteredHasNoLightColor};
  } else if (s.technique == Technique::Prefiltered && request.cascades) {
    s = {Technique::Epipolar, TechniqueChange::PrefilteredNeedsOneShadowMap};
  }
  // Epipolar lines need a screen at least two pixels wide and high.
  if (s.technique == Technique::Epipolar && (request.extent.width < 2 || request.extent.height < 2)) {
    s = {Technique::Reference, TechniqueChange::EpipolarNeeds2x2};
  }
  return s;
}

bool walkCanOverrunCpuLoopBudget(LightType light, std::size_t mapCount, std::uint32_t mapSize,
                                 std::uint32_t translucentLayers) {
  constexpr std::uint64_t kLoopBudget = 65535;
  // A step costs a directional light's walk one iteration, a spot or point light's two (the
  // quadrature). Translucent layers add, at a texel that holds them all, one iteration per layer
  // read (the count and the overflow layer), and for a spot or point light a quadrature each.
  const std::uint64_t layersRead = translucentLayers > 0 ? translucentLayers + 1 : 0;
  const std::uint64_t localPerEdge = 2 + 2 * layersRead;
  // A point light's walk stays within the budget up to 4096² at two iterations a step (measured:
  // docs/REFERENCE.md).
  constexpr std::uint64_t kPointLightMapLimit = 4096;
  if (light == LightType::Point) return std::uint64_t(mapSize) * localPerEdge > kPointLightMapLimit * 2;
  // A ray crosses up to 2·N texel edges in each map it walks (every cascade of a directional light).
  const std::uint64_t perEdge = light == LightType::Spot ? localPerEdge : 1 + layersRead;
  return perEdge * 2 * std::uint64_t(mapSize) * mapCount > kLoopBudget;
}

const char* techniqueChangeNote(TechniqueChange change) {
  switch (change) {
    case TechniqueChange::None: return "";
    case TechniqueChange::NoExtinction: return "medium has no extinction: the back buffer is left as it is";
    case TechniqueChange::NothingScatters:
      return "no in-scattering (sigma_s = 0 or the light is off): L_in cleared to 0, the back buffer attenuated";
    case TechniqueChange::PrefilteredNeedsDirectionalLight:
      return "prefiltered supports directional lights only: epipolar instead";
    case TechniqueChange::PrefilteredHasNoLightColor: return "prefiltered has no light-colour texture: epipolar instead";
    case TechniqueChange::PrefilteredNeedsOneShadowMap:
      return "prefiltered rectifies one shadow map, not cascades: epipolar instead";
    case TechniqueChange::EpipolarNeeds2x2: return "output smaller than 2x2: Reference instead of epipolar";
    case TechniqueChange::TranslucentNeedsReference:
      return "translucent layers are integrated by the Reference only: Reference instead";
  }
  return "";
}

}  // namespace tyndall
