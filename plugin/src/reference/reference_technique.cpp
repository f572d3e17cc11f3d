#include "reference/reference_technique.h"

#include "common/shared_constants.h"
#include "tyndall_shaders.h"

namespace tyndall {

Outcome ReferenceTechnique::create(const Gpu& gpu, const TechniqueResources& resources) {
  const VkSampler nearest = resources.nearest;
  const VkSampler linear = resources.linear;
  const std::array<VkSampler, kMaxShadowMaps> samplers{nearest, nearest, nearest, nearest, nearest, nearest};
  static_assert(kMaxTranslucentLayers == gpu::TYN_MAX_TRANSLUCENT_LAYERS);
  const VkShaderStageFlags stage = VK_SHADER_STAGE_COMPUTE_BIT;
  const std::array<VkDescriptorSetLayoutBinding, gpu::TYN_REFERENCE_BINDING_COUNT> bindings{{
      {gpu::TYN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stage, nullptr},
      {gpu::TYN_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stage, samplers.data()},
      {gpu::TYN_BINDING_SHADOW_MAPS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaxShadowMaps, stage, samplers.data()},
      {gpu::TYN_REFERENCE_BINDING_OUT_SCATTERING, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, stage, nullptr},
      {gpu::TYN_REFERENCE_BINDING_LIGHT_COLOR, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stage, &linear},
      {gpu::TYN_REFERENCE_BINDING_TRANSLUCENT_LAYERS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaxShadowMaps, stage,
       samplers.data()},
      {gpu::TYN_REFERENCE_BINDING_TRANSLUCENT_OVERFLOW, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stage, nullptr},
  }};
  if (Outcome o = createLayouts(gpu, bindings, nullptr, setLayout_, pipelineLayout_); !o) return o;

  const std::array<VkDescriptorPoolSize, 4> sizes{{
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 + 2 * kMaxShadowMaps},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
  }};
  sets_.resize(resources.slots);
  overflow_.resize(resources.slots);
  overflowRecorded_.assign(resources.slots, false);
  for (MappedBuffer& buffer : overflow_) {
    if (Outcome o = createMappedBuffer(gpu, sizeof(std::uint32_t),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, buffer);
        !o) {
      return o;
    }
  }
  return allocateDescriptorSets(gpu, setLayout_, sizes, pool_, sets_);
}

Outcome ReferenceTechnique::ensurePipelines(const Gpu& gpu, const FrameDesc& frame, bool& compiled) {
  if (pipelineOwner_ != nullptr) return pipelineOwner_->ensurePipelines(gpu, frame, compiled);
  return ensurePipeline(gpu, frame.light.type, compiled);
}

Outcome ReferenceTechnique::ensurePipeline(const Gpu& gpu, LightType light, bool& compiled) {
  VkPipeline& pipeline = pipelines_[static_cast<std::size_t>(light)];
  compiled = pipeline == VK_NULL_HANDLE;
  if (!compiled) return {};
  const std::array<std::pair<std::uint32_t, std::uint32_t>, 1> constants{
      {{kLightTypeConstantId, static_cast<std::uint32_t>(light)}}};
  return createSpecializedPipeline(gpu, pipelineLayout_, shaders::reference_scattering_comp(), constants, pipeline);
}

Outcome ReferenceTechnique::createPipelines(const Gpu& gpu) {
  if (pipelineOwner_ != nullptr) return pipelineOwner_->createPipelines(gpu);
  bool compiled = false;
  for (LightType light : {LightType::Directional, LightType::Spot, LightType::Point}) {
    if (Outcome o = ensurePipeline(gpu, light, compiled); !o) return o;
  }
  return {};
}

void ReferenceTechnique::readBackFlags(std::uint32_t slot, Stats& stats) {
  if (slot >= overflow_.size() || !overflowRecorded_[slot]) return;
  overflowRecorded_[slot] = false;
  stats.translucentLayersOverflowed =
      stats.translucentLayersOverflowed || *static_cast<const std::uint32_t*>(overflow_[slot].mapped) != 0;
}

