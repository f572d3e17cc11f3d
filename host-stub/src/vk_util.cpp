#include "vk_util.h"

namespace tyndall::host::vk {

std::string resultName(VkResult result) {
  switch (result) {
#define TYNDALL_RESULT_CASE(name) \
  case name:                      \
    return #name;
    TYNDALL_RESULT_CASE(VK_SUCCESS)
    TYNDALL_RESULT_CASE(VK_NOT_READY)
    TYNDALL_RESULT_CASE(VK_TIMEOUT)
    TYNDALL_RESULT_CASE(VK_INCOMPLETE)
    TYNDALL_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    TYNDALL_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    TYNDALL_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    TYNDALL_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    TYNDALL_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    TYNDALL_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    TYNDALL_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    TYNDALL_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    TYNDALL_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    TYNDALL_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    TYNDALL_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    TYNDALL_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    TYNDALL_RESULT_CASE(VK_ERROR_UNKNOWN)
    TYNDALL_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef TYNDALL_RESULT_CASE
    default:
      return "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
  }
}

bool check(VkResult result, const char* what, std::string& error) {
  if (result == VK_SUCCESS) return true;
  error = std::string(what) + " failed: " + resultName(result);
  return false;
}

bool allocateMemory(const GpuContext& gpu, const VkMemoryRequirements& requirements,
                    VkMemoryPropertyFlags properties, VkDeviceMemory& memory, std::string& error) {
  for (std::uint32_t i = 0; i < gpu.memory.memoryTypeCount; ++i) {
    const bool allowed = (requirements.memoryTypeBits & (1u << i)) != 0;
    if (!allowed || (gpu.memory.memoryTypes[i].propertyFlags & properties) != properties) continue;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = i;
    return check(vkAllocateMemory(gpu.device, &info, nullptr, &memory), "vkAllocateMemory", error);
  }
  error = "no memory type with properties 0x" + std::to_string(properties) + " for type bits " +
          std::to_string(requirements.memoryTypeBits);
  return false;
}

bool isDepthFormat(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return true;
    default:
      return false;
  }
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    reset();
    device_ = other.device_;
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    layerViews_ = std::exchange(other.layerViews_, {});
    layers_ = other.layers_;
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    format_ = other.format_;
    extent_ = other.extent_;
    aspect_ = other.aspect_;
  }
  return *this;
}

bool Image::create(const GpuContext& gpu, const Desc& desc, std::string& error) {
  reset();
  device_ = gpu.device;
  format_ = desc.format;
  extent_ = desc.extent;
  // Views handed to post-processes of depth images expose the depth aspect only (ImageRef's contract).
  aspect_ = isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;

  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.extent.width, desc.extent.height, 1};
  info.mipLevels = 1;
  layers_ = std::max(desc.layers, 1u);
  info.arrayLayers = layers_;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  const std::string what = std::string("vkCreateImage (") + desc.name + ")";
  if (!check(vkCreateImage(device_, &info, nullptr, &image_), what.c_str(), error)) return false;

  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device_, image_, &requirements);
  if (!allocateMemory(gpu, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, memory_, error))
    return false;
  if (!check(vkBindImageMemory(device_, image_, memory_, 0), "vkBindImageMemory", error)) return false;

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image_;
  viewInfo.viewType = layers_ > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = desc.format;
  viewInfo.subresourceRange = {aspect_, 0, 1, 0, layers_};
  if (!check(vkCreateImageView(device_, &viewInfo, nullptr, &view_), "vkCreateImageView", error)) return false;
  if (layers_ == 1) return true;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  for (std::uint32_t layer = 0; layer < layers_; ++layer) {
    viewInfo.subresourceRange = {aspect_, 0, 1, layer, 1};
    VkImageView view = VK_NULL_HANDLE;
    if (!check(vkCreateImageView(device_, &viewInfo, nullptr, &view), "vkCreateImageView (layer)", error)) return false;
    layerViews_.push_back(view);
  }
  return true;
}

