#include "epipolar/epipolar_technique.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>

#include "epipolar/epipolar_plan.h"
#include "epipolar/light_color_sums.h"
#include "epipolar/scattering_lut.h"
#include "technique_selection.h"
#include "tyndall_shaders.h"

namespace tyndall {

namespace {

constexpr VkFormat kSampleFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkImageUsageFlags kSampleUsage = VK_IMAGE_USAGE_STORAGE_BIT;
constexpr VkFormat kShadowBlockFormat = VK_FORMAT_R32G32_SFLOAT;  // nearest, farthest depth
// The min/max trees' nodes, rounded outwards (min_max_tree.h's tyn_min_max_stored_bounds).
constexpr VkFormat kTreeFormat = VK_FORMAT_R16G16_UNORM;
constexpr std::uint32_t kBindings = gpu::TYN_EPIPOLAR_BINDING_COUNT;
// EpipolarConstants' std430 offsets (shaders/epipolar/epipolar_constants.h), row by row.
static_assert(offsetof(gpu::EpipolarConstants, slice_count) == 16);
static_assert(offsetof(gpu::EpipolarConstants, initial_sample_step) == 28);
static_assert(offsetof(gpu::EpipolarConstants, epipole_density) == 32);
static_assert(offsetof(gpu::EpipolarConstants, epipole_block_radius) == 44);
static_assert(offsetof(gpu::EpipolarConstants, depth_break_threshold) == 48);
static_assert(offsetof(gpu::EpipolarConstants, slice_contrast_threshold) == 56);
static_assert(offsetof(gpu::EpipolarConstants, tree_samples) == 64);
static_assert(offsetof(gpu::EpipolarConstants, colored_chunk) == 76);
static_assert(offsetof(gpu::EpipolarConstants, arc_start) == 80);
static_assert(offsetof(gpu::EpipolarConstants, shadow_block_side) == 92);
static_assert(offsetof(gpu::EpipolarConstants, epipole_walk_radius) == 96);
static_assert(sizeof(gpu::EpipolarConstants) == 100);
// TYN_MARCH_PARTS of march.comp and of the passes that size its rounds (dispatch_chain.glsl;
// constant_id 1 is the light-colour switch).
constexpr std::uint32_t kMarchPartsConstantId = 2;
// fixup.comp's and unwarp.comp's TYN_FIXUP_SERIAL.
constexpr std::uint32_t kFixupSerialConstantId = 3;
// unwarp.comp sizes the one-thread-per-pixel fix-up in groups of TYN_EPIPOLAR_FIXUP_GROUP,
// and fixup.comp's workgroup is the split march's.
static_assert(gpu::TYN_EPIPOLAR_FIXUP_GROUP == gpu::TYN_SPLIT_MARCH_PARTS);

// Whether the fix-up walks each pixel in one thread (fixup.comp) rather than splitting its walk
// over a workgroup. Only where the march runs one thread per sample (a CPU driver's default), and
// only for directional lights: a CPU driver gains nothing from the split and pays each part's setup
// and the barriers, but a local light's walk branches per step (cone, penumbra, table or
// quadrature, colour), and eight different pixels in one SIMD vector would run every branch any
// of them takes.
bool serialFixup(std::uint32_t marchParts, LightType light) {
  return marchParts == 1 && light == LightType::Directional;
}
// The march list's header (epipolar_common.glsl's MarchList): the shadow test's and the two march
// rounds' VkDispatchIndirectCommands, the count, the current round, the samples found in shadow,
// the entries the shadow test read, and the producers' finished workgroups.
constexpr VkDeviceSize kMarchHeaderWords = 18;
// The fix-up list's header (epipolar_common.glsl's FixupList): the quads listed, the pixels flagged.
constexpr VkDeviceSize kFixupHeaderWords = 2;
constexpr VkDeviceSize kShadowTestArgsOffset = 0;
constexpr VkDeviceSize kMarchRoundArgsOffset[2] = {3 * sizeof(std::uint32_t), 6 * sizeof(std::uint32_t)};
// Sample-texture sets of other sizes kept for a switch back (profiles differ in slices and
// samples): High, Balanced and Performance each keep theirs while the others run.
constexpr std::size_t kSpareTextureSets = 2;
constexpr VkDeviceSize kMarchCountOffset = 9 * sizeof(std::uint32_t);
constexpr VkDeviceSize kMarchShadowedOffset = 12 * sizeof(std::uint32_t);  // then the listed count
constexpr VkPipelineStageFlags kCompute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
// One VkDispatchIndirectCommand; the fix-up arguments hold the fix-up's, then the blocks pass's.
constexpr VkDeviceSize kDispatchArgsBytes = 3 * sizeof(std::uint32_t);

std::uint32_t groups(std::uint32_t count, std::uint32_t size) { return (count + size - 1) / size; }

}  // namespace

bool walksMaps(LightType light) { return light == LightType::Point; }

VkExtent2D shadowBlockExtent(LightType light, std::uint32_t mapSize, std::uint32_t mapCount) {
  if (light == LightType::Spot || mapSize == 0 || mapCount == 0) return {0, 0};
  // shaders/epipolar/epipolar_common.glsl, tyn_shadow_block_size.
  const std::uint32_t block =
      walksMaps(light) ? gpu::TYN_EPIPOLAR_WALKED_SHADOW_BLOCK : gpu::TYN_EPIPOLAR_SHADOW_BLOCK;
  const std::uint32_t side = groups(mapSize, block);
  return {side, side * mapCount};
}

Outcome validateEpipolarSettings(const EpipolarSettings& s) {
  auto invalid = [](const char* message) { return failure(Status::InvalidArgument, message); };
  if (s.slices < 8 || s.slices > 4096) return invalid("epipolar.slices must be in 8..4096");
  if (s.samplesPerSlice < 2 || s.samplesPerSlice > gpu::TYN_EPIPOLAR_MAX_SAMPLES) {
    return invalid("epipolar.samplesPerSlice must be in 2..4096");
  }
  if (!(s.epipoleDensity == 0.0f || (s.epipoleDensity >= 1.0f && s.epipoleDensity <= 1000.0f))) {
    return invalid("epipolar.epipoleDensity must be 0 (the light's) or in [1, 1000]");
  }
  if (!(s.bilateralDepthThreshold > 0.0f && s.bilateralDepthThreshold <= 1.0f)) {
    return invalid("epipolar.bilateralDepthThreshold must be in (0, 1]");
  }
  if (!(s.fixupWeightThreshold > 0.0f && s.fixupWeightThreshold <= 1.0f)) {
    return invalid("epipolar.fixupWeightThreshold must be in (0, 1]");
  }
  if (!(s.sliceContrastThreshold > 0.0f && s.sliceContrastThreshold <= 1.0f)) {
    return invalid("epipolar.sliceContrastThreshold must be in (0, 1]");
  }
  if (s.initialSampleStep < 1 || s.initialSampleStep > 4096) return invalid("epipolar.initialSampleStep must be in 1..4096");
  if (!(s.refinementThreshold > 0.0f && s.refinementThreshold <= 1.0f)) {
    return invalid("epipolar.refinementThreshold must be in (0, 1]");
  }
  if (!(s.intensityRefinementThreshold > 0.0f && s.intensityRefinementThreshold <= 1.0f)) {
    return invalid("epipolar.intensityRefinementThreshold must be in (0, 1]");
  }
  if (s.maxTreeStep < 2 || s.maxTreeStep > 4096 || (s.maxTreeStep & (s.maxTreeStep - 1)) != 0) {
    return invalid("epipolar.maxTreeStep must be a power of two in 2..4096");
  }
  if (!(s.epipoleFixupRadius >= 0.0f && s.epipoleFixupRadius <= 256.0f)) {
    return invalid("epipolar.epipoleFixupRadius must be in [0, 256]");
  }
  if (!(s.epipoleFixupHeightFraction >= 0.0f && s.epipoleFixupHeightFraction <= 0.25f)) {
    return invalid("epipolar.epipoleFixupHeightFraction must be in [0, 0.25]");
  }
  if (s.fixupSteps > gpu::TYN_EPIPOLAR_MAX_FIXUP_STEPS) return invalid("epipolar.fixupSteps must be in 0..256");
  if (s.coloredStep < 1 || s.coloredStep > 4096 || (s.coloredStep & (s.coloredStep - 1)) != 0) {
    return invalid("epipolar.coloredStep must be a power of two in 1..4096");
  }
  if (!isScatteringResolution(s.resolution)) return invalid("epipolar.resolution is not a ScatteringResolution");
  return {};
}

float epipoleBlockRadius(const EpipolarSettings& settings, std::uint32_t height) {
  return std::max(settings.epipoleFixupRadius, settings.epipoleFixupHeightFraction * static_cast<float>(height));
}

Outcome EpipolarTechnique::create(const Gpu& gpu, const TechniqueResources& resources) {
  const VkSampler nearest = resources.nearest;
  const VkSampler linear = resources.linear;
  const std::uint32_t slots = resources.slots;
  scatteringFormat_ = resources.scatteringFormat;
  // A CPU driver runs the same work serially; a GPU needs several threads per marched sample to
  // fill it (docs/EPIPOLAR.md).
  marchParts_ = resources.marchThreadsPerSample != 0 ? resources.marchThreadsPerSample
                : gpu.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1u
                                                                           : gpu::TYN_EPIPOLAR_MARCH_PARTS_GPU;
  const std::array<VkSampler, kMaxShadowMaps> samplers{nearest, nearest, nearest, nearest, nearest, nearest};
  const VkShaderStageFlags stage = VK_SHADER_STAGE_COMPUTE_BIT;
  // Element i is binding i.
  const std::array<VkDescriptorSetLayoutBinding, kBindings> bindings{{
      {gpu::TYN_EPIPOLAR_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stage, samplers.data()},
      {gpu::TYN_EPIPOLAR_BINDING_SHADOW_MAPS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaxShadowMaps, stage,
       samplers.data()},
      {gpu::TYN_EPIPOLAR_BINDING_SLICE_END_POINTS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_COORDINATES, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_SAMPLE_SCATTERING, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_OUT_SCATTERING, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_SHADOW_BLOCKS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_FIXUP_LIST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_FIXUP_ARGS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_INTERPOLATION_SOURCE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_SLICE_UV, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_MIN_MAX_TREE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_MARCH_LIST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_DEBUG_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_LIGHT_COLOR, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stage, &linear},
      {gpu::TYN_EPIPOLAR_BINDING_SCATTERING_LUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_EPIPOLAR_BINDING_LIGHT_COLOR_SUMS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
  }};
  const VkPushConstantRange push{stage, 0, sizeof(gpu::EpipolarConstants)};
  if (Outcome o = createLayouts(gpu, bindings, &push, setLayout_, pipelineLayout_); !o) return o;

  const std::array<VkDescriptorPoolSize, 4> sizes{{
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 + kMaxShadowMaps},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 11},
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3},
  }};
  sets_.resize(slots);
  if (Outcome o = allocateDescriptorSets(gpu, setLayout_, sizes, pool_, sets_); !o) return o;

  fixupReadback_.resize(slots);
  fixupPending_.assign(slots, false);
  fixupExtent_.assign(slots, VkExtent2D{1, 1});
  for (MappedBuffer& buffer : fixupReadback_) {
    if (Outcome o = createMappedBuffer(gpu, 4 * sizeof(std::uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT, buffer); !o) {
      return o;
    }
  }
  if (Outcome o = createImage(gpu, VK_FORMAT_R32G32B32A32_SFLOAT, {1, 1}, kSampleUsage, scatteringLutPlaceholder_); !o) {
    return o;
  }
  if (Outcome o = createImage(gpu, kShadowBlockFormat, {1, 1}, kSampleUsage, shadowBlocksPlaceholder_); !o) return o;
  return createDeviceBuffer(gpu, 2 * kDispatchArgsBytes,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, fixupArgs_);
}

