#include "composite/composite_pass.h"

#include <array>
#include <span>

#include "common/shared_constants.h"
#include "tyndall_shaders.h"

namespace tyndall {

namespace {

// The frame's constants, the host's depth buffer, and L_in (composite) or T (its AOV pass).
void writeSet(const Gpu& gpu, VkDescriptorSet set, VkBuffer constants, const ImageRef& depth,
              VkImageLayout depthLayout, VkDescriptorType targetType, const VkDescriptorImageInfo& target) {
  const VkDescriptorBufferInfo frame{constants, 0, sizeof(gpu::FrameConstants)};
  const VkDescriptorImageInfo depthInfo{VK_NULL_HANDLE, depth.view, depthLayout};
  std::array<VkWriteDescriptorSet, gpu::TYN_COMPOSITE_BINDING_COUNT> writes{
      descriptorWrite(set, gpu::TYN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER),
      descriptorWrite(set, gpu::TYN_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
      descriptorWrite(set, gpu::TYN_COMPOSITE_BINDING_TARGET, targetType)};
  writes[0].pBufferInfo = &frame;
  writes[1].pImageInfo = &depthInfo;
  writes[2].pImageInfo = &target;
  gpu.vk.vkUpdateDescriptorSets(gpu.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

// The compute composite's SPIR-V per back-buffer format (its storage format qualifier), or empty.
std::span<const std::uint32_t> computeShaderFor(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R16G16B16A16_SFLOAT: return shaders::composite_rgba16f_comp();
    case VK_FORMAT_R32G32B32A32_SFLOAT: return shaders::composite_rgba32f_comp();
    case VK_FORMAT_R8G8B8A8_UNORM: return shaders::composite_rgba8_comp();
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32: return shaders::composite_rgb10_a2_comp();
    default: return {};
  }
}

}  // namespace

bool compositeFormatRunsInCompute(const Gpu& gpu, VkFormat format) {
  return !computeShaderFor(format).empty() &&
         (gpu.optimalFeatures(format) & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0;
}

bool compositeRunsInCompute(const Gpu& gpu, const ImageRef& color) {
  return (color.usage & VK_IMAGE_USAGE_STORAGE_BIT) != 0 && compositeFormatRunsInCompute(gpu, color.format);
}

Outcome CompositePass::create(const Gpu& gpu, VkSampler nearest, std::uint32_t slots) {
  const VkShaderStageFlags fragment = VK_SHADER_STAGE_FRAGMENT_BIT;
  const std::array<VkDescriptorSetLayoutBinding, gpu::TYN_COMPOSITE_BINDING_COUNT> bindings{{
      {gpu::TYN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, fragment, nullptr},
      {gpu::TYN_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragment, &nearest},
      {gpu::TYN_COMPOSITE_BINDING_TARGET, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fragment, &nearest},
  }};
  if (Outcome o = createLayouts(gpu, bindings, nullptr, setLayout_, pipelineLayout_); !o) return o;
  if (Outcome o = createShaderModule(gpu, shaders::composite_vert(), vertex_); !o) return o;
  if (Outcome o = createShaderModule(gpu, shaders::composite_frag(), fragment_); !o) return o;
  const std::array<VkDescriptorPoolSize, 2> sizes{{
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2},
  }};
  sets_.resize(slots);
  if (Outcome o = allocateDescriptorSets(gpu, setLayout_, sizes, pool_, sets_); !o) return o;

  const VkShaderStageFlags compute = VK_SHADER_STAGE_COMPUTE_BIT;
  const std::array<VkDescriptorSetLayoutBinding, gpu::TYN_COMPOSITE_BINDING_COUNT> aovBindings{{
      {gpu::TYN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, compute, nullptr},
      {gpu::TYN_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, compute, &nearest},
      {gpu::TYN_COMPOSITE_BINDING_TARGET, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr},
  }};
  if (Outcome o = createLayouts(gpu, aovBindings, nullptr, transmittanceSetLayout_, transmittanceLayout_); !o) {
    return o;
  }
  // One small pipeline, built here rather than when a frame first asks for the AOV.
  if (Outcome o = createComputePipeline(gpu, transmittanceLayout_, shaders::transmittance_aov_comp(),
                                        transmittancePipeline_);
      !o) {
    return o;
  }
  const std::array<VkDescriptorSetLayoutBinding, gpu::TYN_COMPOSITE_COMPUTE_BINDING_COUNT> computeBindings{{
      {gpu::TYN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, compute, nullptr},
      {gpu::TYN_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, compute, &nearest},
      {gpu::TYN_COMPOSITE_BINDING_TARGET, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, compute, &nearest},
      {gpu::TYN_COMPOSITE_BINDING_COLOR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr},
  }};
  if (Outcome o = createLayouts(gpu, computeBindings, nullptr, computeSetLayout_, computeLayout_); !o) return o;
  const std::array<VkDescriptorPoolSize, 3> computeSizes{{
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
  }};
  computeSets_.resize(slots);
  if (Outcome o = allocateDescriptorSets(gpu, computeSetLayout_, computeSizes, computePool_, computeSets_); !o) {
    return o;
  }
  scatteringAovSets_.resize(slots);
  if (Outcome o = allocateDescriptorSets(gpu, computeSetLayout_, computeSizes, scatteringAovPool_, scatteringAovSets_);
      !o) {
    return o;
  }
  if (Outcome o = createComputePipeline(gpu, computeLayout_, shaders::scattering_aov_comp(), scatteringAovPipeline_);
      !o) {
    return o;
  }

  const std::array<VkDescriptorPoolSize, 3> aovSizes{{
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
  }};
  transmittanceSets_.resize(slots);
  return allocateDescriptorSets(gpu, transmittanceSetLayout_, aovSizes, transmittancePool_, transmittanceSets_);
}

void CompositePass::destroy(const Gpu& gpu) {
  if (scatteringAovPool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, scatteringAovPool_, gpu.allocator);
  if (scatteringAovPipeline_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipeline(gpu.device, scatteringAovPipeline_, gpu.allocator);
  if (computePool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, computePool_, gpu.allocator);
  for (auto& [format, pipeline] : computePipelines_) gpu.vk.vkDestroyPipeline(gpu.device, pipeline, gpu.allocator);
  if (computeLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipelineLayout(gpu.device, computeLayout_, gpu.allocator);
  if (computeSetLayout_ != VK_NULL_HANDLE) {
    gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, computeSetLayout_, gpu.allocator);
  }
  if (transmittancePool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, transmittancePool_, gpu.allocator);
  if (transmittancePipeline_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipeline(gpu.device, transmittancePipeline_, gpu.allocator);
  if (transmittanceLayout_ != VK_NULL_HANDLE) {
    gpu.vk.vkDestroyPipelineLayout(gpu.device, transmittanceLayout_, gpu.allocator);
  }
  if (transmittanceSetLayout_ != VK_NULL_HANDLE) {
    gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, transmittanceSetLayout_, gpu.allocator);
  }
  if (pool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, pool_, gpu.allocator);
  for (auto& [format, pipeline] : pipelines_) gpu.vk.vkDestroyPipeline(gpu.device, pipeline, gpu.allocator);
  if (fragment_ != VK_NULL_HANDLE) gpu.vk.vkDestroyShaderModule(gpu.device, fragment_, gpu.allocator);
  if (vertex_ != VK_NULL_HANDLE) gpu.vk.vkDestroyShaderModule(gpu.device, vertex_, gpu.allocator);
  if (pipelineLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipelineLayout(gpu.device, pipelineLayout_, gpu.allocator);
  if (setLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, setLayout_, gpu.allocator);
  *this = CompositePass{};
}

Outcome CompositePass::ensurePipeline(const Gpu& gpu, VkFormat format) {
  if (pipelines_.contains(format)) return {};

  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex_;
  stages[0].pName = "main";
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment_;
  stages[1].pName = "main";

  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

  // dst.rgb = src0.rgb · 1 + dst.rgb · src1.rgb (= L_in + in · T); alpha untouched.
  VkPipelineColorBlendAttachmentState blend{};
  blend.blendEnable = VK_TRUE;
  blend.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.dstColorBlendFactor = VK_BLEND_FACTOR_SRC1_COLOR;
  blend.colorBlendOp = VK_BLEND_OP_ADD;
  blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
  blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.alphaBlendOp = VK_BLEND_OP_ADD;
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                         VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blendState{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blendState.attachmentCount = 1;
  blendState.pAttachments = &blend;

  const std::array<VkDynamicState, 2> dynamicStates{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamicStates.size());
  dynamic.pDynamicStates = dynamicStates.data();

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &format;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pColorBlendState = &blendState;
  info.pDynamicState = &dynamic;
  info.layout = pipelineLayout_;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result = gpu.vk.vkCreateGraphicsPipelines(gpu.device, gpu.pipelineCache, 1, &info, gpu.allocator, &pipeline);
  if (result != VK_SUCCESS) return vkFailed("vkCreateGraphicsPipelines", result);
  pipelines_.emplace(format, pipeline);
  return {};
}

void CompositePass::record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                           const ImageRef& depth, VkImageLayout depthLayout, VkImageView scattering,
                           const ImageRef& color, VkImageLayout attachmentLayout) {
  const VkDescriptorSet set = sets_[slot];
  writeSet(gpu, set, constants, depth, depthLayout, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
           {VK_NULL_HANDLE, scattering, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});

  VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  attachment.imageView = color.view;
  attachment.imageLayout = attachmentLayout;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, color.extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &attachment;
  gpu.vk.vkCmdBeginRendering(cmd, &rendering);
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(color.extent.width),
                            static_cast<float>(color.extent.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, color.extent};
  gpu.vk.vkCmdSetViewport(cmd, 0, 1, &viewport);
  gpu.vk.vkCmdSetScissor(cmd, 0, 1, &scissor);
  gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_.at(color.format));
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_, 0, 1, &set, 0, nullptr);
  gpu.vk.vkCmdDraw(cmd, 3, 1, 0, 0);
  gpu.vk.vkCmdEndRendering(cmd);
}

Outcome CompositePass::ensureComputePipeline(const Gpu& gpu, VkFormat format) {
  if (computePipelines_.contains(format)) return {};
  const std::span<const std::uint32_t> spirv = computeShaderFor(format);
  if (spirv.empty()) return failure(Status::UnsupportedFormat, "the compute composite has no shader for this format");
  VkPipeline pipeline = VK_NULL_HANDLE;
  if (Outcome o = createComputePipeline(gpu, computeLayout_, spirv, pipeline); !o) return o;
  computePipelines_.emplace(format, pipeline);
  return {};
}

void CompositePass::recordCompute(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                                  const ImageRef& depth, VkImageLayout depthLayout, VkImageView scattering,
                                  const ImageRef& color) {
  recordWithComputeLayout(gpu, cmd, computeSets_[slot], computePipelines_.at(color.format), constants, depth,
                          depthLayout, scattering, color.view, color.extent);
}

void CompositePass::recordScatteringAov(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                                        const ImageRef& depth, VkImageLayout depthLayout, VkImageView scattering,
                                        VkImageView output, VkExtent2D extent) {
  recordWithComputeLayout(gpu, cmd, scatteringAovSets_[slot], scatteringAovPipeline_, constants, depth, depthLayout,
                          scattering, output, extent);
}

void CompositePass::recordWithComputeLayout(const Gpu& gpu, VkCommandBuffer cmd, VkDescriptorSet set,
                                            VkPipeline pipeline, VkBuffer constants, const ImageRef& depth,
                                            VkImageLayout depthLayout, VkImageView scattering, VkImageView storage,
                                            VkExtent2D extent) {
  writeSet(gpu, set, constants, depth, depthLayout, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
           {VK_NULL_HANDLE, scattering, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  const VkDescriptorImageInfo storageInfo{VK_NULL_HANDLE, storage, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet storageWrite = descriptorWrite(set, gpu::TYN_COMPOSITE_BINDING_COLOR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  storageWrite.pImageInfo = &storageInfo;
  gpu.vk.vkUpdateDescriptorSets(gpu.device, 1, &storageWrite, 0, nullptr);
  gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computeLayout_, 0, 1, &set, 0, nullptr);
  const std::uint32_t group = gpu::TYN_PIXEL_GROUP_SIZE;
  gpu.cmdDispatch(cmd, (extent.width + group - 1) / group, (extent.height + group - 1) / group, 1);
}

void CompositePass::recordTransmittance(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                                        const ImageRef& depth, VkImageLayout depthLayout, VkImageView target,
                                        VkExtent2D extent) {
  const VkDescriptorSet set = transmittanceSets_[slot];
  writeSet(gpu, set, constants, depth, depthLayout, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
           {VK_NULL_HANDLE, target, VK_IMAGE_LAYOUT_GENERAL});
  gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, transmittancePipeline_);
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, transmittanceLayout_, 0, 1, &set, 0, nullptr);
  const std::uint32_t group = gpu::TYN_PIXEL_GROUP_SIZE;
  gpu.cmdDispatch(cmd, (extent.width + group - 1) / group, (extent.height + group - 1) / group, 1);
}

}  // namespace tyndall
