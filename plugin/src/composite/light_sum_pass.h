// Several lights per frame: each additional light's technique writes its own L_in target, which
// this pass adds to the frame's (shaders/composite/light_sum.comp); the composite then reads the
// sum once.
#pragma once

#include <array>
#include <vector>

#include "gpu.h"

namespace tyndall {

class LightSumPass {
 public:
  /// `sets`: descriptor sets, one per (frame slot, additional light).
  Outcome create(const Gpu& gpu, std::uint32_t sets);
  void destroy(const Gpu& gpu);
  /// `sum` += `light` over `sum`'s extent (the same as `light`'s); both storage images in GENERAL,
  /// each RGBA16F or RGBA32F (kHalfScatteringFormat, kFullScatteringFormat).
  void record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t set, const OwnedImage& sum, const OwnedImage& light);

 private:
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  std::array<std::array<VkPipeline, 2>, 2> pipelines_{};  // [sum is RGBA32F][light is RGBA32F]
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace tyndall
