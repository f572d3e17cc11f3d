#include "gpu.h"

namespace tyndall {

VkFormatFeatureFlags Gpu::optimalFeatures(VkFormat format) const {
  VkFormatProperties props{};
  vk.vkGetPhysicalDeviceFormatProperties(physicalDevice, format, &props);
  return props.optimalTilingFeatures;
}

Outcome vkFailed(const char* call, VkResult result) {
  Outcome outcome;
  outcome.status = Status::VulkanError;
  outcome.vkResult = result;
  outcome.message = std::string(call) + " failed with VkResult " + std::to_string(static_cast<int>(result));
  return outcome;
}

Outcome failure(Status status, std::string message) {
  Outcome outcome;
  outcome.status = status;
  outcome.message = std::move(message);
  return outcome;
}

namespace {

bool findMemoryType(const Gpu& gpu, std::uint32_t typeBits, VkMemoryPropertyFlags wanted,
                    std::uint32_t& index) {
  for (std::uint32_t i = 0; i < gpu.memory.memoryTypeCount; ++i) {
    if ((typeBits & (1u << i)) != 0 &&
        (gpu.memory.memoryTypes[i].propertyFlags & wanted) == wanted) {
      index = i;
      return true;
    }
  }
  return false;
}

Outcome allocate(const Gpu& gpu, const VkMemoryRequirements& requirements,
                 VkMemoryPropertyFlags wanted, VkDeviceMemory& memory) {
  std::uint32_t type = 0;
  if (!findMemoryType(gpu, requirements.memoryTypeBits, wanted, type)) {
    return failure(Status::UnsupportedFeature, "no memory type with the required properties");
  }
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type;
  VkResult result = gpu.vk.vkAllocateMemory(gpu.device, &info, gpu.allocator, &memory);
  if (result != VK_SUCCESS) return vkFailed("vkAllocateMemory", result);
  gpu.allocatedBytes += requirements.size;
  return {};
}

}  // namespace

namespace {

// One 2D image of `layers` layers with its memory and a view of every layer: a 2D view when
// `array` is false (layers = 1), else a 2D_ARRAY view.
Outcome buildImage(const Gpu& gpu, VkFormat format, VkExtent2D extent, std::uint32_t layers, bool array,
                   VkImageUsageFlags usage, OwnedImage& out) {
  out.format = format;
  out.extent = extent;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {extent.width, extent.height, 1};
  info.mipLevels = 1;
  info.arrayLayers = layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkResult result = gpu.vk.vkCreateImage(gpu.device, &info, gpu.allocator, &out.image);
  if (result != VK_SUCCESS) return vkFailed("vkCreateImage", result);

  VkMemoryRequirements requirements{};
  gpu.vk.vkGetImageMemoryRequirements(gpu.device, out.image, &requirements);
  Outcome outcome = allocate(gpu, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, out.memory);
  if (!outcome) return outcome;
  out.bytes = requirements.size;
  result = gpu.vk.vkBindImageMemory(gpu.device, out.image, out.memory, 0);
  if (result != VK_SUCCESS) return vkFailed("vkBindImageMemory", result);

  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = out.image;
  view.viewType = array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
  result = gpu.vk.vkCreateImageView(gpu.device, &view, gpu.allocator, &out.view);
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkCreateImageView", result);
}

// A failed creation leaves nothing behind: callers create lazily where `image` is null, and a
// half-built image would be taken for a whole one (and never freed) by the next frame.
Outcome createImageLayers(const Gpu& gpu, VkFormat format, VkExtent2D extent, std::uint32_t layers, bool array,
                          VkImageUsageFlags usage, OwnedImage& out) {
  Outcome outcome = buildImage(gpu, format, extent, layers, array, usage, out);
  if (!outcome) destroyImage(gpu, out);
  return outcome;
}

}  // namespace

Outcome createImage(const Gpu& gpu, VkFormat format, VkExtent2D extent, VkImageUsageFlags usage,
                    OwnedImage& out) {
  return createImageLayers(gpu, format, extent, 1, false, usage, out);
}

Outcome createImageArray(const Gpu& gpu, VkFormat format, VkExtent2D extent, std::uint32_t layers,
                         VkImageUsageFlags usage, OwnedImage& out) {
  return createImageLayers(gpu, format, extent, layers, true, usage, out);
}

void destroyImage(const Gpu& gpu, OwnedImage& image) {
  if (image.view != VK_NULL_HANDLE) gpu.vk.vkDestroyImageView(gpu.device, image.view, gpu.allocator);
  if (image.image != VK_NULL_HANDLE) gpu.vk.vkDestroyImage(gpu.device, image.image, gpu.allocator);
  if (image.memory != VK_NULL_HANDLE) {
    gpu.vk.vkFreeMemory(gpu.device, image.memory, gpu.allocator);
    gpu.allocatedBytes -= image.bytes;
  }
  image = OwnedImage{};
}

namespace {

Outcome buildBuffer(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memory,
                    bool map, MappedBuffer& out) {
  out.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkResult result = gpu.vk.vkCreateBuffer(gpu.device, &info, gpu.allocator, &out.buffer);
  if (result != VK_SUCCESS) return vkFailed("vkCreateBuffer", result);
  VkMemoryRequirements requirements{};
  gpu.vk.vkGetBufferMemoryRequirements(gpu.device, out.buffer, &requirements);
  Outcome outcome = allocate(gpu, requirements, memory, out.memory);
  if (!outcome) return outcome;
  out.bytes = requirements.size;
  result = gpu.vk.vkBindBufferMemory(gpu.device, out.buffer, out.memory, 0);
  if (result != VK_SUCCESS) return vkFailed("vkBindBufferMemory", result);
  if (!map) return {};
  result = gpu.vk.vkMapMemory(gpu.device, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped);
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkMapMemory", result);
}

// As for images, a failed creation leaves nothing behind.
Outcome createBuffer(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memory,
                     bool map, MappedBuffer& out) {
  Outcome outcome = buildBuffer(gpu, size, usage, memory, map, out);
  if (!outcome) destroyBuffer(gpu, out);
  return outcome;
}

}  // namespace

Outcome createMappedBuffer(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage,
                           MappedBuffer& out) {
  return createBuffer(gpu, size, usage, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                      true, out);
}

Outcome createDeviceBuffer(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage, MappedBuffer& out) {
  return createBuffer(gpu, size, usage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, false, out);
}

void destroyBuffer(const Gpu& gpu, MappedBuffer& buffer) {
  if (buffer.buffer != VK_NULL_HANDLE) gpu.vk.vkDestroyBuffer(gpu.device, buffer.buffer, gpu.allocator);
  if (buffer.memory != VK_NULL_HANDLE) {
    gpu.vk.vkFreeMemory(gpu.device, buffer.memory, gpu.allocator);
    gpu.allocatedBytes -= buffer.bytes;
  }
  buffer = MappedBuffer{};
}

void memoryBarrier(const Gpu& gpu, VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = srcAccess;
  barrier.dstAccessMask = dstAccess;
  gpu.cmdPipelineBarrier(cmd, srcStage, dstStage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void BarrierBatch::memory(VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                          VkAccessFlags dstAccess) {
  src_ |= srcStage;
  dst_ |= dstStage;
  srcAccess_ |= srcAccess;
  dstAccess_ |= dstAccess;
  hasMemory_ = true;
}

namespace {

VkImageMemoryBarrier imageMemoryBarrier(VkImage image, VkImageAspectFlags aspect, std::uint32_t layer, ImageUse from,
                                        ImageUse to, std::uint32_t layerCount = 1) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = from.access;
  barrier.dstAccessMask = to.access;
  barrier.oldLayout = from.layout;
  barrier.newLayout = to.layout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, 0, 1, layer, layerCount};
  return barrier;
}

}  // namespace

void BarrierBatch::image(VkImage image, VkImageAspectFlags aspect, std::uint32_t layer, ImageUse from, ImageUse to,
                         std::uint32_t layerCount) {
  images_.push_back(imageMemoryBarrier(image, aspect, layer, from, to, layerCount));
  src_ |= from.stage;
  dst_ |= to.stage;
}

void BarrierBatch::record(const Gpu& gpu, VkCommandBuffer cmd) {
  if (!hasMemory_ && images_.empty()) return;
  VkMemoryBarrier memory{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  memory.srcAccessMask = srcAccess_;
  memory.dstAccessMask = dstAccess_;
  gpu.cmdPipelineBarrier(cmd, src_, dst_, 0, hasMemory_ ? 1u : 0u, &memory, 0, nullptr,
                         static_cast<std::uint32_t>(images_.size()), images_.data());
  *this = BarrierBatch{};
}

void imageBarrier(const Gpu& gpu, VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  std::uint32_t layer, ImageUse from, ImageUse to) {
  const VkImageMemoryBarrier barrier = imageMemoryBarrier(image, aspect, layer, from, to);
  gpu.cmdPipelineBarrier(cmd, from.stage, to.stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

bool isDepthFormat(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return true;
    default:
      return false;
  }
}

VkImageAspectFlags barrierAspect(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
      return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      // Without separateDepthStencilLayouts a layout transition must name both aspects.
      return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
      return VK_IMAGE_ASPECT_COLOR_BIT;
  }
}

Outcome createShaderModule(const Gpu& gpu, std::span<const std::uint32_t> spirv,
                           VkShaderModule& out) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkResult result = gpu.vk.vkCreateShaderModule(gpu.device, &info, gpu.allocator, &out);
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkCreateShaderModule", result);
}

Outcome createComputePipeline(const Gpu& gpu, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                              VkPipeline& out, const VkSpecializationInfo* specialization) {
  // Kept: a technique that compiles a list of pipelines and failed part-way compiles the list
  // again, and would otherwise lose (leak) the ones it already had.
  if (out != VK_NULL_HANDLE) return {};
  VkShaderModule module = VK_NULL_HANDLE;
  if (Outcome o = createShaderModule(gpu, spirv, module); !o) return o;
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialization;
  info.layout = layout;
  VkResult result = gpu.vk.vkCreateComputePipelines(gpu.device, gpu.pipelineCache, 1, &info, gpu.allocator, &out);
  gpu.vk.vkDestroyShaderModule(gpu.device, module, gpu.allocator);
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkCreateComputePipelines", result);
}

Outcome createSpecializedPipeline(const Gpu& gpu, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                                  std::span<const std::pair<std::uint32_t, std::uint32_t>> constants,
                                  VkPipeline& out) {
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<std::uint32_t> values;
  for (const auto& [id, value] : constants) {
    entries.push_back({id, static_cast<std::uint32_t>(values.size() * sizeof(std::uint32_t)), sizeof(std::uint32_t)});
    values.push_back(value);
  }
  const VkSpecializationInfo info{static_cast<std::uint32_t>(entries.size()), entries.data(),
                                  values.size() * sizeof(std::uint32_t), values.data()};
  return createComputePipeline(gpu, layout, spirv, out, &info);
}

Outcome createLightPipelines(const Gpu& gpu, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                             LightPipelines& out) {
  for (std::uint32_t type = 0; type < out.size(); ++type) {
    const std::array<std::pair<std::uint32_t, std::uint32_t>, 1> constants{{{kLightTypeConstantId, type}}};
    if (Outcome o = createSpecializedPipeline(gpu, layout, spirv, constants, out[type]); !o) return o;
  }
  return {};
}

void destroyPipelines(const Gpu& gpu, std::span<VkPipeline> pipelines) {
  for (VkPipeline& pipeline : pipelines) {
    if (pipeline != VK_NULL_HANDLE) gpu.vk.vkDestroyPipeline(gpu.device, pipeline, gpu.allocator);
    pipeline = VK_NULL_HANDLE;
  }
}

std::array<VkDescriptorImageInfo, kMaxShadowMaps> shadowMapImageInfos(const ScatteringBindings& b) {
  std::array<VkDescriptorImageInfo, kMaxShadowMaps> infos{};
  for (std::uint32_t i = 0; i < kMaxShadowMaps; ++i) {
    const bool used = b.shadowMaps[i] != VK_NULL_HANDLE;
    infos[i] = {VK_NULL_HANDLE, used ? b.shadowMaps[i] : b.shadowMaps[0],
                used ? b.shadowLayouts[i] : b.shadowLayouts[0]};
  }
  return infos;
}

std::array<VkDescriptorImageInfo, kMaxShadowMaps> translucentLayerImageInfos(const ScatteringBindings& b) {
  std::array<VkDescriptorImageInfo, kMaxShadowMaps> infos{};
  for (std::uint32_t i = 0; i < kMaxShadowMaps; ++i) {
    const bool used = b.translucentLayers[i] != VK_NULL_HANDLE;
    infos[i] = {VK_NULL_HANDLE, used ? b.translucentLayers[i] : b.noTranslucentLayers,
                used ? b.translucentLayouts[i] : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  }
  return infos;
}

Outcome createSampler(const Gpu& gpu, VkFilter filter, VkSamplerAddressMode addressV, VkSampler& out) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = filter;
  info.minFilter = filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeV = addressV;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkResult result = gpu.vk.vkCreateSampler(gpu.device, &info, gpu.allocator, &out);
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkCreateSampler", result);
}

Outcome createLayouts(const Gpu& gpu, std::span<const VkDescriptorSetLayoutBinding> bindings,
                      const VkPushConstantRange* push, VkDescriptorSetLayout& setLayout,
                      VkPipelineLayout& pipelineLayout) {
  VkDescriptorSetLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  layoutInfo.bindingCount = static_cast<std::uint32_t>(bindings.size());
  layoutInfo.pBindings = bindings.data();
  VkResult result = gpu.vk.vkCreateDescriptorSetLayout(gpu.device, &layoutInfo, gpu.allocator, &setLayout);
  if (result != VK_SUCCESS) return vkFailed("vkCreateDescriptorSetLayout", result);

  VkPipelineLayoutCreateInfo pipelineLayoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pipelineLayoutInfo.setLayoutCount = 1;
  pipelineLayoutInfo.pSetLayouts = &setLayout;
  pipelineLayoutInfo.pushConstantRangeCount = push != nullptr ? 1 : 0;
  pipelineLayoutInfo.pPushConstantRanges = push;
  result = gpu.vk.vkCreatePipelineLayout(gpu.device, &pipelineLayoutInfo, gpu.allocator, &pipelineLayout);
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkCreatePipelineLayout", result);
}

Outcome allocateDescriptorSets(const Gpu& gpu, VkDescriptorSetLayout layout,
                               std::span<const VkDescriptorPoolSize> perSetSizes, VkDescriptorPool& pool,
                               std::vector<VkDescriptorSet>& sets) {
  const auto count = static_cast<std::uint32_t>(sets.size());
  std::vector<VkDescriptorPoolSize> sizes(perSetSizes.begin(), perSetSizes.end());
  for (VkDescriptorPoolSize& size : sizes) size.descriptorCount *= count;
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = count;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  VkResult result = gpu.vk.vkCreateDescriptorPool(gpu.device, &poolInfo, gpu.allocator, &pool);
  if (result != VK_SUCCESS) return vkFailed("vkCreateDescriptorPool", result);
  std::vector<VkDescriptorSetLayout> layouts(count, layout);
  VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocInfo.descriptorPool = pool;
  allocInfo.descriptorSetCount = count;
  allocInfo.pSetLayouts = layouts.data();
  result = gpu.vk.vkAllocateDescriptorSets(gpu.device, &allocInfo, sets.data());
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkAllocateDescriptorSets", result);
}

VkWriteDescriptorSet descriptorWrite(VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                                     std::uint32_t count) {
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = count;
  w.descriptorType = type;
  return w;
}

}  // namespace tyndall
