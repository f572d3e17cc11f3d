#include "composite/light_sum_pass.h"

#include <array>

#include "common/shared_constants.h"
#include "technique.h"
#include "tyndall_shaders.h"

namespace tyndall {

Outcome LightSumPass::create(const Gpu& gpu, std::uint32_t sets) {
  const VkShaderStageFlags compute = VK_SHADER_STAGE_COMPUTE_BIT;
  const std::array<VkDescriptorSetLayoutBinding, gpu::TYN_LIGHT_SUM_BINDING_COUNT> bindings{{
      {gpu::TYN_LIGHT_SUM_BINDING_SUM, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr},
      {gpu::TYN_LIGHT_SUM_BINDING_LIGHT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, compute, nullptr},
  }};
  if (Outcome o = createLayouts(gpu, bindings, nullptr, setLayout_, pipelineLayout_); !o) return o;
  // One small pipeline per pair of target formats, built with the context: no frame compiles one.
  const std::array<std::array<std::span<const std::uint32_t>, 2>, 2> code{{
      {shaders::light_sum_rgba16f_rgba16f_comp(), shaders::light_sum_rgba16f_rgba32f_comp()},
      {shaders::light_sum_rgba32f_rgba16f_comp(), shaders::light_sum_rgba32f_rgba32f_comp()},
  }};
  for (std::size_t sum = 0; sum < 2; ++sum) {
    for (std::size_t light = 0; light < 2; ++light) {
      if (Outcome o = createComputePipeline(gpu, pipelineLayout_, code[sum][light], pipelines_[sum][light]); !o) {
        return o;
      }
    }
  }
  const std::array<VkDescriptorPoolSize, 1> sizes{{{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}}};
  sets_.resize(sets);
  return allocateDescriptorSets(gpu, setLayout_, sizes, pool_, sets_);
}

void LightSumPass::destroy(const Gpu& gpu) {
  if (pool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorPool(gpu.device, pool_, gpu.allocator);
  for (auto& row : pipelines_) {
    for (VkPipeline pipeline : row) {
      if (pipeline != VK_NULL_HANDLE) gpu.vk.vkDestroyPipeline(gpu.device, pipeline, gpu.allocator);
    }
  }
  if (pipelineLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyPipelineLayout(gpu.device, pipelineLayout_, gpu.allocator);
  if (setLayout_ != VK_NULL_HANDLE) gpu.vk.vkDestroyDescriptorSetLayout(gpu.device, setLayout_, gpu.allocator);
  *this = LightSumPass{};
}

void LightSumPass::record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t set, const OwnedImage& sum,
                          const OwnedImage& light) {
  const VkDescriptorSet descriptorSet = sets_[set];
  const VkDescriptorImageInfo sumInfo{VK_NULL_HANDLE, sum.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo lightInfo{VK_NULL_HANDLE, light.view, VK_IMAGE_LAYOUT_GENERAL};
  std::array<VkWriteDescriptorSet, 2> writes{
      descriptorWrite(descriptorSet, gpu::TYN_LIGHT_SUM_BINDING_SUM, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE),
      descriptorWrite(descriptorSet, gpu::TYN_LIGHT_SUM_BINDING_LIGHT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)};
  writes[0].pImageInfo = &sumInfo;
  writes[1].pImageInfo = &lightInfo;
  gpu.vk.vkUpdateDescriptorSets(gpu.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
  const VkPipeline pipeline = pipelines_[sum.format == kFullScatteringFormat][light.format == kFullScatteringFormat];
  gpu.vk.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  gpu.vk.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &descriptorSet, 0, nullptr);
  const std::uint32_t group = gpu::TYN_PIXEL_GROUP_SIZE;
  gpu.cmdDispatch(cmd, (sum.extent.width + group - 1) / group, (sum.extent.height + group - 1) / group, 1);
}

}  // namespace tyndall
