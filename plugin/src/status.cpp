#include "tyndall/tyndall.h"

namespace tyndall {

const char* to_string(Status status) noexcept {
  switch (status) {
    case Status::Success: return "Success";
    case Status::InvalidArgument: return "InvalidArgument";
    case Status::UnsupportedFormat: return "UnsupportedFormat";
    case Status::UnsupportedFeature: return "UnsupportedFeature";
    case Status::VulkanError: return "VulkanError";
  }
  return "Unknown";
}

const char* to_string(Profile profile) noexcept {
  switch (profile) {
    case Profile::Reference: return "reference";
    case Profile::High: return "high";
    case Profile::Balanced: return "balanced";
    case Profile::Performance: return "performance";
    case Profile::Auto: return "auto";
  }
  return "unknown";
}

const char* to_string(Technique technique) noexcept {
  switch (technique) {
    case Technique::None: return "none";
    case Technique::Reference: return "reference";
    case Technique::Epipolar: return "epipolar";
    case Technique::Prefiltered: return "prefiltered";
  }
  return "unknown";
}

const char* to_string(CompositePath path) noexcept {
  switch (path) {
    case CompositePath::None: return "none";
    case CompositePath::Fragment: return "fragment";
    case CompositePath::Compute: return "compute";
  }
  return "unknown";
}

const char* to_string(ScatteringResolution resolution) noexcept {
  switch (resolution) {
    case ScatteringResolution::Full: return "full";
    case ScatteringResolution::Half: return "half";
    case ScatteringResolution::Quarter: return "quarter";
  }
  return "unknown";
}

const char* to_string(TechniqueChange change) noexcept {
  switch (change) {
    case TechniqueChange::None: return "none";
    case TechniqueChange::NoExtinction: return "no-extinction";
    case TechniqueChange::NothingScatters: return "nothing-scatters";
    case TechniqueChange::PrefilteredNeedsDirectionalLight: return "prefiltered-needs-directional-light";
    case TechniqueChange::PrefilteredHasNoLightColor: return "prefiltered-has-no-light-color";
    case TechniqueChange::PrefilteredNeedsOneShadowMap: return "prefiltered-needs-one-shadow-map";
    case TechniqueChange::EpipolarNeeds2x2: return "epipolar-needs-2x2";
    case TechniqueChange::TranslucentNeedsReference: return "translucent-needs-reference";
  }
  return "unknown";
}

const char* to_string(ResolutionChange change) noexcept {
  switch (change) {
    case ResolutionChange::None: return "none";
    case ResolutionChange::LocalLightInView: return "local-light-in-view";
    case ResolutionChange::BelowMinimumRows: return "below-minimum-rows";
  }
  return "unknown";
}

const char* to_string(LightSkipped reason) noexcept {
  switch (reason) {
    case LightSkipped::No: return "no";
    case LightSkipped::Off: return "off";
    case LightSkipped::OutsideView: return "outside-view";
    case LightSkipped::NothingScatters: return "nothing-scatters";
  }
  return "unknown";
}

}  // namespace tyndall