Outcome EpipolarTechnique::createCommonPipelines(const Gpu& gpu) {
  if (commonReady_) return {};
  const bool full = scatteringFormat_ == kFullScatteringFormat;  // the passes that bind the L_in target
  const std::array<std::pair<VkPipeline*, std::span<const std::uint32_t>>, 5> pipelines{{
      {&scatteringLutPipeline_, shaders::scattering_lut_comp()},
      {&shadowBlocksPipeline_, shaders::shadow_blocks_comp()},
      {&debugBackgroundPipeline_, full ? shaders::debug_background_rgba32f_comp() : shaders::debug_background_comp()},
      {&debugSamplesPipeline_, shaders::debug_samples_comp()},
      {&debugFixupPipeline_, shaders::debug_fixup_comp()},
  }};
  for (const auto& [pipeline, spirv] : pipelines) {
    if (Outcome o = createComputePipeline(gpu, pipelineLayout_, spirv, *pipeline); !o) return o;
  }
  // The passes that size the march's rounds, for its threads per sample (constant_id 2, as in march.comp).
  const std::array<std::pair<std::uint32_t, std::uint32_t>, 1> parts{{{kMarchPartsConstantId, marchParts_}}};
  const std::array<std::pair<VkPipeline*, std::span<const std::uint32_t>>, 3> sizers{{
      {&setupPipeline_, shaders::slice_setup_comp()},
      {&shadowTestPipeline_, shaders::shadow_test_comp()},
      {&refineIntensityPipeline_, shaders::refine_intensity_comp()},
  }};
  for (const auto& [pipeline, spirv] : sizers) {
    if (Outcome o = createSpecializedPipeline(gpu, pipelineLayout_, spirv, parts, *pipeline); !o) return o;
  }
  // The one-thread-per-pixel fix-up only where the march runs one thread per sample (serialFixup).
  for (std::uint32_t serial = 0; serial <= (marchParts_ == 1 ? 1u : 0u); ++serial) {
    const std::array<std::pair<std::uint32_t, std::uint32_t>, 1> walk{{{kFixupSerialConstantId, serial}}};
    const std::span<const std::uint32_t> unwarp = full ? shaders::unwarp_rgba32f_comp() : shaders::unwarp_comp();
    if (Outcome o = createSpecializedPipeline(gpu, pipelineLayout_, unwarp, walk, unwarpPipelines_[serial]); !o) {
      return o;
    }
  }
  commonReady_ = true;
  return {};
}

