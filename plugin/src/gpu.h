// Small Vulkan building blocks shared by the passes: the device a context works with, images
// and buffers with their memory, barriers, and pipelines from embedded SPIR-V.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tyndall/tuning.h"
#include "vk_dispatch.h"

namespace tyndall {

struct Gpu {
  Dispatch vk;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;
  const VkAllocationCallbacks* allocator = nullptr;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  /// Device memory allocated through createImage / create*Buffer and not freed yet, bytes
  /// (Stats::deviceMemoryBytes). Counted here because every allocation goes through those helpers.
  mutable VkDeviceSize allocatedBytes = 0;
  /// Dispatches and pipeline barriers recorded through the helpers below since the context last
  /// reset them (Stats::dispatches, Stats::barriers); every pass records through them.
  mutable std::uint32_t dispatches = 0;
  mutable std::uint32_t barriers = 0;

  VkFormatFeatureFlags optimalFeatures(VkFormat format) const;
  void cmdDispatch(VkCommandBuffer cmd, std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    ++dispatches;
    vk.vkCmdDispatch(cmd, x, y, z);
  }
  void cmdDispatchIndirect(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset) const {
    ++dispatches;
    vk.vkCmdDispatchIndirect(cmd, buffer, offset);
  }
  void cmdPipelineBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst,
                          VkDependencyFlags flags, std::uint32_t memoryCount, const VkMemoryBarrier* memoryBarriers,
                          std::uint32_t bufferCount, const VkBufferMemoryBarrier* buffers, std::uint32_t imageCount,
                          const VkImageMemoryBarrier* images) const {
    ++barriers;
    vk.vkCmdPipelineBarrier(cmd, src, dst, flags, memoryCount, memoryBarriers, bufferCount, buffers, imageCount, images);
  }
};

/// An outcome for a failed Vulkan call, e.g. vkFailed("vkCreateImage", VK_ERROR_...).
Outcome vkFailed(const char* call, VkResult result);
/// An outcome with a status and message.
Outcome failure(Status status, std::string message);

/// A device-local image owned by Tyndall (size-dependent intermediate targets).
struct OwnedImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  VkDeviceSize bytes = 0;
};
Outcome createImage(const Gpu& gpu, VkFormat format, VkExtent2D extent, VkImageUsageFlags usage,
                    OwnedImage& out);
/// The same with `layers` array layers and a 2D_ARRAY view of all of them.
Outcome createImageArray(const Gpu& gpu, VkFormat format, VkExtent2D extent, std::uint32_t layers,
                         VkImageUsageFlags usage, OwnedImage& out);
void destroyImage(const Gpu& gpu, OwnedImage& image);

/// A persistently mapped, host-coherent buffer (per-frame constants).
struct MappedBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  VkDeviceSize size = 0;
  VkDeviceSize bytes = 0;  ///< memory allocated for it (≥ size)
};
Outcome createMappedBuffer(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage,
                           MappedBuffer& out);
/// A device-local buffer (`mapped` stays null).
Outcome createDeviceBuffer(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage, MappedBuffer& out);
void destroyBuffer(const Gpu& gpu, MappedBuffer& buffer);

/// How an image is used at one point of the command stream.
struct ImageUse {
  VkImageLayout layout;
  VkPipelineStageFlags stage;
  VkAccessFlags access;
};

/// Barriers gathered into one vkCmdPipelineBarrier: the union of their stages orders each at least
/// as strongly as its own call would, and a GPU waits once where it would wait per call. For
/// barriers that are adjacent in the command stream anyway (a frame's acquisitions and releases);
/// one image may appear once.
class BarrierBatch {
 public:
  void memory(VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
              VkAccessFlags dstAccess);
  /// Layers [layer, layer + layerCount) of mip 0.
  void image(VkImage image, VkImageAspectFlags aspect, std::uint32_t layer, ImageUse from, ImageUse to,
             std::uint32_t layerCount = 1);
  /// Records the batch (nothing when empty) and empties it.
  void record(const Gpu& gpu, VkCommandBuffer cmd);

 private:
  VkPipelineStageFlags src_ = 0;
  VkPipelineStageFlags dst_ = 0;
  VkAccessFlags srcAccess_ = 0;
  VkAccessFlags dstAccess_ = 0;
  bool hasMemory_ = false;
  std::vector<VkImageMemoryBarrier> images_;
};

