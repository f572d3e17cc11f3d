// Several lights per frame: each additional light's technique writes its own L_in target, which
// this pass adds to the frame's (shaders/composite/light_sum.comp); the composite then reads the
// sum once.
#pragma once

#include <vector>

#include "gpu.h"

namespace tyndall {

class LightSumPass {
 public:
  /// `sets`: descriptor sets, one per (frame slot, additional light).
  Outcome create(const Gpu& gpu, std::uint32_t sets);
  void destroy(const Gpu& gpu);
  /// `sum` += `light` over `extent`; both storage images in GENERAL, RGBA32F.
  void record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t set, VkImageView sum, VkImageView light,
              VkExtent2D extent);

 private:
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace tyndall
