// Validation of a FrameDesc and the constants the shaders see for it.
#pragma once

#include "camera.h"
#include "common/shared_constants.h"
#include "gpu.h"

#include <optional>
#include <span>
#include <vector>

namespace tyndall {

/// One light of the frame: FrameDesc::light, or one of FrameDesc::additionalLights with the frame's
/// other inputs.
struct LightSetup {
  gpu::FrameConstants constants{};  ///< the frame's constants with this light's fields
  LightDesc light;
  std::span<const ShadowMapDesc> shadowMaps;
  ImageRef lightColor;
  LightSkipped skipped = LightSkipped::No;  ///< why it records nothing (Off, OutsideView, NothingScatters)
  /// A spot or point light in front of the camera: where its position lands, in output pixels
  /// (possibly off the view).
  std::optional<glm::dvec2> imagePixel;
};

struct FrameSetup {
  std::vector<LightSetup> lights;   ///< FrameDesc::light, then FrameDesc::additionalLights
  ProjectionInfo projection;
  glm::vec3 scattering{0.0f};  ///< the medium's σ_s, summed over its components
  glm::vec3 extinction{0.0f};  ///< the medium's σ_t
  bool scatters = false;    ///< some light is not skipped: there is in-scattering to compute
  bool attenuates = false;  ///< some σ_t > 0: the back buffer changes at all
};

/// Checks every input of the frame (DESIGN.md: NaN/Inf or negative coefficients, zero extents,
/// null handles, mismatched sizes, unsupported formats, near ≥ far, singular matrices) and
/// builds its constants. Nothing is recorded for a frame that fails.
Outcome prepareFrame(const Gpu& gpu, VkExtent2D outputExtent, const FrameDesc& frame,
                     FrameSetup& out);

/// The power of two the frame's half-float L_in targets hold L_in times (FrameConstants::target_scale):
/// the reciprocal of a typical L_in of the frame's brightest light that runs, E · σ_s · ℓ / 4π with
/// ℓ = min(1/σ_t, D) for the channel that gives most (D: the far distance, or the sky's, for a
/// directional light; the camera's distance d from a spot or point light, whose E is I/d² there).
/// 1 when no light runs. An estimate within a few powers of two is enough: half floats keep 2⁻¹¹
/// relative precision from 2⁻¹⁴ to 2¹⁵ times it.
float scatteringTargetScale(const FrameSetup& setup);

}  // namespace tyndall
