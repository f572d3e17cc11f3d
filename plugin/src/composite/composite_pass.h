// Composite: out = in · T + L_in into the host's back buffer (shaders/composite/). A compute pass
// writes it in place when the host made it a storage image of a format compute can read and write
// (compositeRunsInCompute); otherwise one full-screen triangle blends it with dual-source blending.
// One pipeline per back-buffer format and path. T = exp(−σ_t s) is computed from the depth buffer
// where it is used, here and in the T AOV's compute pass, so that no technique stores it.
#pragma once

#include <map>
#include <vector>

#include "gpu.h"

namespace tyndall {

/// Whether the composite of a back buffer like `color` runs in compute: STORAGE in its usage, and
/// a format the compute composite has a SPIR-V for that the device can store to.
bool compositeRunsInCompute(const Gpu& gpu, const ImageRef& color);
/// The format half of it: a back buffer of `format` with STORAGE usage would composite in compute.
bool compositeFormatRunsInCompute(const Gpu& gpu, VkFormat format);

class CompositePass {
 public:
  Outcome create(const Gpu& gpu, VkSampler nearest, std::uint32_t slots);
  void destroy(const Gpu& gpu);
  /// Builds the fragment pipeline for a back-buffer format if it does not exist yet.
  Outcome ensurePipeline(const Gpu& gpu, VkFormat format);
  [[nodiscard]] bool hasPipeline(VkFormat format) const { return pipelines_.contains(format); }
  /// Builds the compute pipeline for a storage back-buffer format (compositeRunsInCompute).
  Outcome ensureComputePipeline(const Gpu& gpu, VkFormat format);
  [[nodiscard]] bool hasComputePipeline(VkFormat format) const { return computePipelines_.contains(format); }
  /// `color` must be in `attachmentLayout` (COLOR_ATTACHMENT_OPTIMAL or GENERAL); `scattering` in
  /// SHADER_READ_ONLY_OPTIMAL and the host's depth (`depth.view` in `depthLayout`) readable by the
  /// fragment shader; `constants` the slot's FrameConstants.
  void record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants, const ImageRef& depth,
              VkImageLayout depthLayout, VkImageView scattering, const ImageRef& color, VkImageLayout attachmentLayout);
  /// The compute path: `color` in GENERAL, readable and writable by compute shaders; `scattering`
  /// in SHADER_READ_ONLY_OPTIMAL and the depth readable by compute shaders.
  void recordCompute(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                     const ImageRef& depth, VkImageLayout depthLayout, VkImageView scattering, const ImageRef& color);
  /// The L_in AOV of a reduced-resolution target: the upsampled L_in of every pixel of `extent`
  /// into `output` (storage, GENERAL, RGBA32F); `scattering` and the depth as for recordCompute.
  void recordScatteringAov(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                           const ImageRef& depth, VkImageLayout depthLayout, VkImageView scattering,
                           VkImageView output, VkExtent2D extent);
  /// The T AOV: T of every pixel of `extent` into `target` (storage, GENERAL, RGBA32F), the depth
  /// readable by compute shaders.
  void recordTransmittance(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, VkBuffer constants,
                           const ImageRef& depth, VkImageLayout depthLayout, VkImageView target, VkExtent2D extent);

 private:
  // A pass of the compute composite's layout: the frame, the depth, L_in sampled, and `storage`
  // (the back buffer, or the L_in AOV's output) written over `extent`.
  void recordWithComputeLayout(const Gpu& gpu, VkCommandBuffer cmd, VkDescriptorSet set, VkPipeline pipeline,
                               VkBuffer constants, const ImageRef& depth, VkImageLayout depthLayout,
                               VkImageView scattering, VkImageView storage, VkExtent2D extent);

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
  // The compute composite: its own set (the back buffer as a storage image), a pipeline per format.
  VkDescriptorSetLayout computeSetLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout computeLayout_ = VK_NULL_HANDLE;
  VkDescriptorPool computePool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> computeSets_;
  std::map<VkFormat, VkPipeline> computePipelines_;
  // The L_in AOV's upsample: the compute composite's layout, sets of its own (the composite's set
  // of the slot is bound earlier in the same command buffer and must not change).
  VkPipeline scatteringAovPipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool scatteringAovPool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> scatteringAovSets_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace tyndall