void ReferenceTechnique::destroy(const Gpu& gpu) {
  for (MappedBuffer& buffer : overflow_) destroyBuffer(gpu, buffer);
  if (pool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, pool_, gpu.allocator);
  destroyPipelines(gpu, pipelines_);
  if (pipelineLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipelineLayout(gpu.device, pipelineLayout_, gpu.allocator);
  if (setLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, setLayout_, gpu.allocator);
  *this = ReferenceTechnique{};
}

void ReferenceTechnique::record(const Gpu& gpu, VkCommandBuffer cmd, const RecordTarget& target) {
  const ScatteringBindings& b = target.bindings;
  const VkExtent2D extent = target.extent;
  const VkDescriptorSet set = sets_[target.slot];
  const VkDescriptorBufferInfo constants{b.constants, 0, sizeof(gpu::FrameConstants)};
  const VkDescriptorImageInfo depth{VK_NULL_HANDLE, b.depth, b.depthLayout};
  const std::array<VkDescriptorImageInfo, kMaxShadowMaps> shadow = shadowMapImageInfos(b);
  const VkDescriptorImageInfo scattering{VK_NULL_HANDLE, b.scattering, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo lightColor{VK_NULL_HANDLE, b.lightColor, b.lightColorLayout};
  const std::array<VkDescriptorImageInfo, kMaxShadowMaps> layers = translucentLayerImageInfos(b);
  const VkDescriptorBufferInfo overflow{overflow_[target.slot].buffer, 0, sizeof(std::uint32_t)};

  std::array<VkWriteDescriptorSet, gpu::TYN_REFERENCE_BINDING_COUNT> writes{
      descriptorWrite(set, gpu::TYN_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER),
      descriptorWrite(set, gpu::TYN_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
      descriptorWrite(set, gpu::TYN_BINDING_SHADOW_MAPS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaxShadowMaps),
      descriptorWrite(set, gpu::TYN_REFERENCE_BINDING_OUT_SCATTERING, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
      descriptorWrite(set, gpu::TYN_REFERENCE_BINDING_LIGHT_COLOR, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
      descriptorWrite(set, gpu::TYN_REFERENCE_BINDING_TRANSLUCENT_LAYERS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                      kMaxShadowMaps),
      descriptorWrite(set, gpu::TYN_REFERENCE_BINDING_TRANSLUCENT_OVERFLOW, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)};
  writes[0].pBufferInfo = &constants;
  writes[1].pImageInfo = &depth;
  writes[2].pImageInfo = shadow.data();
  writes[3].pImageInfo = &scattering;
  writes[4].pImageInfo = &lightColor;
  writes[5].pImageInfo = layers.data();
  writes[6].pBufferInfo = &overflow;
  gpu.vk.vkUpdateDescriptorSets(gpu.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

  const ReferenceTechnique& owner = pipelineOwner_ != nullptr ? *pipelineOwner_ : *this;
  gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, owner.pipelines_[static_cast<std::size_t>(b.light)]);
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set, 0, nullptr);
  // With translucent layers the flag starts at 0, is set by rays that meet an overflow layer, and
  // is read by the host when the slot comes round again.
  const bool translucent = b.translucentLayers[0] != VK_NULL_HANDLE;
  if (translucent) {
    gpu.vk.vkCmdFillBuffer(cmd, overflow.buffer, 0, sizeof(std::uint32_t), 0);
    memoryBarrier(gpu, cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  }
  const std::uint32_t group = gpu::TYN_PIXEL_GROUP_SIZE;
  gpu.cmdDispatch(cmd, (extent.width + group - 1) / group, (extent.height + group - 1) / group, 1);
  if (translucent) {
    memoryBarrier(gpu, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  }
  overflowRecorded_[target.slot] = translucent;
}

}  // namespace tyndall
