// Validation of a FrameDesc and the constants the shaders see for it.
#pragma once

#include "camera.h"
#include "common/shared_constants.h"
#include "gpu.h"

namespace tyndall {

struct FrameSetup {
  gpu::FrameConstants constants{};
  ProjectionInfo projection;
  bool scatters = false;    ///< some σ_s > 0: there is in-scattering to compute
  bool attenuates = false;  ///< some σ_t > 0: the back buffer changes at all
};

/// Checks every input of the frame (DESIGN.md: NaN/Inf or negative coefficients, zero extents,
/// null handles, mismatched sizes, unsupported formats, near ≥ far, singular matrices) and
/// builds its constants. Nothing is recorded for a frame that fails.
Outcome prepareFrame(const Gpu& gpu, VkExtent2D outputExtent, const FrameDesc& frame,
                     FrameSetup& out);

}  // namespace tyndall
