#include "composite/light_sum_pass.h"

#include <array>

#include "common/shared_constants.h"
#include "tyndall_shaders.h"

namespace tyndall {

Outcome LightSumPass::create(const Gpu& gpu, std::uint32_t sets) {
  const VkShaderStageFlags compute = VK_SHADER_STAGE_COMPUTE_BIT;
  const std::array<VkDescriptorSetLayoutBinding, gpu::TYN_LIGHT_SUM_BINDING_COUNT> bindings{{
      {gpu::TYN_LIGHT_SUM_BINDING_SUM, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr},
      {gpu::TYN_LIGHT_SUM_BINDING_LIGHT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr},
  }};
  if (Outcome o = createLayouts(gpu, bindings, nullptr, setLayout_, pipelineLayout_); !o) return o;
  // One small pipeline, built with the context: no frame compiles it.
  if (Outcome o = createComputePipeline(gpu, pipelineLayout_, shaders::light_sum_comp(), pipeline_); !o) return o;
  const std::array<VkDescriptorPoolSize, 1> sizes{{{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}}};
  sets_.resize(sets);
  return allocateDescriptorSets(gpu, setLayout_, sizes, pool_, sets_);
}

void LightSumPass::destroy(const Gpu& gpu) {
  if (pool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, pool_, gpu.allocator);
  if (pipeline_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipeline(gpu.device, pipeline_, gpu.allocator);
  if (pipelineLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipelineLayout(gpu.device, pipelineLayout_, gpu.allocator);
  if (setLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, setLayout_, gpu.allocator);
  *this = LightSumPass{};
}

void LightSumPass::record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t set, VkImageView sum, VkImageView light,
                          VkExtent2D extent) {
  const VkDescriptorSet descriptorSet = sets_[set];
  const VkDescriptorImageInfo sumInfo{VK_NULL_HANDLE, sum, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo lightInfo{VK_NULL_HANDLE, light, VK_IMAGE_LAYOUT_GENERAL};
  std::array<VkWriteDescriptorSet, 2> writes{
      descriptorWrite(descriptorSet, gpu::TYN_LIGHT_SUM_BINDING_SUM, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
      descriptorWrite(descriptorSet, gpu::TYN_LIGHT_SUM_BINDING_LIGHT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)};
  writes[0].pImageInfo = &sumInfo;
  writes[1].pImageInfo = &lightInfo;
  gpu.vk.vkUpdateDescriptorSets(gpu.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
  gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &descriptorSet, 0, nullptr);
  const std::uint32_t group = gpu::TYN_PIXEL_GROUP_SIZE;
  gpu.cmdDispatch(cmd, (extent.width + group - 1) / group, (extent.height + group - 1) / group, 1);
}

}  // namespace tyndall
