// Prefiltered single scattering (klehm2014, peters2017 §5) for directional lights: the host's
// shadow map is resampled into a rectified shadow map whose rows are epipolar slices and in which
// every view ray has one constant depth; transmittance-weighted prefix sums along the rows then
// hold, for every view ray at once, the filtered visibility up to each distance, so a pixel needs
// one lookup (per prefix-sum set) and a reconstruction from moments or Fourier coefficients.
// Pixels around an on-screen epipole are ray-marched instead (klehm2014 Fig. 8).
// Shaders: shaders/prefiltered/. Maths: rectification.h, moments.h, rectification_setup.h.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/shared_constants.h"
#include "gpu.h"
#include "prefiltered/prefiltered_constants.h"
#include "retire_queue.h"
#include "technique.h"
#include "timing.h"

namespace tyndall {

/// Checks a PrefilteredSettings' every field; the message names the field.
Outcome validatePrefilteredSettings(const PrefilteredSettings& settings);

class PrefilteredTechnique final : public ScatteringTechnique {
 public:
  using Bindings = ScatteringBindings;

  /// Pipelines of every storage variant and both prefix-sum schemes, the descriptor sets and the
  /// per-slot constant buffers: nothing here depends on the output, the settings or the frame.
  /// `linear`: linear, clamp to edge (the moment map's bilinear lookups, and the light-colour
  /// texture the epipole block's Reference walk reads).
  Outcome create(const Gpu& gpu, const TechniqueResources& resources) override;
  /// Compiles the technique's pipelines (at context creation, in Context::warmUp, or in the first
  /// frame that runs it with PipelineCreation::OnFirstUse).
  void sharePipelinesOf(ScatteringTechnique& owner) override {
    pipelineOwner_ = &static_cast<PrefilteredTechnique&>(owner);
  }
  Outcome createPipelines(const Gpu& gpu) override;
  Outcome ensurePipelines(const Gpu& gpu, const FrameDesc& frame, bool& compiled) override;
  void destroy(const Gpu& gpu) override;
  Outcome prepare(const Gpu& gpu, const FrameInputs& in, TechniqueReport& report) override;
  void releaseRetired(const Gpu& gpu, std::uint64_t frameIndex, std::uint32_t framesInFlight) override;
  [[nodiscard]] ResolutionRequest resolution(const FrameDesc& frame, const ProfileChoice& choice) const override;
  [[nodiscard]] VkFormat scatteringFormat() const override { return scatteringFormat_; }
  /// Records the passes prepare() chose; each is timed and appended to the target's passes.
  void record(const Gpu& gpu, VkCommandBuffer cmd, const RecordTarget& target) override;

 private:
  /// The frame's CPU set-up: rectification bounds and the projective/non-linear choice, the
  /// extinction of the prefix weights, the epipole block; writes the slot's constants and makes
  /// the maps match the settings (maps of other sizes are kept until no frame in flight can use
  /// them). `decisions` and `note` receive what was chosen, for the stats. The light must be
  /// directional, and something must scatter (selectTechnique sees to both).
  Outcome prepareFrame(const Gpu& gpu, const FrameDesc& frame, const PrefilteredSettings& settings, VkExtent2D extent,
                       std::uint32_t slot, std::uint64_t frameIndex, PrefilteredStats& decisions,
                       std::string& note);

  // What the maps are made for: a frame whose key differs gets new maps.
  struct MapKey {
    std::uint32_t basis = ~0u;
    std::uint32_t columns = 0;  // 0: no maps yet
    std::uint32_t rows = 0;
    std::uint32_t sets = 0;
    std::uint32_t momentMapSize = 0;  // 1 without filtered resampling
    bool depthBounds = false;
    bool texelWalk = false;
    bool operator==(const MapKey&) const = default;
  };
  struct Maps {
    OwnedImage momentMap;   // host map size × 1 (RGBA16_UNORM), 1 × 1 when filtering is off
    OwnedImage rectifiedA;  // columns × rows, one layer per slot of image A
    OwnedImage rectifiedB;  // columns × rows, image B of the two-image variants
    OwnedImage prefixA;     // columns × rows, layers of A × prefix-sum sets
    OwnedImage prefixB;
    // The texels and their rows' min/max trees, tyn_depth_bounds_tree_width(columns) × rows
    // (RG16_UNORM), 1 × 1 without the row depth bounds.
    OwnedImage depthBoundsTexels;
    OwnedImage depthBoundsPrefix;
    // Each texel's two depths and the second's weight for the texel walk, columns × rows
    // (RGBA16_UNORM), 1 × 1 without it.
    OwnedImage texelDepths;
    MapKey key;
  };
  Outcome ensureMaps(const Gpu& gpu, const MapKey& key, std::uint64_t frameIndex);
  void destroyMaps(const Gpu& gpu, Maps& maps);
  void writeDescriptors(const Gpu& gpu, std::uint32_t slot, const Bindings& bindings);

  VkSampler prefixSampler_ = VK_NULL_HANDLE;  // linear, clamp along u, repeat along v
  PrefilteredTechnique* pipelineOwner_ = nullptr;  // sharePipelinesOf: whose pipelines record() binds
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  bool pipelinesReady_ = false;
  /// TechniqueResources::scatteringFormat: kFullScatteringFormat builds the _rgba32f shader variants.
  VkFormat scatteringFormat_ = kHalfScatteringFormat;
  VkPipeline momentMapPipeline_ = VK_NULL_HANDLE;
  std::array<VkPipeline, 6> rectifyPipelines_{};           // per storage variant
  // Prefix sums per PrefixSumScheme (kPrefixSumSchemes), per storage variant.
  std::array<std::array<VkPipeline, 6>, 3> prefixSumPipelines_{};
  std::array<VkPipeline, 6> evaluatePipelines_{};          // specialised per storage variant
  VkPipeline fixupArgsPipeline_ = VK_NULL_HANDLE;
  VkPipeline fixupPipeline_ = VK_NULL_HANDLE;
  std::uint32_t supportedVariants_ = 0;  // bit per storage variant whose formats the device has
  bool momentMapSupported_ = false;
  bool depthBoundsSupported_ = false;
  bool texelDepthsSupported_ = false;  // storage only: the walk's depths are loaded, never filtered
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
  std::vector<MappedBuffer> constants_;  // per slot: PrefilteredConstants
  MappedBuffer fixupArgs_;               // PrefilteredFixupArgs
  Maps maps_;
  RetireQueue<Maps> retired_;

  // This frame's choices (prepare → record).
  struct FramePlan {
    std::uint32_t basis = 0;
    std::uint32_t sets = 1;
    bool filtered = false;
    PrefixSumScheme prefixSums = PrefixSumScheme::RowParallel;
    bool epipoleBlock = false;
    bool boundsTree = false;  // trimmed segments: the prefix-sum pass also builds the min/max trees
  } plan_;
};

}  // namespace tyndall
