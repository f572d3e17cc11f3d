// The epipolar technique (engelhardt2010, yusov2013): in-scattering is ray-marched only at
// samples along epipolar lines (slices from the projected light to the screen border), then
// interpolated back to every pixel with a bilateral filter on depth; pixels no sample
// represents are ray-marched individually by the fix-up pass (indirect dispatch, so nothing
// runs when nothing is flagged). Shaders: shaders/epipolar/.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/shared_constants.h"
#include "epipolar/epipolar_constants.h"
#include "gpu.h"
#include "retire_queue.h"
#include "technique.h"
#include "timing.h"

namespace tyndall {

/// The block image (shaders/epipolar/shadow_blocks.comp) for `mapCount` shadow maps of `mapSize`²
/// texels: the blocks along each side of a map wide, the maps' blocks stacked one under another.
/// A directional light's fix-up and the march and fix-up of a light whose maps are walked
/// (walksMaps: point) walk the blocks (block_walk.glsl); a spot light's march runs along
/// its slices' min/max trees instead, and its fix-up keeps the Reference's per-part quadrature: 0 × 0.
VkExtent2D shadowBlockExtent(LightType light, std::uint32_t mapSize, std::uint32_t mapCount);

/// Whether every sample of the light walks its maps with the Reference's texel walk, for want of a
/// slice line: a point light's six maps (shaders/epipolar/epipolar_common.glsl,
/// tyn_epipolar_walks_maps). A directional light's cascades each have a line per slice.
bool walksMaps(LightType light);

/// Checks an EpipolarSettings' every field; the message names the field.
Outcome validateEpipolarSettings(const EpipolarSettings& settings);

/// The epipole block's radius in pixels for an output `height` pixels high: the larger of
/// `epipoleFixupRadius` and `epipoleFixupHeightFraction` × height.
float epipoleBlockRadius(const EpipolarSettings& settings, std::uint32_t height);

class EpipolarTechnique final : public ScatteringTechnique {
 public:
  using Bindings = ScatteringBindings;

  Outcome create(const Gpu& gpu, const TechniqueResources& resources) override;
  void sharePipelinesOf(ScatteringTechnique& owner) override {
    pipelineOwner_ = &static_cast<EpipolarTechnique&>(owner);
  }
  Outcome createPipelines(const Gpu& gpu) override;
  /// Compiles what a frame with this light (and light-colour texture or none) needs.
  Outcome ensurePipelines(const Gpu& gpu, const FrameDesc& frame, bool& compiled) override;
  /// planEpipolarFrame, then the textures, the fix-up list and the scattering table it needs.
  Outcome prepare(const Gpu& gpu, const FrameInputs& in, TechniqueReport& report) override;
  void record(const Gpu& gpu, VkCommandBuffer cmd, const RecordTarget& target) override;
  /// Stats::epipolarCounts from the slot's previous epipolar frame.
  void readBack(std::uint32_t slot, Stats& stats) override;
  void releaseRetired(const Gpu& gpu, std::uint64_t frameIndex, std::uint32_t framesInFlight) override;
  [[nodiscard]] ResolutionRequest resolution(const FrameDesc& frame, const ProfileChoice& choice) const override;
  [[nodiscard]] bool drawsDebugViews() const override { return true; }
  [[nodiscard]] VkFormat scatteringFormat() const override { return scatteringFormat_; }
  void destroy(const Gpu& gpu) override;
  /// Drops the fix-up list, which holds every pixel of the L_in target: for a new output extent
  /// (the GPU idle). The next prepare() creates it for its target.
  void destroySizeDependent(const Gpu& gpu) override;

 private:

  /// Makes the sample textures match `settings`, the slice lines and trees cover `lineMaps` maps
  /// (EpipolarFramePlan::lineMaps), the tree texture hold `treeSamples` 1D samples per slice and
  /// map (0: no tree is built this frame) and the light-colour sums `colorSamples` (0: no
  /// light-colour texture, or no slice lines this frame). Textures of other sizes are kept until no
  /// frame in flight can use them (frames in flight need no stall when the parameters change).
  /// `shadowBlocks`: the shadow-map block image's extent (shadowBlockExtent), 0 × 0 when the frame
  /// needs none. `extent`: the L_in target's, for the fix-up list.
  Outcome prepareTextures(const Gpu& gpu, const EpipolarSettings& settings, std::uint32_t lineMaps,
                          std::uint32_t treeSamples, std::uint32_t colorSamples, VkExtent2D shadowBlocks,
                          VkExtent2D extent, std::uint64_t frameIndex);


  /// A spot or point light's march and fix-up read the semi-analytic scattering table (yusov2013),
  /// built for the frame's medium: creates the table at the first such light and says whether this
  /// frame must (re)build it (the medium changed since the last build).
  Outcome prepareScatteringTable(const Gpu& gpu, const FrameDesc& frame, bool& build);

  struct Counts {
    std::uint32_t fixedUp = 0;   // pixels the fix-up pass ray-marched
    std::uint32_t marched = 0;   // samples ray-marched (both rounds)
    std::uint32_t shadowed = 0;  // samples the shadow test found in shadow along their whole ray
  };
  /// The counts of the slot's previous frame (it has completed when the slot comes round again);
  /// false when unknown.
  bool takeCounts(std::uint32_t slot, Counts& out);
  /// Compiles what a frame with this light needs (PipelineCreation::OnFirstUse).
  Outcome ensureLightPipelines(const Gpu& gpu, LightType light, bool colored, bool& compiled);

