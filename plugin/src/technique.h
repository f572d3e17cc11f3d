// The interface every scattering technique implements. The context selects one per frame
// (technique_selection.h), lets it prepare the frame on the CPU, acquires the host's images, has it
// record its passes into the L_in target, and composites; it knows nothing of any technique's data.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gpu.h"
#include "profiles.h"
#include "timing.h"

namespace tyndall {

/// Whether `resolution` is one of ScatteringResolution's values.
constexpr bool isScatteringResolution(ScatteringResolution resolution) {
  return resolution == ScatteringResolution::Full || resolution == ScatteringResolution::Half ||
         resolution == ScatteringResolution::Quarter;
}

/// The L_in target's extent for an output extent: one texel per `resolution` × `resolution` block,
/// a partial block at the right and bottom edges included.
constexpr VkExtent2D targetExtentFor(VkExtent2D output, ScatteringResolution resolution) {
  const auto stride = static_cast<std::uint32_t>(resolution);
  return {(output.width + stride - 1) / stride, (output.height + stride - 1) / stride};
}

/// The L_in target's formats. The approximate techniques write half floats unless
/// ContextTuning::fullFloatTargets: their error is orders of magnitude above its rounding (2⁻¹¹
/// relative) and it halves the frame's largest allocation (shaders/common/scattering_target.glsl
/// clamps to its range). The Reference, the validation path whose AOVs are compared against
/// double-precision references, keeps full floats.
constexpr VkFormat kHalfScatteringFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kFullScatteringFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

/// A technique's L_in resolution and the fewest target rows it runs with (resolutionForRows).
struct ResolutionRequest {
  ScatteringResolution resolution = ScatteringResolution::Full;
  std::uint32_t minimumRows = 0;
};

/// What every technique is created with.
struct TechniqueResources {
  VkSampler nearest = VK_NULL_HANDLE;  ///< nearest, clamp to edge
  VkSampler linear = VK_NULL_HANDLE;   ///< linear, clamp to edge (the light-colour texture's)
  std::uint32_t slots = 1;             ///< frames in flight: one descriptor set and constant buffer each
  std::uint32_t marchThreadsPerSample = 0;  ///< ContextTuning::marchThreadsPerSample (0: by device)
  /// The L_in target format the approximate techniques write: kHalfScatteringFormat, or
  /// kFullScatteringFormat with ContextTuning::fullFloatTargets.
  VkFormat scatteringFormat = kHalfScatteringFormat;
};

/// What a technique's frame is made from.
struct FrameInputs {
  const FrameDesc& frame;
  const ProfileChoice& choice;  ///< the profile row; FrameDesc's settings override its parameters
  VkExtent2D extent{};          ///< the output's
  VkExtent2D targetExtent{};    ///< the L_in target's (resolution(), targetExtentFor)
  std::uint32_t slot = 0;       ///< the frame-in-flight slot
  std::uint64_t frameIndex = 0;
  std::uint32_t framesInFlight = 1;
};

/// What a technique decided for the frame, for the stats.
struct TechniqueReport {
  std::string note;  ///< appended to Stats::techniqueNote, starting with "; " when not empty
  std::optional<EpipolarStats> epipolar;
  std::optional<PrefilteredStats> prefiltered;
};

/// Where a technique records: the frame's inputs, readable by compute shaders, and the L_in
/// target, writable (GENERAL). Each pass is timed by `timer` and its name appended to `passes`.
struct RecordTarget {
  std::uint32_t slot = 0;
  const ScatteringBindings& bindings;
  VkExtent2D extent{};  ///< the L_in target's (FrameInputs::targetExtent)
  GpuTimer& timer;
  std::vector<std::string>& passes;
};

class ScatteringTechnique {
 public:
  virtual ~ScatteringTechnique() = default;

  /// Size-independent resources: layouts, descriptor sets, constant buffers (no pipeline).
  virtual Outcome create(const Gpu& gpu, const TechniqueResources& resources) = 0;
  /// The resolution asked for the frame's L_in target: FrameDesc::resolution (no floor), else
  /// FrameDesc's settings', else the profile row's, with their minimumRows; full by default (the
  /// Reference).
  [[nodiscard]] virtual ResolutionRequest resolution(const FrameDesc& /*frame*/, const ProfileChoice& /*choice*/) const {
    return {};
  }
  /// The format of the L_in target it writes (its shaders' storage-image qualifier).
  [[nodiscard]] virtual VkFormat scatteringFormat() const = 0;
  /// Records with `owner`'s pipelines from now on, compiling none of its own: an additional light's
  /// instance needs its own descriptor sets, buffers and textures, not its own pipelines. `owner`,
  /// the same technique's first-light instance, compiles them and outlives this one.
  virtual void sharePipelinesOf(ScatteringTechnique& owner) = 0;
  /// Compiles every pipeline (context creation with PipelineCreation::AtCreate, Context::warmUp).
  virtual Outcome createPipelines(const Gpu& gpu) = 0;
  /// Compiles what this frame needs and is not compiled yet; `compiled` says whether anything was.
  virtual Outcome ensurePipelines(const Gpu& gpu, const FrameDesc& frame, bool& compiled) = 0;
  /// The frame's CPU set-up: parameters validated, resources sized, constants written. Nothing is
  /// recorded; a failure leaves the frame unrecorded.
  virtual Outcome prepare(const Gpu& gpu, const FrameInputs& in, TechniqueReport& report) = 0;
  /// Records the passes prepare() chose, in the same frame.
  virtual void record(const Gpu& gpu, VkCommandBuffer cmd, const RecordTarget& target) = 0;
  /// A technique recorded as one timed pass names it: the context opens that pass before it
  /// acquires the frame's inputs, so that on a driver that takes timestamps when it flushes (at
  /// barriers) the stamps bracket the work. Techniques that time their own passes return nullptr.
  [[nodiscard]] virtual const char* singlePassName() const { return nullptr; }
  /// Whether the technique draws FrameDesc::debugView; the context then provides the image.
  [[nodiscard]] virtual bool drawsDebugViews() const { return false; }
  /// Reads what the slot's previous frame counted on the GPU (it has completed when the slot comes
  /// round again) into `stats`; nothing by default.
  virtual void readBack(std::uint32_t /*slot*/, Stats& /*stats*/) {}
  /// The same for flags that every light's instance raises (ORed into `stats`); nothing by default.
  virtual void readBackFlags(std::uint32_t /*slot*/, Stats& /*stats*/) {}
  /// Destroys what earlier frames retired (textures of other sizes) once no frame in flight can use
  /// it. Called every frame for every technique, whichever runs, so that a technique that stopped
  /// running does not keep what it retired.
  virtual void releaseRetired(const Gpu& /*gpu*/, std::uint64_t /*frameIndex*/, std::uint32_t /*framesInFlight*/) {}
  /// Drops what depends on the output's size (the GPU idle).
  virtual void destroySizeDependent(const Gpu& /*gpu*/) {}
  virtual void destroy(const Gpu& gpu) = 0;
};

}  // namespace tyndall