/// Global memory barrier: `srcAccess` writes in `srcStage` made visible to `dstAccess` in `dstStage`.
void memoryBarrier(const Gpu& gpu, VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

/// Whole-image barrier (mip 0, one layer) from one use to the next.
void imageBarrier(const Gpu& gpu, VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  std::uint32_t layer, ImageUse from, ImageUse to);

/// Aspect flags to name in barriers for a format (depth-stencil formats need both).
VkImageAspectFlags barrierAspect(VkFormat format);
bool isDepthFormat(VkFormat format);

Outcome createShaderModule(const Gpu& gpu, std::span<const std::uint32_t> spirv,
                           VkShaderModule& out);
/// A compute pipeline from embedded SPIR-V (entry point "main"), optionally specialised. An `out`
/// that already holds a pipeline is kept: retrying after a failure compiles only what is missing.
Outcome createComputePipeline(const Gpu& gpu, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                              VkPipeline& out, const VkSpecializationInfo* specialization = nullptr);

/// constant_id of TYN_LIGHT_TYPE (shaders/common/medium.glsl): passes that integrate light are
/// built once per light type.
inline constexpr std::uint32_t kLightTypeConstantId = 7;

/// A compute pipeline with 32-bit specialisation constants, as (constant_id, value) pairs.
Outcome createSpecializedPipeline(const Gpu& gpu, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                                  std::span<const std::pair<std::uint32_t, std::uint32_t>> constants,
                                  VkPipeline& out);

/// One pipeline per light type (indexed by LightType), specialised on TYN_LIGHT_TYPE.
using LightPipelines = std::array<VkPipeline, 3>;
Outcome createLightPipelines(const Gpu& gpu, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                             LightPipelines& out);
void destroyPipelines(const Gpu& gpu, std::span<VkPipeline> pipelines);
/// A sampler without mip levels: `filter` both ways, clamped to the edge along u and w, `addressV`
/// along v.
Outcome createSampler(const Gpu& gpu, VkFilter filter, VkSamplerAddressMode addressV, VkSampler& out);
/// A pass's one descriptor set layout of `bindings` and its pipeline layout (that set, and the
/// push-constant range when `push` is given).
Outcome createLayouts(const Gpu& gpu, std::span<const VkDescriptorSetLayoutBinding> bindings,
                      const VkPushConstantRange* push, VkDescriptorSetLayout& setLayout,
                      VkPipelineLayout& pipelineLayout);
/// A pool holding exactly `sets.size()` sets of `layout` (one per frame slot), and the sets.
Outcome allocateDescriptorSets(const Gpu& gpu, VkDescriptorSetLayout layout,
                               std::span<const VkDescriptorPoolSize> perSetSizes, VkDescriptorPool& pool,
                               std::vector<VkDescriptorSet>& sets);
/// A descriptor write of `count` descriptors of `type` at `binding` of `set`; the caller points it
/// at its buffer or image infos.
VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                                     std::uint32_t count = 1);

/// What a scattering technique reads and writes in a frame: the host's depth buffer and shadow
/// maps (readable by compute shaders) and Tyndall's L_in target (storage, GENERAL). T is not a
/// technique's business: the composite computes it from the depth buffer.
struct ScatteringBindings {
  VkBuffer constants = VK_NULL_HANDLE;  ///< FrameConstants of the slot
  VkImageView depth = VK_NULL_HANDLE;
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  std::array<VkImageView, kMaxShadowMaps> shadowMaps{};
  std::array<VkImageLayout, kMaxShadowMaps> shadowLayouts{};
  VkImageView scattering = VK_NULL_HANDLE;
  /// The light-colour texture (readable by compute shaders), or a white texel without one.
  VkImageView lightColor = VK_NULL_HANDLE;
  VkImageLayout lightColorLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  bool hasLightColor = false;
  /// Each map's translucent layers (ShadowMapDesc::translucentLayers, 2D_ARRAY views); null: none.
  std::array<VkImageView, kMaxShadowMaps> translucentLayers{};
  std::array<VkImageLayout, kMaxShadowMaps> translucentLayouts{};
  /// One empty layer ((1, 0): no surface), 2D_ARRAY, bound where a map has no translucent layers.
  VkImageView noTranslucentLayers = VK_NULL_HANDLE;
  LightType light = LightType::Directional;
  /// The debug view's target (storage, GENERAL) when the frame asks for one, else null.
  VkImageView debug = VK_NULL_HANDLE;
  DebugView debugView = DebugView::None;
};

/// Descriptors of the shadow-map array; unused elements repeat map 0, because every element
/// must be valid without the partiallyBound feature.
std::array<VkDescriptorImageInfo, kMaxShadowMaps> shadowMapImageInfos(const ScatteringBindings& bindings);
/// Descriptors of the translucent layers' array; maps without layers get `noTranslucentLayers`.
std::array<VkDescriptorImageInfo, kMaxShadowMaps> translucentLayerImageInfos(const ScatteringBindings& bindings);

}  // namespace tyndall
