// Composite: out = in · T + L_in into the host's back buffer with one full-screen triangle and
// dual-source blending (shaders/composite/). One pipeline per back-buffer format. T = exp(−σ_t s)
// is computed from the depth buffer where it is used, here and in the T AOV's compute pass, so
// that no technique stores it.
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
  /// `color` must be in `attachmentLayout` (COLOR_ATTACHMENT_OPTIMAL or GENERAL); `scattering` in
  /// SHADER_READ_ONLY_OPTIMAL and the host's depth (`depth.view` in `depthLayout`) readable by the
  /// fragment shader; `constants` the slot's FrameConstants.
  void record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants, const ImageRef& depth,
              VkImageLayout depthLayout, VkImageView scattering, const ImageRef& color, VkImageLayout attachmentLayout);
  /// The T AOV: T of every pixel of `extent` into `target` (storage, GENERAL, RGBA32F), the depth
  /// readable by compute shaders.
  void recordTransmittance(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                           const ImageRef& depth, VkImageLayout depthLayout, VkImageView target, VkExtent2D extent);

 private:
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  // The T AOV's compute pass: its own set (the depth, T as a storage image).
  VkDescriptorSetLayout transmittanceSetLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout transmittanceLayout_ = VK_NULL_HANDLE;
  VkPipeline transmittancePipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool transmittancePool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> transmittanceSets_;
  VkShaderModule vertex_ = VK_NULL_HANDLE;
  VkShaderModule fragment_ = VK_NULL_HANDLE;
  std::map<VkFormat, VkPipeline> pipelines_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace tyndall
