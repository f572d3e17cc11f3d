// The translucent peel pass (passes.h, TranslucentPass).
#include "host_shaders.h"
#include "passes.h"

namespace tyndall::host::detail {

bool TranslucentPass::create(const vk::GpuContext& gpu, std::uint32_t setCount, std::string& error) {
  device_ = gpu.device;
  // Both inputs are read with texelFetch; the sampler only has to exist.
  const VkSamplerCreateInfo samplerInfo = vk::clampedSamplerInfo(VK_FILTER_NEAREST);
  VkSampler sampler = VK_NULL_HANDLE;
  if (!vk::check(vkCreateSampler(device_, &samplerInfo, nullptr, &sampler), "vkCreateSampler", error)) return false;
  sampler_ = vk::UniqueSampler(device_, sampler);

  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
  };
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 2;
  setInfo.pBindings = bindings;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  if (!vk::check(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout), "vkCreateDescriptorSetLayout",
                 error)) {
    return false;
  }
  setLayout_ = vk::UniqueDescriptorSetLayout(device_, setLayout);

  if (setCount > 0) {
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * setCount};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = setCount;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
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
  }

  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(gpu::PeelPush)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  if (!vk::check(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout", error))
    return false;
  layout_ = vk::UniquePipelineLayout(device_, layout);

  vk::GraphicsPipelineDesc desc;
  desc.layout = layout;
  desc.vertexShader = shaders::peel_vert();
  desc.fragmentShader = shaders::peel_frag();
  desc.bindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                     {1, 0, VK_FORMAT_R32_SFLOAT, offsetof(Vertex, opacity)}};
  desc.colorFormats = {kLayerFormat};
  desc.depthFormat = kShadowFormat;
  desc.depthCompare = VK_COMPARE_OP_LESS;
  desc.depthClamp = true;
  return vk::createGraphicsPipeline(device_, desc, pipeline_, error);
}

void TranslucentPass::bind(std::uint32_t set, VkImageView opaqueDepth, VkImageView previousLayer) {
  const VkDescriptorImageInfo images[] = {
      {sampler_.get(), opaqueDepth, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {sampler_.get(), previousLayer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
  };
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = sets_[set];
  write.dstBinding = 0;
  write.descriptorCount = 2;
  write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  write.pImageInfo = images;
  vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
}

void TranslucentPass::record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& layers,
                             std::uint32_t layer, std::uint32_t set, const vk::Image& depth,
                             const glm::mat4& worldToClip) const {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = layers.layerView(layer);
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color = {{1.0f, 0.0f, 0.0f, 0.0f}};  // no surface
  VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthAttachment.imageView = depth.view();
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depthAttachment.clearValue.depthStencil = {1.0f, 0};

  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, layers.extent()};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  rendering.pDepthAttachment = &depthAttachment;
  vkCmdBeginRendering(cmd, &rendering);
  vk::setViewport(cmd, layers.extent());
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &sets_[set], 0, nullptr);
  const gpu::PeelPush push{worldToClip, glm::ivec4(static_cast<int>(layer), 0, 0, 0)};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                     &push);
  drawTranslucentGeometry(cmd, geometry);
  vkCmdEndRendering(cmd);
}

}  // namespace tyndall::host::detail
