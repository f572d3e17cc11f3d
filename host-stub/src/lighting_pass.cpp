// The full-screen deferred lighting pass.
#include "host_shaders.h"
#include "passes.h"

namespace tyndall::host::detail {

namespace {

constexpr std::uint32_t kParamsBinding = 0;
constexpr std::uint32_t kDepthBinding = 1;
constexpr std::uint32_t kAlbedoBinding = 2;
constexpr std::uint32_t kNormalBinding = 3;
constexpr std::uint32_t kShadowBinding = 4;
constexpr std::uint32_t kLightColorBinding = 5;
constexpr auto kShadowCount = static_cast<std::uint32_t>(gpu::kHostMaxShadowMaps);

}  // namespace

bool LightingPass::create(const vk::GpuContext& gpu, VkFormat colorFormat, std::uint32_t slotCount,
                          std::uint32_t lightCount, std::string& error) {
  device_ = gpu.device;
  lightCount_ = lightCount;
  const std::uint32_t setCount = slotCount * lightCount;

  // The G-buffer is read with texelFetch; the sampler only has to exist.
  const VkSamplerCreateInfo pointInfo = vk::clampedSamplerInfo(VK_FILTER_NEAREST);
  VkSampler sampler = VK_NULL_HANDLE;
  if (!vk::check(vkCreateSampler(device_, &pointInfo, nullptr, &sampler), "vkCreateSampler", error))
    return false;
  pointSampler_ = vk::UniqueSampler(device_, sampler);

  // Hardware comparison (ref ≤ stored → lit), bilinearly filtered where the format allows: a
  // 2×2 PCF that softens the stair-steps of the hard test at no cost.
  VkFormatProperties shadowFormat{};
  vkGetPhysicalDeviceFormatProperties(gpu.physicalDevice, kShadowFormat, &shadowFormat);
  const bool linear =
      (shadowFormat.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
  VkSamplerCreateInfo shadowInfo = pointInfo;
  shadowInfo.magFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  shadowInfo.minFilter = shadowInfo.magFilter;
  shadowInfo.compareEnable = VK_TRUE;
  shadowInfo.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  if (!vk::check(vkCreateSampler(device_, &shadowInfo, nullptr, &sampler), "vkCreateSampler", error))
    return false;
  shadowSampler_ = vk::UniqueSampler(device_, sampler);

  // The light's colour texture: bilinear, clamped to its edge (as Tyndall samples it).
  VkSamplerCreateInfo linearInfo = pointInfo;
  linearInfo.magFilter = VK_FILTER_LINEAR;
  linearInfo.minFilter = VK_FILTER_LINEAR;
  if (!vk::check(vkCreateSampler(device_, &linearInfo, nullptr, &sampler), "vkCreateSampler", error))
    return false;
  linearSampler_ = vk::UniqueSampler(device_, sampler);

  const VkShaderStageFlags fragment = VK_SHADER_STAGE_FRAGMENT_BIT;
  const VkDescriptorSetLayoutBinding bindings[] = {
      {kParamsBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, fragment, nullptr},
      {kDepthBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragment, nullptr},
      {kAlbedoBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragment, nullptr},
      {kNormalBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragment, nullptr},
      {kShadowBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kShadowCount, fragment, nullptr},
      {kLightColorBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragment, nullptr},
  };
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 6;
  setInfo.pBindings = bindings;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  if (!vk::check(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout),
                 "vkCreateDescriptorSetLayout", error)) {
    return false;
  }
  setLayout_ = vk::UniqueDescriptorSetLayout(device_, setLayout);

  const VkDescriptorPoolSize sizes[] = {
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, setCount},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, setCount * (4 + kShadowCount)},
  };
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = setCount;
  poolInfo.poolSizeCount = 2;
  poolInfo.pPoolSizes = sizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  if (!vk::check(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool", error))
    return false;
  pool_ = vk::UniqueDescriptorPool(device_, pool);

  const std::vector<VkDescriptorSetLayout> layouts(setCount, setLayout);
  VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocInfo.descriptorPool = pool;
  allocInfo.descriptorSetCount = setCount;
  allocInfo.pSetLayouts = layouts.data();
  sets_.resize(setCount);
  if (!vk::check(vkAllocateDescriptorSets(device_, &allocInfo, sets_.data()), "vkAllocateDescriptorSets", error))
    return false;

  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  if (!vk::check(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout", error))
    return false;
  layout_ = vk::UniquePipelineLayout(device_, layout);

  vk::GraphicsPipelineDesc desc;
  desc.layout = layout;
  desc.vertexShader = shaders::fullscreen_vert();
  desc.fragmentShader = shaders::lighting_frag();
  desc.colorFormats = {colorFormat};
  if (!vk::createGraphicsPipeline(device_, desc, pipeline_, error)) return false;
  if (lightCount < 2) return true;
  desc.additiveBlend = true;
  return vk::createGraphicsPipeline(device_, desc, additivePipeline_, error);
}

void LightingPass::bindSlot(std::uint32_t slot, std::uint32_t light, const SlotInputs& inputs) {
  const VkDescriptorSet set = sets_[slot * lightCount_ + light];
  const VkDescriptorBufferInfo params{inputs.params, 0, sizeof(gpu::LightingParams)};
  auto gbuffer = [this](VkImageView view) {
    return VkDescriptorImageInfo{pointSampler_.get(), view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  };
  const VkDescriptorImageInfo depth = gbuffer(inputs.depth);
  const VkDescriptorImageInfo albedo = gbuffer(inputs.albedo);
  const VkDescriptorImageInfo normal = gbuffer(inputs.normal);
  // Every element of the array is statically used by the shader, so the ones a directional or
  // spot light does not have repeat its single map.
  VkDescriptorImageInfo shadows[kShadowCount];
  for (std::uint32_t i = 0; i < kShadowCount; ++i) {
    const VkImageView view = i < inputs.shadowMaps.size() ? inputs.shadowMaps[i] : inputs.shadowMaps.front();
    shadows[i] = {shadowSampler_.get(), view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  }

  const VkDescriptorImageInfo lightColor{linearSampler_.get(), inputs.lightColor,
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet writes[6]{};
  for (VkWriteDescriptorSet& write : writes) {
    write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    write.dstSet = set;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  writes[0].dstBinding = kParamsBinding;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  writes[0].pBufferInfo = &params;
  writes[1].dstBinding = kDepthBinding;
  writes[1].pImageInfo = &depth;
  writes[2].dstBinding = kAlbedoBinding;
  writes[2].pImageInfo = &albedo;
  writes[3].dstBinding = kNormalBinding;
  writes[3].pImageInfo = &normal;
  writes[4].dstBinding = kShadowBinding;
  writes[4].descriptorCount = kShadowCount;
  writes[4].pImageInfo = shadows;
  writes[5].dstBinding = kLightColorBinding;
  writes[5].pImageInfo = &lightColor;
  vkUpdateDescriptorSets(device_, 6, writes, 0, nullptr);
}

void LightingPass::record(VkCommandBuffer cmd, std::uint32_t slot, const vk::Image& target) const {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = target.view();
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // the full-screen triangle writes every pixel
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;

  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, target.extent()};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &rendering);
  vk::setViewport(cmd, target.extent());
  // All lights in one rendering: blending follows primitive order within it, so the lights need
  // no barrier between them.
  for (std::uint32_t light = 0; light < lightCount_; ++light) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, light == 0 ? pipeline_.get() : additivePipeline_.get());
    const VkDescriptorSet set = sets_[slot * lightCount_ + light];
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &set, 0, nullptr);
    vkCmdDraw(cmd, 3, 1, 0, 0);
  }
  vkCmdEndRendering(cmd);
}

}  // namespace tyndall::host::detail
