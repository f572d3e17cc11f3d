// The Reference technique: brute force per pixel, texel by texel through the shadow map
// (shaders/reference/). Writes L_in to Tyndall's target.
#pragma once

#include <array>
#include <vector>

#include "gpu.h"

namespace tyndall {

class ReferencePass {
 public:
  using Bindings = ScatteringBindings;

  /// `linear`: the light-colour texture's sampler (linear, clamp to edge).
  Outcome create(const Gpu& gpu, VkSampler nearest, VkSampler linear, std::uint32_t slots);
  /// Compiles the pipeline of every light type (see EpipolarTechnique::createPipelines), or one.
  Outcome createPipelines(const Gpu& gpu);
  Outcome ensurePipeline(const Gpu& gpu, LightType light, bool& compiled);
  void destroy(const Gpu& gpu);
  /// Updates the slot's descriptors and dispatches one thread per pixel.
  void record(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, const Bindings& bindings,
              VkExtent2D extent);

 private:
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  LightPipelines pipelines_{};  // per light type
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace tyndall