// march.comp per light type (TYN_LIGHT_TYPE) and light-colour texture (TYN_MARCH_LIGHT_COLOR,
// constant_id 1); the fix-up per light type.
Outcome EpipolarTechnique::ensurePipelines(const Gpu& gpu, const FrameDesc& frame, bool& compiled) {
  if (pipelineOwner_ != nullptr) return pipelineOwner_->ensurePipelines(gpu, frame, compiled);
  return ensureLightPipelines(gpu, frame.light.type, !frame.lightColor.empty(), compiled);
}

Outcome EpipolarTechnique::ensureLightPipelines(const Gpu& gpu, LightType light, bool colored, bool& compiled) {
  compiled = !commonReady_;
  if (Outcome o = createCommonPipelines(gpu); !o) return o;
  const auto type = static_cast<std::uint32_t>(light);
  VkPipeline& march = marchPipelines_[type][colored ? 1 : 0];
  if (march == VK_NULL_HANDLE) {
    compiled = true;
    const std::array<std::pair<std::uint32_t, std::uint32_t>, 3> constants{
        {{kLightTypeConstantId, type}, {1, colored ? 1u : 0u}, {kMarchPartsConstantId, marchParts_}}};
    if (Outcome o = createSpecializedPipeline(gpu, pipelineLayout_, shaders::march_comp(), constants, march); !o) {
      return o;
    }
  }
  if (fixupPipelines_[type] == VK_NULL_HANDLE) {
    compiled = true;
    const std::array<std::pair<std::uint32_t, std::uint32_t>, 2> constants{
        {{kLightTypeConstantId, type}, {kFixupSerialConstantId, serialFixup(marchParts_, light) ? 1u : 0u}}};
    const std::span<const std::uint32_t> fixup =
        scatteringFormat_ == kFullScatteringFormat ? shaders::fixup_rgba32f_comp() : shaders::fixup_comp();
    if (Outcome o = createSpecializedPipeline(gpu, pipelineLayout_, fixup, constants, fixupPipelines_[type]);
        !o) {
      return o;
    }
  }
  return {};
}