void Image::reset() {
  for (VkImageView view : layerViews_) vkDestroyImageView(device_, view, nullptr);
  layerViews_.clear();
  if (view_ != VK_NULL_HANDLE) vkDestroyImageView(device_, view_, nullptr);
  if (image_ != VK_NULL_HANDLE) vkDestroyImage(device_, image_, nullptr);
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    reset();
    device_ = other.device_;
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = other.size_;
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

bool Buffer::create(const GpuContext& gpu, VkDeviceSize size, VkBufferUsageFlags usage,
                    VkMemoryPropertyFlags properties, std::string& error) {
  reset();
  device_ = gpu.device;
  size_ = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  if (!check(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer", error)) return false;
  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device_, buffer_, &requirements);
  if (!allocateMemory(gpu, requirements, properties, memory_, error)) return false;
  if (!check(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory", error)) return false;
  if ((properties & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) != 0) {
    return check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory", error);
  }
  return true;
}

void Buffer::reset() {
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device_, buffer_, nullptr);
  // Freeing mapped memory unmaps it implicitly.
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

VkSamplerCreateInfo clampedSamplerInfo(VkFilter filter) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = filter;
  info.minFilter = filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  return info;
}

Barriers& Barriers::image(VkImage image, VkImageAspectFlags aspect, VkImageLayout oldLayout,
                          VkImageLayout newLayout, Scope src, Scope dst, std::uint32_t layer,
                          std::uint32_t layerCount) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = src.stages;
  barrier.srcAccessMask = src.access;
  barrier.dstStageMask = dst.stages;
  barrier.dstAccessMask = dst.access;
  barrier.oldLayout = oldLayout;
  barrier.newLayout = newLayout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, 0, 1, layer, layerCount};
  images_.push_back(barrier);
  return *this;
}

Barriers& Barriers::buffer(VkBuffer buffer, Scope src, Scope dst) {
  VkBufferMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
  barrier.srcStageMask = src.stages;
  barrier.srcAccessMask = src.access;
  barrier.dstStageMask = dst.stages;
  barrier.dstAccessMask = dst.access;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.buffer = buffer;
  barrier.offset = 0;
  barrier.size = VK_WHOLE_SIZE;
  buffers_.push_back(barrier);
  return *this;
}

void Barriers::record(VkCommandBuffer cmd) {
  if (images_.empty() && buffers_.empty()) return;
  VkDependencyInfo info{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  info.imageMemoryBarrierCount = static_cast<std::uint32_t>(images_.size());
  info.pImageMemoryBarriers = images_.data();
  info.bufferMemoryBarrierCount = static_cast<std::uint32_t>(buffers_.size());
  info.pBufferMemoryBarriers = buffers_.data();
  vkCmdPipelineBarrier2(cmd, &info);
  images_.clear();
  buffers_.clear();
}

bool submitAndWait(const GpuContext& gpu, VkCommandPool pool,
                   const std::function<void(VkCommandBuffer)>& body, std::string& error) {
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (!check(vkAllocateCommandBuffers(gpu.device, &allocInfo, &cmd), "vkAllocateCommandBuffers", error))
    return false;
  // Freed on every path; the fence wait below guarantees the GPU is done with it.
  struct FreeOnExit {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } freeOnExit{gpu.device, pool, cmd};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (!check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer", error)) return false;
  body(cmd);
  if (!check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer", error)) return false;

  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence rawFence = VK_NULL_HANDLE;
  if (!check(vkCreateFence(gpu.device, &fenceInfo, nullptr, &rawFence), "vkCreateFence", error))
    return false;
  UniqueFence fence(gpu.device, rawFence);

  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  {
    std::lock_guard<std::mutex> lock(*gpu.queueMutex);
    if (!check(vkQueueSubmit2(gpu.queue, 1, &submit, fence.get()), "vkQueueSubmit2", error)) return false;
  }
  return check(vkWaitForFences(gpu.device, 1, &rawFence, VK_TRUE, UINT64_MAX), "vkWaitForFences", error);
}

bool createShaderModule(VkDevice device, std::span<const std::uint32_t> words,
                        UniqueShaderModule& out, std::string& error) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = words.size_bytes();
  info.pCode = words.data();
  VkShaderModule module = VK_NULL_HANDLE;
  if (!check(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule", error))
    return false;
  out = UniqueShaderModule(device, module);
  return true;
}

bool createGraphicsPipeline(VkDevice device, const GraphicsPipelineDesc& desc, UniquePipeline& out,
                            std::string& error) {
  UniqueShaderModule vertexModule;
  UniqueShaderModule fragmentModule;
  if (!createShaderModule(device, desc.vertexShader, vertexModule, error)) return false;
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stage.stage = VK_SHADER_STAGE_VERTEX_BIT;
  stage.module = vertexModule.get();
  stage.pName = "main";
  stages.push_back(stage);
  if (!desc.fragmentShader.empty()) {
    if (!createShaderModule(device, desc.fragmentShader, fragmentModule, error)) return false;
    stage.stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stage.module = fragmentModule.get();
    stages.push_back(stage);
  }

  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = static_cast<std::uint32_t>(desc.bindings.size());
  vertexInput.pVertexBindingDescriptions = desc.bindings.data();
  vertexInput.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(desc.attributes.size());
  vertexInput.pVertexAttributeDescriptions = desc.attributes.data();

  VkPipelineInputAssemblyStateCreateInfo inputAssembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  inputAssembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;

  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;

  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.depthClampEnable = desc.depthClamp ? VK_TRUE : VK_FALSE;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  // Cull mode and front face are dynamic (core in Vulkan 1.3): set per draw.
  raster.lineWidth = 1.0f;

  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

  const bool hasDepth = desc.depthFormat != VK_FORMAT_UNDEFINED;
  VkPipelineDepthStencilStateCreateInfo depthStencil{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depthStencil.depthTestEnable = hasDepth ? VK_TRUE : VK_FALSE;
  depthStencil.depthWriteEnable = hasDepth && desc.depthWrite ? VK_TRUE : VK_FALSE;
  depthStencil.depthCompareOp = desc.depthCompare;

  std::vector<VkPipelineColorBlendAttachmentState> blendAttachments(desc.colorFormats.size());
  for (VkPipelineColorBlendAttachmentState& attachment : blendAttachments) {
    attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    if (desc.additiveBlend) {
      attachment.blendEnable = VK_TRUE;
      attachment.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
      attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
      attachment.colorBlendOp = VK_BLEND_OP_ADD;
      attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
      attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      attachment.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    if (desc.alphaBlend) {
      attachment.blendEnable = VK_TRUE;
      attachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
      attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      attachment.colorBlendOp = VK_BLEND_OP_ADD;
      attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
      attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      attachment.alphaBlendOp = VK_BLEND_OP_ADD;
    }
  }
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = static_cast<std::uint32_t>(blendAttachments.size());
  blend.pAttachments = blendAttachments.data();

  const VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                                          VK_DYNAMIC_STATE_CULL_MODE, VK_DYNAMIC_STATE_FRONT_FACE};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 4;
  dynamic.pDynamicStates = dynamicStates;

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = static_cast<std::uint32_t>(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &inputAssembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depthStencil;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = desc.layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  if (!check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
             "vkCreateGraphicsPipelines", error)) {
    return false;
  }
  out = UniquePipeline(device, pipeline);
  return true;
}

void setViewport(VkCommandBuffer cmd, VkExtent2D extent) {
  VkViewport viewport{};
  viewport.width = static_cast<float>(extent.width);
  viewport.height = static_cast<float>(extent.height);
  viewport.maxDepth = 1.0f;
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  VkRect2D scissor{{0, 0}, extent};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace tyndall::host::vk