  struct SampleTextures {
    OwnedImage endPoints;    // slices × 1
    OwnedImage coordinates;  // samples × slices
    OwnedImage scattering;   // samples × slices
    OwnedImage interpolationSource;  // samples × slices, R32_UINT
    OwnedImage sliceUv;      // slices × line maps: line origin and direction in each map's UV
    // (L − 1) × (slices · line maps), RG32F: one min/max tree per row (tyn_epipolar_tree_row);
    // 1 × 1 when unused.
    OwnedImage tree;
    // RGBA32F, the light-colour sums (light_color_sums.h's layout: L per slice, in rows of at most
    // 4096); 1 × 1 when unused.
    OwnedImage colorSums;
    MappedBuffer marchList;  // dispatch args, count, then up to slices × samples packed samples
    std::uint32_t slices = 0;
    std::uint32_t samples = 0;
    std::uint32_t treeWidth = 0;
    std::uint32_t lineMaps = 0;
    std::uint32_t colorSamples = 0;
  };
  void destroyTextures(const Gpu& gpu, SampleTextures& textures);
  Outcome prepareShadowBlocks(const Gpu& gpu, VkExtent2D blocks, std::uint64_t frameIndex);
  void writeDescriptors(const Gpu& gpu, std::uint32_t slot, const Bindings& bindings);
  Outcome createCommonPipelines(const Gpu& gpu);

  EpipolarTechnique* pipelineOwner_ = nullptr;  // sharePipelinesOf: whose pipelines record() binds
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  bool commonReady_ = false;  // every pipeline but march's and the fix-up's light variants
  // slice_setup.comp, shadow_test.comp and refine_intensity.comp size the march's rounds (constant
  // TYN_MARCH_PARTS); unwarp.comp sizes the fix-up ([0] a workgroup per pixel, [1] a thread per
  // pixel: serialFixup).
  VkPipeline setupPipeline_ = VK_NULL_HANDLE;
  VkPipeline shadowTestPipeline_ = VK_NULL_HANDLE;
  VkPipeline refineIntensityPipeline_ = VK_NULL_HANDLE;
  // march.comp specialised: [light type][light-colour texture].
  std::array<std::array<VkPipeline, 2>, 3> marchPipelines_{};
  std::uint32_t marchParts_ = 1;  ///< march.comp's and the round sizers' TYN_MARCH_PARTS
  /// TechniqueResources::scatteringFormat: kFullScatteringFormat builds the _rgba32f shader variants.
  VkFormat scatteringFormat_ = kHalfScatteringFormat;
  std::array<VkPipeline, 2> unwarpPipelines_{};
  LightPipelines fixupPipelines_{};  // per light type, each walking as serialFixup says
  VkPipeline scatteringLutPipeline_ = VK_NULL_HANDLE;
  VkPipeline shadowBlocksPipeline_ = VK_NULL_HANDLE;
  VkPipeline debugBackgroundPipeline_ = VK_NULL_HANDLE;
  VkPipeline debugSamplesPipeline_ = VK_NULL_HANDLE;
  VkPipeline debugFixupPipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
  std::vector<MappedBuffer> fixupReadback_;  // per slot: fix-up and marched counts, read a lap later
  std::vector<bool> fixupPending_;
  std::vector<VkExtent2D> fixupExtent_;  // per slot: the L_in target the counted fix-up ran over
  MappedBuffer fixupArgs_;                   // VkDispatchIndirectCommand
  // The spot light's scattering table (RGBA32F, TYN_SCATTERING_LUT_WIDTH × HEIGHT, GENERAL),
  // created at the first spot light; until then a 1×1 placeholder keeps binding 16 valid.
  OwnedImage scatteringLut_;
  OwnedImage scatteringLutPlaceholder_;
  bool placeholderInitialised_ = false;
  std::vector<float> scatteringLutMedium_;   // what the table was built for; empty: never built
  // The shadow-map blocks of a directional or point light (RG32F, shadowBlockExtent, rewritten by
  // every frame's epipolar_shadow_blocks pass that reads them); until the first one, and for spot
  // lights, a 1×1 placeholder keeps binding 7 valid. Blocks of another extent are kept until no
  // frame in flight can use them.
  OwnedImage shadowBlocks_;  // 0 × 0 before the first
  OwnedImage shadowBlocksPlaceholder_;
  bool shadowBlocksUsed_ = false;  // this frame builds and reads shadowBlocks_
  RetireQueue<OwnedImage> retiredShadowBlocks_;
  // Size-dependent.
  // Two counts, then one entry per listed 2×2 quad of the L_in target; from prepare(), for the
  // largest target a frame has run at (a list too small for a frame's target is retired and replaced).
  MappedBuffer fixupList_;
  VkDeviceSize fixupEntries_ = 0;
  RetireQueue<MappedBuffer> retiredFixupLists_;
  SampleTextures textures_;
  RetireQueue<SampleTextures> retired_;  // see kSpareTextureSets
  std::uint64_t frameIndex_ = 0;
  // This frame's plan (prepare → record).
  gpu::EpipolarConstants constants_{};
  LightType light_ = LightType::Directional;
  bool walksMaps_ = false;  // walksMaps() of this frame's light
  bool buildTable_ = false;
};

}  // namespace tyndall