Outcome EpipolarTechnique::createPipelines(const Gpu& gpu) {
  if (pipelineOwner_ != nullptr) return pipelineOwner_->createPipelines(gpu);
  bool compiled = false;
  for (LightType light : {LightType::Directional, LightType::Spot, LightType::Point}) {
    for (bool colored : {false, true}) {
      if (Outcome o = ensureLightPipelines(gpu, light, colored, compiled); !o) return o;
    }
  }
  return {};
}

void EpipolarTechnique::destroyTextures(const Gpu& gpu, SampleTextures& textures) {
  destroyBuffer(gpu, textures.marchList);
  destroyImage(gpu, textures.tree);
  destroyImage(gpu, textures.colorSums);
  destroyImage(gpu, textures.sliceUv);
  destroyImage(gpu, textures.interpolationSource);
  destroyImage(gpu, textures.scattering);
  destroyImage(gpu, textures.coordinates);
  destroyImage(gpu, textures.endPoints);
  textures = SampleTextures{};
}

void EpipolarTechnique::destroySizeDependent(const Gpu& gpu) {
  destroyBuffer(gpu, fixupList_);
  fixupEntries_ = 0;
  retiredFixupLists_.destroyAll([&](MappedBuffer& buffer) { destroyBuffer(gpu, buffer); });
}

