#include "prefiltered/prefiltered_technique.h"

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>

#include <glm/gtc/type_ptr.hpp>

#include "common/epipole.h"
#include "prefiltered/depth_bounds.h"
#include "prefiltered/prefiltered_plan.h"
#include "prefiltered/rectification_setup.h"
#include "prefiltered/weight_taps.h"
#include "tyndall_shaders.h"

namespace tyndall {

static_assert(static_cast<std::uint32_t>(PrefilteredBasis::Moments4_64) == gpu::TYN_PF_MOMENTS4_64);
static_assert(static_cast<std::uint32_t>(PrefilteredBasis::Moments4_128) == gpu::TYN_PF_MOMENTS4_128);
static_assert(static_cast<std::uint32_t>(PrefilteredBasis::Moments6_64) == gpu::TYN_PF_MOMENTS6_64);
static_assert(static_cast<std::uint32_t>(PrefilteredBasis::Moments6_96) == gpu::TYN_PF_MOMENTS6_96);
static_assert(static_cast<std::uint32_t>(PrefilteredBasis::Moments6_192) == gpu::TYN_PF_MOMENTS6_192);
static_assert(static_cast<std::uint32_t>(PrefilteredBasis::Fourier32) == gpu::TYN_PF_FOURIER32);
static_assert(static_cast<std::uint32_t>(PrefilteredSpacing::MeanTheta) == gpu::TYN_PF_SPACING_MEAN_THETA);
static_assert(static_cast<std::uint32_t>(PrefilteredSpacing::ReferenceRay) == gpu::TYN_PF_SPACING_REFERENCE_RAY);
static_assert(static_cast<std::uint32_t>(PrefilteredSpacing::FastestRay) == gpu::TYN_PF_SPACING_FASTEST_RAY);
static_assert(sizeof(gpu::PrefilteredConstants) == 9 * 16 + (64 + 2 * 16) + 8 * 16,
              "PrefilteredConstants must match its std140 layout");
// PrefilteredConstants' std140 offsets (shaders/prefiltered/prefiltered_constants.h), row by row.
constexpr std::size_t kPrefilteredRows = sizeof(gpu::NonLinearRectificationParams) +
                                         sizeof(gpu::ProjectiveRectificationParams);
static_assert(offsetof(gpu::PrefilteredConstants, map_columns) == kPrefilteredRows);
static_assert(offsetof(gpu::PrefilteredConstants, rows_wrap) == kPrefilteredRows + 12);
static_assert(offsetof(gpu::PrefilteredConstants, filtered_resampling) == kPrefilteredRows + 16);
static_assert(offsetof(gpu::PrefilteredConstants, host_map_size) == kPrefilteredRows + 28);
static_assert(offsetof(gpu::PrefilteredConstants, set_extinction) == kPrefilteredRows + 32);
static_assert(offsetof(gpu::PrefilteredConstants, channel_set) == kPrefilteredRows + 48);
static_assert(offsetof(gpu::PrefilteredConstants, epipole) == kPrefilteredRows + 64);
static_assert(offsetof(gpu::PrefilteredConstants, epipole_block_pixels) == kPrefilteredRows + 80);
static_assert(offsetof(gpu::PrefilteredConstants, trimmed) == kPrefilteredRows + 92);
static_assert(offsetof(gpu::PrefilteredConstants, overestimation) == kPrefilteredRows + 96);
static_assert(offsetof(gpu::PrefilteredConstants, depth_bounds) == kPrefilteredRows + 100);
static_assert(offsetof(gpu::PrefilteredConstants, short_ray_columns) == kPrefilteredRows + 112);
static_assert(offsetof(gpu::PrefilteredConstants, texel_walk_steps) == kPrefilteredRows + 116);
static_assert(sizeof(gpu::PrefilteredFixupArgs) == 32);
static_assert(offsetof(gpu::PrefilteredFixupArgs, rect_lo) == 16);

namespace {

constexpr std::uint32_t kBindings = gpu::TYN_PF_BINDING_COUNT;
constexpr VkPipelineStageFlags kCompute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
constexpr VkImageUsageFlags kMapUsage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
// The moment shadow map of the filtered resampling: Θ4* in 16-bit UNORM (peters2017 D.1), which
// every Vulkan device can filter linearly.
constexpr VkFormat kMomentMapFormat = VK_FORMAT_R16G16B16A16_UNORM;
// The row depth bounds (shaders/prefiltered/depth_bounds.h): min and max, rounded outwards to 16 bits.
constexpr VkFormat kDepthBoundsFormat = VK_FORMAT_R16G16_UNORM;
// The texel walk's depths (depth_bounds.h "Texel walk"): z1, z2 and w2 in 16-bit UNORM.
constexpr VkFormat kTexelDepthsFormat = VK_FORMAT_R16G16B16A16_UNORM;

// prefix_sums.glsl's specialisation per PrefixSumScheme (in its order): constant_id 0, threads per
// row; 1, rows per workgroup (which also sizes the dispatch); 2, the workgroup scan's walk.
constexpr std::array<std::array<std::uint32_t, 3>, 3> kPrefixSumSchemes{{
    {gpu::TYN_PF_ROW_THREADS, gpu::TYN_PF_ROWS_PER_GROUP, 0u},
    {1u, gpu::TYN_PF_THREAD_PER_ROW_GROUP, 0u},
    {gpu::TYN_PF_SCAN_THREADS, 1u, 1u},
}};

// The storage variants' images, as shaders/prefiltered/storage_variants.glsl declares them.
struct Storage {
  const char* name;
  VkFormat a;
  std::uint32_t layersA;
  VkFormat b;  // VK_FORMAT_UNDEFINED: one image
  std::span<const std::uint32_t> (*rectify)();
  std::span<const std::uint32_t> (*prefixSums)();
};
const std::array<Storage, 6> kStorage{{
    {"moments4_64", VK_FORMAT_R16G16B16A16_UNORM, 1, VK_FORMAT_UNDEFINED, shaders::rectify_moments4_64_comp,
     shaders::prefix_sums_moments4_64_comp},
    {"moments4_128", VK_FORMAT_R32G32B32A32_SFLOAT, 1, VK_FORMAT_UNDEFINED, shaders::rectify_moments4_128_comp,
     shaders::prefix_sums_moments4_128_comp},
    {"moments6_64", VK_FORMAT_A2B10G10R10_UNORM_PACK32, 2, VK_FORMAT_UNDEFINED, shaders::rectify_moments6_64_comp,
     shaders::prefix_sums_moments6_64_comp},
    {"moments6_96", VK_FORMAT_R16G16B16A16_UNORM, 1, VK_FORMAT_R16G16_UNORM, shaders::rectify_moments6_96_comp,
     shaders::prefix_sums_moments6_96_comp},
    {"moments6_192", VK_FORMAT_R32G32B32A32_SFLOAT, 1, VK_FORMAT_R32G32_SFLOAT, shaders::rectify_moments6_192_comp,
     shaders::prefix_sums_moments6_192_comp},
    {"fourier32", VK_FORMAT_R8G8B8A8_UNORM, gpu::TYN_FOURIER_LAYERS, VK_FORMAT_UNDEFINED,
     shaders::rectify_fourier32_comp, shaders::prefix_sums_fourier32_comp},
}};

std::uint32_t slotsOf(const Storage& s) { return s.layersA + (s.b != VK_FORMAT_UNDEFINED ? 1u : 0u); }

std::uint32_t groups(std::uint32_t count, std::uint32_t size) { return (count + size - 1) / size; }

bool usable(const Gpu& gpu, VkFormat format) {
  const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                      VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  return (gpu.optimalFeatures(format) & needed) == needed;
}

// Whole-image (every layer) transition that discards the contents: the maps are rewritten every
// frame, and the previous frame's compute reads must be done first.
void discardToGeneral(const Gpu& gpu, VkCommandBuffer cmd, std::initializer_list<const OwnedImage*> images) {
  std::vector<VkImageMemoryBarrier> barriers;
  for (const OwnedImage* image : images) {
    if (image->image == VK_NULL_HANDLE) continue;
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = 0;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image->image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
    barriers.push_back(b);
  }
  gpu.cmdPipelineBarrier(cmd, kCompute, kCompute, 0, 0, nullptr, 0, nullptr,
                              static_cast<std::uint32_t>(barriers.size()), barriers.data());
}

}  // namespace

const char* to_string(PrefilteredBasis basis) noexcept {
  const auto i = static_cast<std::uint32_t>(basis);
  return i < kStorage.size() ? kStorage[i].name : "unknown";
}

Outcome validatePrefilteredSettings(const PrefilteredSettings& s) {
  auto invalid = [](const char* message) { return failure(Status::InvalidArgument, message); };
  if (static_cast<std::uint32_t>(s.basis) > static_cast<std::uint32_t>(PrefilteredBasis::Fourier32)) {
    return invalid("prefiltered.basis is not a PrefilteredBasis");
  }
  if (static_cast<std::uint32_t>(s.rectification) > static_cast<std::uint32_t>(PrefilteredRectification::Projective)) {
    return invalid("prefiltered.rectification is not a PrefilteredRectification");
  }
  if (s.rows < 16 || s.rows > 4096) return invalid("prefiltered.rows must be in 16..4096");
  if (s.columns < 16 || s.columns > 4096) return invalid("prefiltered.columns must be in 16..4096");
  if (static_cast<std::uint32_t>(s.spacing) > static_cast<std::uint32_t>(PrefilteredSpacing::FastestRay)) {
    return invalid("prefiltered.spacing is not a PrefilteredSpacing");
  }
  if (s.rayWeightTaps < 1 || s.rayWeightTaps > gpu::TYN_PF_MAX_TAPS) return invalid("prefiltered.rayWeightTaps must be in 1..8");
  if (s.rayWeightTaps > 1 && s.spacing != PrefilteredSpacing::FastestRay) {
    return invalid("prefiltered.rayWeightTaps > 1 needs prefiltered.spacing = FastestRay (the re-weighting is "
                   "non-negative only from the slice's fastest ray)");
  }
  if (static_cast<std::uint32_t>(s.prefixSums) > static_cast<std::uint32_t>(PrefixSumScheme::WorkgroupScan)) {
    return invalid("prefiltered.prefixSums is not a PrefixSumScheme");
  }
  if (!(s.overestimation >= 0.0f && s.overestimation <= 1.0f)) return invalid("prefiltered.overestimation must be in [0, 1]");
  if (s.epipoleBlockPixels > 256) return invalid("prefiltered.epipoleBlockPixels must be in 0..256");
  if (s.shortRayColumns > s.columns) return invalid("prefiltered.shortRayColumns must be in 0..columns");
  if (s.texelWalkSteps > 64) return invalid("prefiltered.texelWalkSteps must be in 0..64");
  if (!isScatteringResolution(s.resolution)) return invalid("prefiltered.resolution is not a ScatteringResolution");
  return {};
}

Outcome PrefilteredTechnique::create(const Gpu& gpu, const TechniqueResources& resources) {
  scatteringFormat_ = resources.scatteringFormat;
  const VkSampler nearest = resources.nearest;
  const VkSampler linear = resources.linear;
  const std::uint32_t slots = resources.slots;
  // Rows of a full-circle non-linear map continue across φ = ±π.
  if (Outcome o = createSampler(gpu, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, prefixSampler_); !o) return o;

  for (std::uint32_t i = 0; i < kStorage.size(); ++i) {
    const Storage& s = kStorage[i];
    if (usable(gpu, s.a) && (s.b == VK_FORMAT_UNDEFINED || usable(gpu, s.b))) supportedVariants_ |= 1u << i;
  }
  momentMapSupported_ = usable(gpu, kMomentMapFormat);
  depthBoundsSupported_ = (gpu.optimalFeatures(kDepthBoundsFormat) & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0;
  texelDepthsSupported_ = (gpu.optimalFeatures(kTexelDepthsFormat) & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0;

  const std::array<VkSampler, kMaxShadowMaps> nearestSamplers{nearest, nearest, nearest, nearest, nearest, nearest};
  const VkShaderStageFlags stage = VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorType image = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  const VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  const std::array<VkDescriptorSetLayoutBinding, kBindings> bindings{{
      {gpu::TYN_PF_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_DEPTH, image, 1, stage, nearestSamplers.data()},
      {gpu::TYN_PF_BINDING_SHADOW_MAPS, image, kMaxShadowMaps, stage, nearestSamplers.data()},
      {gpu::TYN_PF_BINDING_CONSTANTS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_OUT_SCATTERING, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_LIGHT_COLOR, image, 1, stage, &linear},
      {gpu::TYN_PF_BINDING_MOMENT_MAP, image, 1, stage, &linear},
      {gpu::TYN_PF_BINDING_MOMENT_MAP_STORAGE, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_RECTIFIED_A, image, 1, stage, nearestSamplers.data()},
      {gpu::TYN_PF_BINDING_RECTIFIED_B, image, 1, stage, nearestSamplers.data()},
      {gpu::TYN_PF_BINDING_RECTIFIED_A_STORAGE, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_RECTIFIED_B_STORAGE, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_PREFIX_A, image, 1, stage, &prefixSampler_},
      {gpu::TYN_PF_BINDING_PREFIX_B, image, 1, stage, &prefixSampler_},
      {gpu::TYN_PF_BINDING_PREFIX_A_STORAGE, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_PREFIX_B_STORAGE, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_FIXUP_ARGS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_DEPTH_BOUNDS_TEXELS, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_DEPTH_BOUNDS_PREFIX, storage, 1, stage, nullptr},
      {gpu::TYN_PF_BINDING_TEXEL_DEPTHS, storage, 1, stage, nullptr},
  }};
  if (Outcome o = createLayouts(gpu, bindings, nullptr, setLayout_, pipelineLayout_); !o) return o;

  const std::array<VkDescriptorPoolSize, 4> sizes{{
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1 + kMaxShadowMaps + 6},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 9},
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
  }};
  sets_.resize(slots);
  if (Outcome o = allocateDescriptorSets(gpu, setLayout_, sizes, pool_, sets_); !o) return o;
  constants_.resize(slots);
  for (MappedBuffer& buffer : constants_) {
    if (Outcome o = createMappedBuffer(gpu, sizeof(gpu::PrefilteredConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, buffer);
        !o) {
      return o;
    }
  }
  return createDeviceBuffer(gpu, sizeof(gpu::PrefilteredFixupArgs),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, fixupArgs_);
}

void PrefilteredTechnique::destroyMaps(const Gpu& gpu, Maps& maps) {
  destroyImage(gpu, maps.texelDepths);
  destroyImage(gpu, maps.depthBoundsPrefix);
  destroyImage(gpu, maps.depthBoundsTexels);
  destroyImage(gpu, maps.prefixB);
  destroyImage(gpu, maps.prefixA);
  destroyImage(gpu, maps.rectifiedB);
  destroyImage(gpu, maps.rectifiedA);
  destroyImage(gpu, maps.momentMap);
  maps = Maps{};
}

Outcome PrefilteredTechnique::createPipelines(const Gpu& gpu) {
  if (pipelineOwner_ != nullptr) return pipelineOwner_->createPipelines(gpu);
  if (pipelinesReady_) return {};
  auto make = [&](std::span<const std::uint32_t> spirv, VkPipeline& out, const VkSpecializationInfo* spec = nullptr) {
    return createComputePipeline(gpu, pipelineLayout_, spirv, out, spec);
  };
  if (Outcome o = make(shaders::moment_shadow_map_comp(), momentMapPipeline_); !o) return o;
  if (Outcome o = make(shaders::epipole_fixup_args_comp(), fixupArgsPipeline_); !o) return o;
  const bool full = scatteringFormat_ == kFullScatteringFormat;
  if (Outcome o = make(full ? shaders::epipole_fixup_rgba32f_comp() : shaders::epipole_fixup_comp(), fixupPipeline_);
      !o) {
    return o;
  }
  // prefix_sums.glsl's workgroup size and walk per PrefixSumScheme (kPrefixSumSchemes).
  const std::array<VkSpecializationMapEntry, 3> schemeEntries{{{0, 0, 4}, {1, 4, 4}, {2, 8, 4}}};
  // evaluate.comp's storage variant (constant_id 0).
  const VkSpecializationMapEntry basisEntry{0, 0, 4};
  for (std::uint32_t i = 0; i < kStorage.size(); ++i) {
    if (Outcome o = make(kStorage[i].rectify(), rectifyPipelines_[i]); !o) return o;
    for (std::size_t scheme = 0; scheme < kPrefixSumSchemes.size(); ++scheme) {
      const VkSpecializationInfo spec{3, schemeEntries.data(), sizeof(kPrefixSumSchemes[scheme]),
                                      kPrefixSumSchemes[scheme].data()};
      if (Outcome o = make(kStorage[i].prefixSums(), prefixSumPipelines_[scheme][i], &spec); !o) return o;
    }
    const VkSpecializationInfo basisSpec{1, &basisEntry, sizeof(i), &i};
    if (Outcome o = make(full ? shaders::evaluate_rgba32f_comp() : shaders::evaluate_comp(), evaluatePipelines_[i],
                         &basisSpec);
        !o) {
      return o;
    }
  }

  pipelinesReady_ = true;
  return {};
}

void PrefilteredTechnique::destroy(const Gpu& gpu) {
  retired_.destroyAll([&](Maps& maps) { destroyMaps(gpu, maps); });
  destroyMaps(gpu, maps_);
  destroyBuffer(gpu, fixupArgs_);
  for (MappedBuffer& buffer : constants_) destroyBuffer(gpu, buffer);
  constants_.clear();
  if (pool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, pool_, gpu.allocator);
  std::vector<VkPipeline> pipelines{momentMapPipeline_, fixupArgsPipeline_, fixupPipeline_};
  for (std::uint32_t i = 0; i < kStorage.size(); ++i) {
    for (VkPipeline p : {rectifyPipelines_[i], evaluatePipelines_[i]}) pipelines.push_back(p);
    for (const auto& scheme : prefixSumPipelines_) pipelines.push_back(scheme[i]);
  }
  for (VkPipeline pipeline : pipelines) {
    if (pipeline != VK_NULL_HANDLE) gpu.vk.vkDestroyPipeline(gpu.device, pipeline, gpu.allocator);
  }
  if (pipelineLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipelineLayout(gpu.device, pipelineLayout_, gpu.allocator);
  if (setLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, setLayout_, gpu.allocator);
  if (prefixSampler_ != VK_NULL_HANDLE) gpu.vk.vkDestroySampler(gpu.device, prefixSampler_, gpu.allocator);
  *this = PrefilteredTechnique{};
}

Outcome PrefilteredTechnique::ensureMaps(const Gpu& gpu, const MapKey& key, std::uint64_t frameIndex) {
  if (maps_.key == key) return {};
  // Frames still in flight may use the old maps: they are destroyed once those have completed.
  if (maps_.key.columns != 0) {
    retired_.retire(frameIndex, maps_);
    maps_ = Maps{};
  }
  const Storage& s = kStorage[key.basis];
  Maps fresh;
  fresh.key = key;
  const VkExtent2D extent{key.columns, key.rows};
  const VkExtent2D boundsExtent = key.depthBounds ? extent : VkExtent2D{1, 1};
  Outcome outcome =
      createImage(gpu, kMomentMapFormat, {key.momentMapSize, key.momentMapSize}, kMapUsage, fresh.momentMap);
  if (outcome) outcome = createImageArray(gpu, s.a, extent, s.layersA, kMapUsage, fresh.rectifiedA);
  if (outcome) outcome = createImageArray(gpu, s.a, extent, s.layersA * key.sets, kMapUsage, fresh.prefixA);
  if (outcome && s.b != VK_FORMAT_UNDEFINED) {
    outcome = createImageArray(gpu, s.b, extent, 1, kMapUsage, fresh.rectifiedB);
    if (outcome) outcome = createImageArray(gpu, s.b, extent, key.sets, kMapUsage, fresh.prefixB);
  }
  // The texel image also holds each row's min/max tree beside its texels (depth_bounds.h).
  const VkExtent2D treeExtent =
      key.depthBounds
          ? VkExtent2D{static_cast<std::uint32_t>(gpu::tyn_depth_bounds_tree_width(static_cast<int>(key.columns))), key.rows}
          : VkExtent2D{1, 1};
  if (outcome) {
    outcome = createImage(gpu, kDepthBoundsFormat, treeExtent, VK_IMAGE_USAGE_STORAGE_BIT, fresh.depthBoundsTexels);
  }
  if (outcome) {
    outcome = createImage(gpu, kDepthBoundsFormat, boundsExtent, VK_IMAGE_USAGE_STORAGE_BIT, fresh.depthBoundsPrefix);
  }
  if (outcome) {
    outcome = createImage(gpu, kTexelDepthsFormat, key.texelWalk ? extent : VkExtent2D{1, 1},
                          VK_IMAGE_USAGE_STORAGE_BIT, fresh.texelDepths);
  }
  if (!outcome) {
    destroyMaps(gpu, fresh);
    return outcome;
  }
  maps_ = fresh;
  return {};
}

Outcome PrefilteredTechnique::ensurePipelines(const Gpu& gpu, const FrameDesc& frame, bool& compiled) {
  if (pipelineOwner_ != nullptr) return pipelineOwner_->ensurePipelines(gpu, frame, compiled);
  compiled = !pipelinesReady_;
  return createPipelines(gpu);
}

ResolutionRequest PrefilteredTechnique::resolution(const FrameDesc& frame, const ProfileChoice& choice) const {
  if (frame.resolution) return {*frame.resolution, 0};
  const auto& s = frame.prefiltered != nullptr ? *frame.prefiltered : choice.prefiltered;
  return {s.resolution, s.minimumRows};
}

Outcome PrefilteredTechnique::prepare(const Gpu& gpu, const FrameInputs& in, TechniqueReport& report) {
  const PrefilteredSettings& settings = in.frame.prefiltered != nullptr ? *in.frame.prefiltered : in.choice.prefiltered;
  PrefilteredStats decisions;
  if (Outcome o = prepareFrame(gpu, in.frame, settings, in.extent, in.slot, in.frameIndex, decisions, report.note);
      !o) {
    return o;
  }
  report.prefiltered = decisions;
  return {};
}

void PrefilteredTechnique::releaseRetired(const Gpu& gpu, std::uint64_t frameIndex, std::uint32_t framesInFlight) {
  retired_.release(frameIndex, framesInFlight, [&](Maps& maps) { destroyMaps(gpu, maps); });
}

Outcome PrefilteredTechnique::prepareFrame(const Gpu& gpu, const FrameDesc& frame, const PrefilteredSettings& settings,
                                           VkExtent2D extent, std::uint32_t slot, std::uint64_t frameIndex,
                                           PrefilteredStats& decisions, std::string& note) {
  const std::uint32_t basis = static_cast<std::uint32_t>(settings.basis);
  const Storage& storage = kStorage[basis];
  if ((supportedVariants_ & (1u << basis)) == 0) {
    return failure(Status::UnsupportedFeature, std::string("prefiltered.basis ") + storage.name +
                                                   ": the device cannot store and linearly filter its formats");
  }
  if (settings.filteredResampling && !momentMapSupported_) {
    return failure(Status::UnsupportedFeature,
                   "prefiltered.filteredResampling: the device cannot store and filter R16G16B16A16_UNORM");
  }
  if (settings.depthBounds && !depthBoundsSupported_) {
    return failure(Status::UnsupportedFeature, "prefiltered.depthBounds: the device cannot store R16G16_UNORM");
  }

  PrefilteredFramePlan frame_plan;
  if (Outcome o = planPrefilteredFrame(frame, settings, extent, frame_plan); !o) return o;
  if (frame_plan.texelWalkSteps > 0 && !texelDepthsSupported_) {
    return failure(Status::UnsupportedFeature, "prefiltered.texelWalkSteps: the device cannot store R16G16B16A16_UNORM");
  }
  const std::uint32_t mapSize = frame.shadowMaps[0].depth.extent.width;
  const MapKey key{basis, settings.columns, settings.rows, frame_plan.decisions.prefixSumSets,
                   settings.filteredResampling ? mapSize : 1u, settings.depthBounds, frame_plan.texelWalkSteps > 0};
  if (Outcome o = ensureMaps(gpu, key, frameIndex); !o) {
    return o;
  }
  std::memcpy(constants_[slot].mapped, &frame_plan.constants, sizeof(frame_plan.constants));
  decisions = frame_plan.decisions;
  plan_.basis = basis;
  plan_.sets = frame_plan.decisions.prefixSumSets;
  plan_.filtered = settings.filteredResampling;
  plan_.prefixSums = settings.prefixSums;
  plan_.epipoleBlock = frame_plan.decisions.epipoleBlockMarched;
  plan_.boundsTree = frame_plan.decisions.trimmedSegments;
  note += frame_plan.note;
  return {};
}

void PrefilteredTechnique::writeDescriptors(const Gpu& gpu, std::uint32_t slot, const Bindings& b) {
  const VkDescriptorSet set = sets_[slot];
  const VkDescriptorBufferInfo frameConstants{b.constants, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo constants{constants_[slot].buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo args{fixupArgs_.buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorImageInfo depth{VK_NULL_HANDLE, b.depth, b.depthLayout};
  const std::array<VkDescriptorImageInfo, kMaxShadowMaps> shadow = shadowMapImageInfos(b);
  auto general = [](const OwnedImage& image, const OwnedImage& fallback) {
    return VkDescriptorImageInfo{VK_NULL_HANDLE, image.view != VK_NULL_HANDLE ? image.view : fallback.view,
                                 VK_IMAGE_LAYOUT_GENERAL};
  };
  // Image B of a one-image variant is never read or written; A stands in to keep the set valid.
  const VkDescriptorImageInfo scattering{VK_NULL_HANDLE, b.scattering, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo moments = general(maps_.momentMap, maps_.momentMap);
  const VkDescriptorImageInfo rectA = general(maps_.rectifiedA, maps_.rectifiedA);
  const VkDescriptorImageInfo rectB = general(maps_.rectifiedB, maps_.rectifiedA);
  const VkDescriptorImageInfo prefixA = general(maps_.prefixA, maps_.prefixA);
  const VkDescriptorImageInfo prefixB = general(maps_.prefixB, maps_.prefixA);
  const VkDescriptorImageInfo boundsTexels = general(maps_.depthBoundsTexels, maps_.depthBoundsTexels);
  const VkDescriptorImageInfo boundsPrefix = general(maps_.depthBoundsPrefix, maps_.depthBoundsPrefix);
  const VkDescriptorImageInfo texelDepths = general(maps_.texelDepths, maps_.texelDepths);

  std::array<VkWriteDescriptorSet, kBindings> writes{};
  auto write = [&](std::uint32_t binding, VkDescriptorType type, std::uint32_t count) -> VkWriteDescriptorSet& {
    return writes[binding] = descriptorWrite(set, binding, type, count);
  };
  const VkDescriptorType image = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  const VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  write(gpu::TYN_PF_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1).pBufferInfo = &frameConstants;
  write(gpu::TYN_PF_BINDING_DEPTH, image, 1).pImageInfo = &depth;
  write(gpu::TYN_PF_BINDING_SHADOW_MAPS, image, kMaxShadowMaps).pImageInfo = shadow.data();
  write(gpu::TYN_PF_BINDING_CONSTANTS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1).pBufferInfo = &constants;
  write(gpu::TYN_PF_BINDING_OUT_SCATTERING, storage, 1).pImageInfo = &scattering;
  const VkDescriptorImageInfo lightColor{VK_NULL_HANDLE, b.lightColor, b.lightColorLayout};
  write(gpu::TYN_PF_BINDING_LIGHT_COLOR, image, 1).pImageInfo = &lightColor;
  write(gpu::TYN_PF_BINDING_MOMENT_MAP, image, 1).pImageInfo = &moments;
  write(gpu::TYN_PF_BINDING_MOMENT_MAP_STORAGE, storage, 1).pImageInfo = &moments;
  write(gpu::TYN_PF_BINDING_RECTIFIED_A, image, 1).pImageInfo = &rectA;
  write(gpu::TYN_PF_BINDING_RECTIFIED_B, image, 1).pImageInfo = &rectB;
  write(gpu::TYN_PF_BINDING_RECTIFIED_A_STORAGE, storage, 1).pImageInfo = &rectA;
  write(gpu::TYN_PF_BINDING_RECTIFIED_B_STORAGE, storage, 1).pImageInfo = &rectB;
  write(gpu::TYN_PF_BINDING_PREFIX_A, image, 1).pImageInfo = &prefixA;
  write(gpu::TYN_PF_BINDING_PREFIX_B, image, 1).pImageInfo = &prefixB;
  write(gpu::TYN_PF_BINDING_PREFIX_A_STORAGE, storage, 1).pImageInfo = &prefixA;
  write(gpu::TYN_PF_BINDING_PREFIX_B_STORAGE, storage, 1).pImageInfo = &prefixB;
  write(gpu::TYN_PF_BINDING_FIXUP_ARGS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1).pBufferInfo = &args;
  write(gpu::TYN_PF_BINDING_DEPTH_BOUNDS_TEXELS, storage, 1).pImageInfo = &boundsTexels;
  write(gpu::TYN_PF_BINDING_DEPTH_BOUNDS_PREFIX, storage, 1).pImageInfo = &boundsPrefix;
  write(gpu::TYN_PF_BINDING_TEXEL_DEPTHS, storage, 1).pImageInfo = &texelDepths;
  gpu.vk.vkUpdateDescriptorSets(gpu.device, kBindings, writes.data(), 0, nullptr);
}

void PrefilteredTechnique::record(const Gpu& gpu, VkCommandBuffer cmd, const RecordTarget& target) {
  const PrefilteredTechnique& owner = pipelineOwner_ != nullptr ? *pipelineOwner_ : *this;
  const std::uint32_t slot = target.slot;
  const Bindings& bindings = target.bindings;
  const VkExtent2D extent = target.extent;
  GpuTimer& timer = target.timer;
  std::vector<std::string>& passes = target.passes;
  writeDescriptors(gpu, slot, bindings);
  const VkDescriptorSet set = sets_[slot];
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set, 0, nullptr);
  const VkAccessFlags readWrite = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  const Storage& storage = kStorage[plan_.basis];

  // Each pass's timestamps come before the barrier that starts it (see Context::recordScattering).
  auto pass = [&](const char* name, VkPipeline pipeline, auto&& dispatch) {
    timer.beginPass(gpu, cmd, name);
    memoryBarrier(gpu, cmd, kCompute, VK_ACCESS_SHADER_WRITE_BIT, kCompute, readWrite);
    gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    dispatch();
    timer.endPass(gpu, cmd);
    passes.emplace_back(name);
  };

  // Every map is bound (the evaluation's descriptors name the prefix sums even when it skips
  // them), so every map is in GENERAL.
  discardToGeneral(gpu, cmd, {&maps_.momentMap, &maps_.rectifiedA, &maps_.rectifiedB, &maps_.prefixA, &maps_.prefixB,
                              &maps_.depthBoundsTexels, &maps_.depthBoundsPrefix, &maps_.texelDepths});
  if (plan_.filtered) {
    const std::uint32_t size = maps_.key.momentMapSize;
    pass("prefiltered_moment_shadow_map", owner.momentMapPipeline_, [&] {
      gpu.cmdDispatch(cmd, groups(size, gpu::TYN_PF_TEXEL_GROUP), groups(size, gpu::TYN_PF_TEXEL_GROUP), 1);
    });
  }
  pass("prefiltered_rectify", owner.rectifyPipelines_[plan_.basis], [&] {
    gpu.cmdDispatch(cmd, groups(maps_.key.columns, gpu::TYN_PF_TEXEL_GROUP),
                         groups(maps_.key.rows, gpu::TYN_PF_TEXEL_GROUP), 1);
  });
  const auto scheme = static_cast<std::size_t>(plan_.prefixSums);
  const VkPipeline prefix = owner.prefixSumPipelines_[scheme][plan_.basis];
  const std::uint32_t rowsPerGroup = kPrefixSumSchemes[scheme][1];
  pass("prefiltered_prefix_sums", prefix, [&] {
    // One more layer builds the rows' min/max trees for the trimmed segments (prefix_sums.glsl).
    gpu.cmdDispatch(cmd, 1, groups(maps_.key.rows, rowsPerGroup),
                         plan_.sets * slotsOf(storage) + (plan_.boundsTree ? 1u : 0u));
  });
  pass("prefiltered_evaluate", owner.evaluatePipelines_[plan_.basis], [&] {
    gpu.cmdDispatch(cmd, groups(extent.width, gpu::TYN_PIXEL_GROUP_SIZE),
                         groups(extent.height, gpu::TYN_PIXEL_GROUP_SIZE), 1);
  });
  if (plan_.epipoleBlock) {
    // The previous frame's indirect read of the arguments must be done before they are rewritten.
    timer.beginPass(gpu, cmd, "prefiltered_epipole_fixup_args");
    memoryBarrier(gpu, cmd, kCompute | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, VK_ACCESS_SHADER_WRITE_BIT, kCompute,
                  readWrite);
    gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, owner.fixupArgsPipeline_);
    gpu.cmdDispatch(cmd, 1, 1, 1);
    timer.endPass(gpu, cmd);
    passes.emplace_back("prefiltered_epipole_fixup_args");

    timer.beginPass(gpu, cmd, "prefiltered_epipole_fixup");
    memoryBarrier(gpu, cmd, kCompute, VK_ACCESS_SHADER_WRITE_BIT, kCompute | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                  readWrite | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
    gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, owner.fixupPipeline_);
    gpu.cmdDispatchIndirect(cmd, fixupArgs_.buffer, 0);
    timer.endPass(gpu, cmd);
    passes.emplace_back("prefiltered_epipole_fixup");
  }
  // Later passes (composite, AOV copies) read the targets after a barrier of the caller's.
  memoryBarrier(gpu, cmd, kCompute, VK_ACCESS_SHADER_WRITE_BIT, kCompute, VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace tyndall
