// The Reference technique: brute force per pixel, texel by texel through the shadow map
// (shaders/reference/). Writes L_in to Tyndall's target in one timed pass.
#pragma once

#include <vector>

#include "gpu.h"
#include "technique.h"

namespace tyndall {

class ReferenceTechnique final : public ScatteringTechnique {
 public:
  Outcome create(const Gpu& gpu, const TechniqueResources& resources) override;
  /// The pipeline of every light type.
  void sharePipelinesOf(ScatteringTechnique& owner) override {
    pipelineOwner_ = &static_cast<ReferenceTechnique&>(owner);
  }
  Outcome createPipelines(const Gpu& gpu) override;
  Outcome ensurePipelines(const Gpu& gpu, const FrameDesc& frame, bool& compiled) override;
  /// Nothing to set up: the frame's constants are the context's.
  Outcome prepare(const Gpu& /*gpu*/, const FrameInputs& /*in*/, TechniqueReport& /*report*/) override { return {}; }
  /// Updates the slot's descriptors and dispatches one thread per pixel.
  void record(const Gpu& gpu, VkCommandBuffer cmd, const RecordTarget& target) override;
  [[nodiscard]] const char* singlePassName() const override { return "reference_scattering"; }
  [[nodiscard]] VkFormat scatteringFormat() const override { return kFullScatteringFormat; }
  /// Stats::translucentLayersOverflowed from the slot's previous frame with translucent layers.
  void readBackFlags(std::uint32_t slot, Stats& stats) override;
  void destroy(const Gpu& gpu) override;

 private:
  Outcome ensurePipeline(const Gpu& gpu, LightType light, bool& compiled);

  ReferenceTechnique* pipelineOwner_ = nullptr;  // sharePipelinesOf: whose pipelines record() binds
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  LightPipelines pipelines_{};  // per light type
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
  std::vector<MappedBuffer> overflow_;   // per slot: one uint the shader sets, read a lap later
  std::vector<bool> overflowRecorded_;   // per slot: its last frame had translucent layers
};

}  // namespace tyndall
