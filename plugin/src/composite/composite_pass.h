// Composite: out = in · T + L_in into the host's back buffer with one full-screen triangle and
// dual-source blending (shaders/composite/). One pipeline per back-buffer format.
#pragma once

#include <map>
#include <vector>

#include "gpu.h"

namespace tyndall {

class CompositePass {
 public:
  Outcome create(const Gpu& gpu, VkSampler nearest, std::uint32_t slots);
  void destroy(const Gpu& gpu);
  /// Builds the pipeline for a back-buffer format if it does not exist yet.
  Outcome ensurePipeline(const Gpu& gpu, VkFormat format);
  [[nodiscard]] bool hasPipeline(VkFormat format) const { return pipelines_.contains(format); }
  /// `color` must be in `attachmentLayout` (COLOR_ATTACHMENT_OPTIMAL or GENERAL); the two
  /// inputs in SHADER_READ_ONLY_OPTIMAL, readable by the fragment shader.
  void record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkImageView scattering,
              VkImageView transmittance, const ImageRef& color, VkImageLayout attachmentLayout);

 private:
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  VkShaderModule vertex_ = VK_NULL_HANDLE;
  VkShaderModule fragment_ = VK_NULL_HANDLE;
  std::map<VkFormat, VkPipeline> pipelines_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace tyndall