void EpipolarTechnique::destroy(const Gpu& gpu) {
  retired_.destroyAll([&](SampleTextures& textures) { destroyTextures(gpu, textures); });
  destroyTextures(gpu, textures_);
  destroySizeDependent(gpu);
  destroyBuffer(gpu, fixupArgs_);
  destroyImage(gpu, scatteringLut_);
  destroyImage(gpu, scatteringLutPlaceholder_);
  retiredShadowBlocks_.destroyAll([&](OwnedImage& image) { destroyImage(gpu, image); });
  destroyImage(gpu, shadowBlocks_);
  destroyImage(gpu, shadowBlocksPlaceholder_);
  for (MappedBuffer& buffer : fixupReadback_) destroyBuffer(gpu, buffer);
  fixupReadback_.clear();
  if (pool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, pool_, gpu.allocator);
  for (VkPipeline pipeline : {setupPipeline_, shadowTestPipeline_, refineIntensityPipeline_, unwarpPipelines_[0],
                              unwarpPipelines_[1], scatteringLutPipeline_, shadowBlocksPipeline_, debugBackgroundPipeline_,
                              debugSamplesPipeline_, debugFixupPipeline_}) {
    if (pipeline != VK_NULL_HANDLE) gpu.vk.vkDestroyPipeline(gpu.device, pipeline, gpu.allocator);
  }
  for (auto& pipelines : marchPipelines_) destroyPipelines(gpu, pipelines);
  destroyPipelines(gpu, fixupPipelines_);
  if (pipelineLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipelineLayout(gpu.device, pipelineLayout_, gpu.allocator);
  if (setLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, setLayout_, gpu.allocator);
  *this = EpipolarTechnique{};
}

Outcome EpipolarTechnique::prepare(const Gpu& gpu, const FrameInputs& in, TechniqueReport& report) {
  const EpipolarSettings& settings = in.frame.epipolar != nullptr ? *in.frame.epipolar : in.choice.epipolar;
  const EpipolarFramePlan plan = planEpipolarFrame(in.frame, settings, in.extent);
  if (Outcome o = prepareTextures(gpu, settings, plan.lineMaps, plan.treeSamples, plan.colorSamples,
                                  plan.shadowBlocks, in.targetExtent, in.frameIndex);
      !o) {
    return o;
  }
  if (Outcome o = prepareScatteringTable(gpu, in.frame, buildTable_); !o) return o;
  constants_ = plan.constants;
  light_ = in.frame.light.type;
  walksMaps_ = plan.walksMaps;
  report.epipolar = plan.stats;
  report.note = epipolarNote(plan.stats);
  return {};
}

ResolutionRequest EpipolarTechnique::resolution(const FrameDesc& frame, const ProfileChoice& choice) const {
  if (frame.resolution) return {*frame.resolution, 0};
  const auto& s = frame.epipolar != nullptr ? *frame.epipolar : choice.epipolar;
  return {s.resolution, s.minimumRows};
}

void EpipolarTechnique::readBack(std::uint32_t slot, Stats& stats) {
  if (Counts counts; takeCounts(slot, counts)) {
    const VkExtent2D extent = fixupExtent_[slot];
    stats.epipolarCounts = EpipolarCounts{
        counts.marched, counts.shadowed, static_cast<double>(counts.fixedUp) / (double(extent.width) * extent.height)};
  }
}

void EpipolarTechnique::releaseRetired(const Gpu& gpu, std::uint64_t frameIndex, std::uint32_t framesInFlight) {
  retiredFixupLists_.release(frameIndex, framesInFlight, [&](MappedBuffer& buffer) { destroyBuffer(gpu, buffer); });
  // The kSpareTextureSets most recently retired sets are kept; older ones are destroyed once no
  // frame in flight uses them.
  retired_.release(frameIndex, framesInFlight, [&](SampleTextures& textures) { destroyTextures(gpu, textures); },
                   kSpareTextureSets);
  retiredShadowBlocks_.release(frameIndex, framesInFlight, [&](OwnedImage& image) { destroyImage(gpu, image); });
}

Outcome EpipolarTechnique::prepareTextures(const Gpu& gpu, const EpipolarSettings& settings, std::uint32_t lineMaps,
                                           std::uint32_t treeSamples, std::uint32_t colorSamples,
                                           VkExtent2D shadowBlocks, VkExtent2D extent, std::uint64_t frameIndex) {
  frameIndex_ = frameIndex;
  // The fix-up list, at the first frame that runs the technique (a context that only runs the
  // Reference holds none), with an entry per 2×2 quad of the L_in target after its two counts
  // (epipolar_common.glsl's FixupList); a larger target replaces it.
  if (const VkDeviceSize entries = VkDeviceSize((extent.width + 1) / 2) * ((extent.height + 1) / 2);
      entries > fixupEntries_) {
    MappedBuffer list;
    if (Outcome o = createDeviceBuffer(gpu, (entries + kFixupHeaderWords) * sizeof(std::uint32_t),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                       list);
        !o) {
      return o;
    }
    if (fixupList_.buffer != VK_NULL_HANDLE) retiredFixupLists_.retire(frameIndex, fixupList_);
    fixupList_ = list;
    fixupEntries_ = entries;
  }
  if (Outcome o = prepareShadowBlocks(gpu, shadowBlocks, frameIndex); !o) return o;
  // A tree of L 1D samples takes L − 1 texels per row, one row per slice and line map; without
  // one a 1 × 1 texture keeps the descriptor valid.
  lineMaps = std::max(lineMaps, 1u);
  const std::uint32_t treeWidth = treeSamples > 1 ? treeSamples - 1 : 1;
  const std::uint32_t treeRows = treeSamples > 1 ? settings.slices * lineMaps : 1;
  auto fits = [&](const SampleTextures& t) {
    return t.slices == settings.slices && t.samples == settings.samplesPerSlice && t.treeWidth == treeWidth &&
           t.lineMaps == lineMaps && t.colorSamples == colorSamples;
  };
  if (!fits(textures_)) {
    if (textures_.slices != 0) {
      retired_.retire(frameIndex, textures_);
      textures_ = SampleTextures{};
    }
    // A set of these sizes retired by an earlier switch serves again, so that switching between
    // profiles allocates nothing once each has run.
    if (std::optional<SampleTextures> spare = retired_.take(fits)) textures_ = *spare;
  }
  if (textures_.slices != 0) return {};
  SampleTextures fresh;
  fresh.slices = settings.slices;
  fresh.samples = settings.samplesPerSlice;
  fresh.treeWidth = treeWidth;
  fresh.lineMaps = lineMaps;
  fresh.colorSamples = colorSamples;
  Outcome outcome = createImage(gpu, kSampleFormat, {settings.slices, 1}, kSampleUsage, fresh.endPoints);
  if (outcome) {
    outcome = createImage(gpu, kSampleFormat, {settings.samplesPerSlice, settings.slices}, kSampleUsage,
                          fresh.coordinates);
  }
  if (outcome) {
    outcome = createImage(gpu, kSampleFormat, {settings.samplesPerSlice, settings.slices}, kSampleUsage,
                          fresh.scattering);
  }
  if (outcome) {
    outcome = createImage(gpu, VK_FORMAT_R32_UINT, {settings.samplesPerSlice, settings.slices}, kSampleUsage,
                          fresh.interpolationSource);
  }
  if (outcome) outcome = createImage(gpu, kSampleFormat, {settings.slices, lineMaps}, kSampleUsage, fresh.sliceUv);
  if (outcome) outcome = createImage(gpu, kTreeFormat, {treeWidth, treeRows}, kSampleUsage, fresh.tree);
  if (outcome) {
    const int samples = static_cast<int>(colorSamples);
    const VkExtent2D sums =
        colorSamples != 0 ? VkExtent2D{static_cast<std::uint32_t>(gpu::tyn_color_sums_width(samples)),
                                       settings.slices * static_cast<std::uint32_t>(gpu::tyn_color_sums_rows(samples))}
                          : VkExtent2D{1, 1};
    outcome = createImage(gpu, kSampleFormat, sums, kSampleUsage, fresh.colorSums);
  }
  if (outcome) {
    // Every sample at most once per round, and the refinement's entries once more when the shadow
    // test lists them again (epipolar_common.glsl's MarchList).
    const VkDeviceSize entries = 2 * VkDeviceSize(settings.slices) * settings.samplesPerSlice;
    outcome = createDeviceBuffer(gpu, (kMarchHeaderWords + entries) * sizeof(std::uint32_t),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 fresh.marchList);
  }
  if (!outcome) {
    destroyTextures(gpu, fresh);
    return outcome;
  }
  textures_ = fresh;
  return {};
}

Outcome EpipolarTechnique::prepareShadowBlocks(const Gpu& gpu, VkExtent2D blocks, std::uint64_t frameIndex) {
  shadowBlocksUsed_ = blocks.width != 0;
  if (blocks.width == 0 ||
      (blocks.width == shadowBlocks_.extent.width && blocks.height == shadowBlocks_.extent.height)) {
    return {};
  }
  if (shadowBlocks_.image != VK_NULL_HANDLE) {
    retiredShadowBlocks_.retire(frameIndex, shadowBlocks_);
    shadowBlocks_ = OwnedImage{};
  }
  if (Outcome o = createImage(gpu, kShadowBlockFormat, blocks, kSampleUsage, shadowBlocks_); !o) {
    shadowBlocksUsed_ = false;
    return o;
  }
  return {};
}

Outcome EpipolarTechnique::prepareScatteringTable(const Gpu& gpu, const FrameDesc& frame, bool& build) {
  build = false;
  // Spot and point lights: the march and the fix-up integrate their lit sections from it.
  if (frame.light.type == LightType::Directional || frame.shadowMaps.empty()) return {};
  if (scatteringLut_.image == VK_NULL_HANDLE) {
    if (Outcome o = createImage(gpu, VK_FORMAT_R32G32B32A32_SFLOAT,
                                {gpu::TYN_SCATTERING_LUT_WIDTH, gpu::TYN_SCATTERING_LUT_HEIGHT}, kSampleUsage,
                                scatteringLut_);
        !o) {
      return o;
    }
  }
  // The table depends on the medium only: σ_s, σ_a, phase and g of every component.
  std::vector<float> medium;
  for (const MediumComponent& c : frame.medium) {
    medium.insert(medium.end(), c.scattering.begin(), c.scattering.end());
    medium.insert(medium.end(), c.absorption.begin(), c.absorption.end());
    medium.push_back(static_cast<float>(c.phase));
    medium.push_back(c.g);
  }
  build = medium != scatteringLutMedium_;
  if (build) scatteringLutMedium_ = std::move(medium);
  return {};
}

bool EpipolarTechnique::takeCounts(std::uint32_t slot, Counts& out) {
  if (slot >= fixupPending_.size() || !fixupPending_[slot]) return false;
  fixupPending_[slot] = false;
  const auto* counts = static_cast<const std::uint32_t*>(fixupReadback_[slot].mapped);
  out.fixedUp = counts[0];
  out.marched = counts[1] - counts[3];  // the list's entries less those the shadow test listed again
  out.shadowed = counts[2];
  return true;
}

void EpipolarTechnique::writeDescriptors(const Gpu& gpu, std::uint32_t slot, const Bindings& b) {
  const VkDescriptorSet set = sets_[slot];
  const VkDescriptorBufferInfo constants{b.constants, 0, VK_WHOLE_SIZE};
  const VkDescriptorImageInfo depth{VK_NULL_HANDLE, b.depth, b.depthLayout};
  const std::array<VkDescriptorImageInfo, kMaxShadowMaps> shadow = shadowMapImageInfos(b);
  const VkDescriptorImageInfo source{VK_NULL_HANDLE, textures_.interpolationSource.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo sliceUv{VK_NULL_HANDLE, textures_.sliceUv.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo tree{VK_NULL_HANDLE, textures_.tree.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo colorSums{VK_NULL_HANDLE, textures_.colorSums.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo endPoints{VK_NULL_HANDLE, textures_.endPoints.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo coordinates{VK_NULL_HANDLE, textures_.coordinates.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo sampleScattering{VK_NULL_HANDLE, textures_.scattering.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo outScattering{VK_NULL_HANDLE, b.scattering, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorBufferInfo list{fixupList_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo args{fixupArgs_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo marchList{textures_.marchList.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorImageInfo lightColor{VK_NULL_HANDLE, b.lightColor, b.lightColorLayout};

  const VkDescriptorImageInfo lut{VK_NULL_HANDLE,
                                  (scatteringLut_.view != VK_NULL_HANDLE ? scatteringLut_ : scatteringLutPlaceholder_).view,
                                  VK_IMAGE_LAYOUT_GENERAL};
  const OwnedImage& blockImage = shadowBlocksUsed_ ? shadowBlocks_ : shadowBlocksPlaceholder_;
  const VkDescriptorImageInfo blocks{VK_NULL_HANDLE, blockImage.view, VK_IMAGE_LAYOUT_GENERAL};
  // The debug view's target in frames that draw one; otherwise L_in's target stands in, which no
  // pass reads through this binding then, so that every binding is written.
  const VkDescriptorImageInfo debug{VK_NULL_HANDLE, b.debug != VK_NULL_HANDLE ? b.debug : b.scattering,
                                    VK_IMAGE_LAYOUT_GENERAL};

  // Write i is binding i.
  std::array<VkWriteDescriptorSet, kBindings> writes{};
  auto write = [&](std::uint32_t binding, VkDescriptorType type, std::uint32_t count = 1) -> VkWriteDescriptorSet& {
    return writes[binding] = descriptorWrite(set, binding, type, count);
  };
  write(gpu::TYN_EPIPOLAR_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER).pBufferInfo = &constants;
  write(gpu::TYN_EPIPOLAR_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER).pImageInfo = &depth;
  write(gpu::TYN_EPIPOLAR_BINDING_SHADOW_MAPS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaxShadowMaps).pImageInfo =
      shadow.data();
  write(gpu::TYN_EPIPOLAR_BINDING_SLICE_END_POINTS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &endPoints;
  write(gpu::TYN_EPIPOLAR_BINDING_COORDINATES, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &coordinates;
  write(gpu::TYN_EPIPOLAR_BINDING_SAMPLE_SCATTERING, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &sampleScattering;
  write(gpu::TYN_EPIPOLAR_BINDING_OUT_SCATTERING, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &outScattering;
  write(gpu::TYN_EPIPOLAR_BINDING_SHADOW_BLOCKS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &blocks;
  write(gpu::TYN_EPIPOLAR_BINDING_FIXUP_LIST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER).pBufferInfo = &list;
  write(gpu::TYN_EPIPOLAR_BINDING_FIXUP_ARGS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER).pBufferInfo = &args;
  write(gpu::TYN_EPIPOLAR_BINDING_INTERPOLATION_SOURCE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &source;
  write(gpu::TYN_EPIPOLAR_BINDING_SLICE_UV, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &sliceUv;
  write(gpu::TYN_EPIPOLAR_BINDING_MIN_MAX_TREE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &tree;
  write(gpu::TYN_EPIPOLAR_BINDING_MARCH_LIST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER).pBufferInfo = &marchList;
  write(gpu::TYN_EPIPOLAR_BINDING_DEBUG_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &debug;
  write(gpu::TYN_EPIPOLAR_BINDING_LIGHT_COLOR, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER).pImageInfo = &lightColor;
  write(gpu::TYN_EPIPOLAR_BINDING_SCATTERING_LUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &lut;
  write(gpu::TYN_EPIPOLAR_BINDING_LIGHT_COLOR_SUMS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE).pImageInfo = &colorSums;
  gpu.vk.vkUpdateDescriptorSets(gpu.device, kBindings, writes.data(), 0, nullptr);
}

void EpipolarTechnique::record(const Gpu& gpu, VkCommandBuffer cmd, const RecordTarget& target) {
  const EpipolarTechnique& owner = pipelineOwner_ != nullptr ? *pipelineOwner_ : *this;
  const std::uint32_t slot = target.slot;
  const Bindings& bindings = target.bindings;
  const gpu::EpipolarConstants& constants = constants_;
  const LightType light = light_;
  const bool buildTable = buildTable_;
  const VkExtent2D extent = target.extent;
  GpuTimer& timer = target.timer;
  std::vector<std::string>& passes = target.passes;
  writeDescriptors(gpu, slot, bindings);
  const VkDescriptorSet set = sets_[slot];
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set, 0, nullptr);
  gpu.vk.vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
  const std::uint32_t slices = textures_.slices;
  const std::uint32_t samples = textures_.samples;
  const VkAccessFlags readWrite = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;

  // Each pass's timestamps come before the barrier that starts it (see Context::recordScattering).
  auto pass = [&](const char* name, VkPipeline pipeline, auto&& dispatch) {
    timer.beginPass(gpu, cmd, name);
    memoryBarrier(gpu, cmd, kCompute | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, kCompute, readWrite);
    gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    dispatch();
    timer.endPass(gpu, cmd);
    passes.emplace_back(name);
  };

  // A dispatch sized on the GPU by the VkDispatchIndirectCommand at the start of `args`.
  auto indirectPass = [&](const char* name, VkPipeline pipeline, VkBuffer args, VkDeviceSize offset) {
    timer.beginPass(gpu, cmd, name);
    memoryBarrier(gpu, cmd, kCompute, VK_ACCESS_SHADER_WRITE_BIT, kCompute | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                  readWrite | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
    gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    gpu.cmdDispatchIndirect(cmd, args, offset);
    timer.endPass(gpu, cmd);
    passes.emplace_back(name);
  };

  // One barrier before the first pass: the sample textures are rewritten every frame (earlier
  // contents and reads discarded), and so are the blocks and a rebuilt table; the counts start at
  // zero once the previous frame's indirect reads are done.
  BarrierBatch start;
  const ImageUse discarded{VK_IMAGE_LAYOUT_UNDEFINED, kCompute, 0};
  const ImageUse written{VK_IMAGE_LAYOUT_GENERAL, kCompute, readWrite};
  for (const OwnedImage* image : {&textures_.endPoints, &textures_.coordinates, &textures_.scattering,
                                  &textures_.interpolationSource, &textures_.sliceUv, &textures_.tree,
                                  &textures_.colorSums}) {
    start.image(image->image, VK_IMAGE_ASPECT_COLOR_BIT, 0, discarded, written);
  }
  if (!placeholderInitialised_) {
    for (const OwnedImage* image : {&scatteringLutPlaceholder_, &shadowBlocksPlaceholder_}) {
      start.image(image->image, VK_IMAGE_ASPECT_COLOR_BIT, 0, discarded, written);
    }
    placeholderInitialised_ = true;
  }
  if (shadowBlocksUsed_) start.image(shadowBlocks_.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, discarded, written);
  if (buildTable) start.image(scatteringLut_.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, discarded, written);
  start.memory(kCompute | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  start.record(gpu, cmd);
  gpu.vk.vkCmdFillBuffer(cmd, fixupList_.buffer, 0, kFixupHeaderWords * sizeof(std::uint32_t), 0);
  gpu.vk.vkCmdFillBuffer(cmd, textures_.marchList.buffer, 0, kMarchHeaderWords * sizeof(std::uint32_t), 0);

  // One workgroup per slice: its end points, line, tree, colour sums, coordinates and refinement
  // (slice_setup.comp); its last group sizes the shadow test or the march's first round.
  pass("epipolar_slice_setup", owner.setupPipeline_, [&] { gpu.cmdDispatch(cmd, slices, 1, 1); });
  if (buildTable) {
    pass("epipolar_scattering_lut", owner.scatteringLutPipeline_, [&] {
      gpu.cmdDispatch(cmd, groups(gpu::TYN_SCATTERING_LUT_HEIGHT, gpu::TYN_EPIPOLAR_SLICE_GROUP), 1, 1);
    });
  }
  // A walked light's samples (point: no slice line) are all walked through its maps:
  // their blocks first, so that the walks cross every block that decides its texels in one step.
  if (shadowBlocksUsed_ && walksMaps_) {
    const std::uint32_t side = shadowBlocks_.extent.width;
    pass("epipolar_shadow_blocks", owner.shadowBlocksPipeline_, [&] {
      gpu.cmdDispatch(cmd, groups(side, gpu::TYN_EPIPOLAR_SHADOW_BLOCK_GROUP),
                           groups(side, gpu::TYN_EPIPOLAR_SHADOW_BLOCK_GROUP), shadowBlocks_.extent.height / side);
    });
  }
  // With a tree, samples whose whole ray it shows in shadow get zero without being marched; the
  // test's last group sizes the march's first round.
  if (!walksMaps_ && constants.tree_enabled != 0) {
    indirectPass("epipolar_shadow_test", owner.shadowTestPipeline_, textures_.marchList.buffer, kShadowTestArgsOffset);
  }
  // One thread per listed sample, sized on the GPU; a second round for the samples the intensity
  // refinement adds.
  const VkPipeline march = owner.marchPipelines_[static_cast<std::size_t>(light)][bindings.hasLightColor ? 1 : 0];
  indirectPass("epipolar_march", march, textures_.marchList.buffer, kMarchRoundArgsOffset[0]);
  if (constants.intensity_refinement_threshold < 1.0f) {
    pass("epipolar_refine_intensity", owner.refineIntensityPipeline_, [&] { gpu.cmdDispatch(cmd, slices, 1, 1); });
    indirectPass("epipolar_march_refined", march, textures_.marchList.buffer, kMarchRoundArgsOffset[1]);
  }
  // Interpolates along the slices and across them, a thread per 2×2 quad of the target; its last
  // group sizes the fix-up.
  pass("epipolar_unwarp", owner.unwarpPipelines_[serialFixup(marchParts_, light) ? 1 : 0], [&] {
    gpu.cmdDispatch(cmd, groups(groups(extent.width, 2), gpu::TYN_PIXEL_GROUP_SIZE),
                         groups(groups(extent.height, 2), gpu::TYN_PIXEL_GROUP_SIZE), 1);
  });
  // A directional light's fix-up crosses its map block by block (block_walk.glsl) where it walks
  // enough rays to repay the blocks; the unwarp decides, zero groups otherwise.
  if (shadowBlocksUsed_ && light == LightType::Directional && !walksMaps_) {
    indirectPass("epipolar_shadow_blocks", owner.shadowBlocksPipeline_, fixupArgs_.buffer, kDispatchArgsBytes);
  }

  // The fix-up dispatch is sized on the GPU by the number of flagged pixels.
  indirectPass("epipolar_fixup", owner.fixupPipelines_[static_cast<std::size_t>(light)], fixupArgs_.buffer, 0);

  if (bindings.debugView != DebugView::None) {
    pass("epipolar_debug_background", owner.debugBackgroundPipeline_, [&] {
      gpu.cmdDispatch(cmd, groups(extent.width, gpu::TYN_PIXEL_GROUP_SIZE),
                           groups(extent.height, gpu::TYN_PIXEL_GROUP_SIZE), 1);
    });
    if (bindings.debugView == DebugView::EpipolarSamples) {
      pass("epipolar_debug_samples", owner.debugSamplesPipeline_,
           [&] { gpu.cmdDispatch(cmd, groups(samples, 8), groups(slices, 8), 1); });
    } else {
      pass("epipolar_debug_fixup", owner.debugFixupPipeline_, [&] { gpu.cmdDispatchIndirect(cmd, fixupArgs_.buffer, 0); });
    }
  }

  // The counts go to the slot's readback buffer, read when the slot comes round again.
  memoryBarrier(gpu, cmd, kCompute, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_READ_BIT);
  const VkBufferCopy fixupCount{sizeof(std::uint32_t), 0, sizeof(std::uint32_t)};  // the pixels
  const std::array<VkBufferCopy, 2> marchCounts{
      VkBufferCopy{kMarchCountOffset, sizeof(std::uint32_t), sizeof(std::uint32_t)},
      VkBufferCopy{kMarchShadowedOffset, 2 * sizeof(std::uint32_t), 2 * sizeof(std::uint32_t)}};
  gpu.vk.vkCmdCopyBuffer(cmd, fixupList_.buffer, fixupReadback_[slot].buffer, 1, &fixupCount);
  gpu.vk.vkCmdCopyBuffer(cmd, textures_.marchList.buffer, fixupReadback_[slot].buffer,
                         static_cast<std::uint32_t>(marchCounts.size()), marchCounts.data());
  memoryBarrier(gpu, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                VK_ACCESS_HOST_READ_BIT);
  fixupPending_[slot] = true;
  fixupExtent_[slot] = extent;
  // Later passes (composite, AOV copies) read the targets after barriers of the caller's.
}

}  // namespace tyndall
