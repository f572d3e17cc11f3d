#include "floor_pass.h"

#include <array>
#include <cmath>
#include <map>
#include <span>
#include <vector>

#include "bench_shaders.h"

namespace tyndall::samples::bench {

namespace {

// The stub host's limit on frames in flight (RenderSettings::framesInFlight): one descriptor set
// and one pair of timestamps per slot, so a slot is rewritten only after its frame completed.
constexpr std::uint32_t kMaxSlots = 16;

struct PushConstants {
  float fog[4];
  float projection[4];
};

bool check(VkResult result, const char* what, std::string& error) {
  if (result == VK_SUCCESS) return true;
  error = std::string(what) + " failed (VkResult " + std::to_string(static_cast<int>(result)) + ")";
  return false;
}

}  // namespace

std::string computeFloorUnavailable(const host::Device& device, const host::RenderSettings& settings) {
  if (!settings.storageBackBuffer) return "the back buffer has no STORAGE usage (storageBackBuffer off)";
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(device.physicalDevice(), settings.backBufferFormat, &properties);
  if ((properties.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) == 0) {
    return "the back buffer's format has no storage-image support";
  }
  // The host enables this feature wherever the device has it (host::Device).
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(device.physicalDevice(), &features);
  if (!features.shaderStorageImageWriteWithoutFormat) return "the device lacks shaderStorageImageWriteWithoutFormat";
  return {};
}

struct FloorPass::Impl {
  FloorKind kind = FloorKind::Fragment;
  VkDevice device = VK_NULL_HANDLE;
  double timestampPeriodNs = 1.0;
  std::uint64_t timestampMask = ~0ull;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::array<VkDescriptorSet, kMaxSlots> sets{};
  VkShaderModule vertex = VK_NULL_HANDLE;
  VkShaderModule fragment = VK_NULL_HANDLE;
  VkShaderModule compute = VK_NULL_HANDLE;
  std::map<VkFormat, VkPipeline> pipelines;  // fragment: one per back-buffer format
  VkPipeline computePipeline = VK_NULL_HANDLE;  // compute: one for every format (written without a format)
  VkQueryPool queries = VK_NULL_HANDLE;
  std::optional<std::uint32_t> lastSlot;

  ~Impl() {
    if (device == VK_NULL_HANDLE) return;
    for (auto& [format, pipeline] : pipelines) vkDestroyPipeline(device, pipeline, nullptr);
    vkDestroyPipeline(device, computePipeline, nullptr);
    vkDestroyShaderModule(device, vertex, nullptr);
    vkDestroyShaderModule(device, fragment, nullptr);
    vkDestroyShaderModule(device, compute, nullptr);
    vkDestroyQueryPool(device, queries, nullptr);
    vkDestroyDescriptorPool(device, pool, nullptr);
    vkDestroyPipelineLayout(device, pipelineLayout, nullptr);
    vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
    vkDestroySampler(device, sampler, nullptr);
  }

  bool shaderModule(std::span<const std::uint32_t> code, VkShaderModule& out, std::string& error) const {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = code.size_bytes();
    info.pCode = code.data();
    return check(vkCreateShaderModule(device, &info, nullptr, &out), "vkCreateShaderModule", error);
  }

  VkPipeline pipelineFor(VkFormat format, std::string& error) {
    if (auto it = pipelines.find(format); it != pipelines.end()) return it->second;
    const std::array<VkPipelineShaderStageCreateInfo, 2> stages{{
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vertex, "main", nullptr},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fragment, "main",
         nullptr},
    }};
    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    // out = src0 + dst · src1 (colour); the back buffer's alpha is kept.
    VkPipelineColorBlendAttachmentState blend{};
    blend.blendEnable = VK_TRUE;
    blend.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.dstColorBlendFactor = VK_BLEND_FACTOR_SRC1_COLOR;
    blend.colorBlendOp = VK_BLEND_OP_ADD;
    blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.alphaBlendOp = VK_BLEND_OP_ADD;
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo blendState{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blendState.attachmentCount = 1;
    blendState.pAttachments = &blend;
    const std::array<VkDynamicState, 2> dynamic{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamicState{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamicState.dynamicStateCount = static_cast<std::uint32_t>(dynamic.size());
    dynamicState.pDynamicStates = dynamic.data();
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &format;
    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = static_cast<std::uint32_t>(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pColorBlendState = &blendState;
    info.pDynamicState = &dynamicState;
    info.layout = pipelineLayout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    if (!check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
               "vkCreateGraphicsPipelines (floor pass)", error)) {
      return VK_NULL_HANDLE;
    }
    pipelines[format] = pipeline;
    return pipeline;
  }

  bool createComputePipeline(std::string& error) {
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, compute,
                  "main", nullptr};
    info.layout = pipelineLayout;
    return check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &computePipeline),
                 "vkCreateComputePipelines (compute floor pass)", error);
  }

  VkShaderStageFlags stage() const {
    return kind == FloorKind::Compute ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
  }

  void recordFragment(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, VkPipeline pipeline,
                      VkDescriptorSet set, const PushConstants& constants) const;
  void recordCompute(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, VkDescriptorSet set,
                     const PushConstants& constants) const;
};

std::unique_ptr<FloorPass> FloorPass::create(host::Device& device, FloorKind kind, std::string& error) {
  auto impl = std::make_unique<Impl>();
  Impl& p = *impl;
  p.kind = kind;
  p.device = device.device();
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device.physicalDevice(), &properties);
  p.timestampPeriodNs = properties.limits.timestampPeriod;
  std::uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device.physicalDevice(), &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(device.physicalDevice(), &familyCount, families.data());
  const std::uint32_t validBits = families.at(device.queueFamily()).timestampValidBits;
  if (validBits == 0) {
    error = "the floor pass needs timestamps, which the device's queue does not support";
    return nullptr;
  }
  p.timestampMask = validBits >= 64 ? ~0ull : (1ull << validBits) - 1;

  VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sampler.magFilter = sampler.minFilter = VK_FILTER_NEAREST;
  sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  if (!check(vkCreateSampler(p.device, &sampler, nullptr, &p.sampler), "vkCreateSampler", error)) return nullptr;
  // Fragment: depth (the blender reads the colour). Compute: depth, colour, colour as storage.
  const std::array<VkDescriptorSetLayoutBinding, 3> bindings{{
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, p.stage(), nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, p.stage(), nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, p.stage(), nullptr},
  }};
  const std::uint32_t bindingCount = kind == FloorKind::Compute ? 3 : 1;
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = bindingCount;
  setInfo.pBindings = bindings.data();
  if (!check(vkCreateDescriptorSetLayout(p.device, &setInfo, nullptr, &p.setLayout), "vkCreateDescriptorSetLayout",
             error)) {
    return nullptr;
  }
  VkPushConstantRange push{p.stage(), 0, sizeof(PushConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &p.setLayout;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  if (!check(vkCreatePipelineLayout(p.device, &layoutInfo, nullptr, &p.pipelineLayout), "vkCreatePipelineLayout",
             error)) {
    return nullptr;
  }
  const std::array<VkDescriptorPoolSize, 2> poolSizes{{
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * kMaxSlots},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kMaxSlots},
  }};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = kMaxSlots;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(poolSizes.size());
  poolInfo.pPoolSizes = poolSizes.data();
  if (!check(vkCreateDescriptorPool(p.device, &poolInfo, nullptr, &p.pool), "vkCreateDescriptorPool", error)) {
    return nullptr;
  }
  std::array<VkDescriptorSetLayout, kMaxSlots> layouts;
  layouts.fill(p.setLayout);
  VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocInfo.descriptorPool = p.pool;
  allocInfo.descriptorSetCount = kMaxSlots;
  allocInfo.pSetLayouts = layouts.data();
  if (!check(vkAllocateDescriptorSets(p.device, &allocInfo, p.sets.data()), "vkAllocateDescriptorSets", error)) {
    return nullptr;
  }
  VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
  queryInfo.queryCount = 2 * kMaxSlots;
  if (!check(vkCreateQueryPool(p.device, &queryInfo, nullptr, &p.queries), "vkCreateQueryPool", error)) {
    return nullptr;
  }
  if (kind == FloorKind::Compute) {
    if (!p.shaderModule(shaders::floor_comp(), p.compute, error) || !p.createComputePipeline(error)) return nullptr;
  } else if (!p.shaderModule(shaders::floor_vert(), p.vertex, error) ||
             !p.shaderModule(shaders::floor_frag(), p.fragment, error)) {
    return nullptr;
  }
  return std::unique_ptr<FloorPass>(new FloorPass(std::move(impl)));
}

FloorPass::FloorPass(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FloorPass::~FloorPass() = default;

bool FloorPass::resize(VkExtent2D, std::string&) { return true; }

bool FloorPass::record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string& error) {
  Impl& p = *impl_;
  if (inputs.frameSlot >= kMaxSlots) {
    error = "floor pass: frame slot " + std::to_string(inputs.frameSlot) + " beyond " + std::to_string(kMaxSlots);
    return false;
  }
  VkPipeline pipeline = p.computePipeline;
  if (p.kind == FloorKind::Compute) {
    if ((inputs.color.usage & VK_IMAGE_USAGE_STORAGE_BIT) == 0) {
      error = "compute floor pass: the back buffer has no STORAGE usage";
      return false;
    }
  } else {
    pipeline = p.pipelineFor(inputs.color.format, error);
    if (pipeline == VK_NULL_HANDLE) return false;
  }
  const VkDescriptorSet set = p.sets[inputs.frameSlot];
  // The slot's previous frame is complete (the host waited on its fence before recording).
  const std::array<VkDescriptorImageInfo, 3> images{{
      {p.sampler, inputs.depth.view, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
      {p.sampler, inputs.color.view, VK_IMAGE_LAYOUT_GENERAL},
      {VK_NULL_HANDLE, inputs.color.view, VK_IMAGE_LAYOUT_GENERAL},
  }};
  std::array<VkWriteDescriptorSet, 3> writes{};
  for (std::uint32_t i = 0; i < writes.size(); ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = i == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[i].pImageInfo = &images[i];
  }
  vkUpdateDescriptorSets(p.device, p.kind == FloorKind::Compute ? 3 : 1, writes.data(), 0, nullptr);

  const std::uint32_t firstQuery = 2 * inputs.frameSlot;
  vkCmdResetQueryPool(cmd, p.queries, firstQuery, 2);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, p.queries, firstQuery);
  const PushConstants constants{{0.5f, 0.55f, 0.6f, 0.01f},
                                {inputs.projection[2][2], inputs.projection[3][2], 0.0f, 0.0f}};
  if (p.kind == FloorKind::Compute) {
    p.recordCompute(cmd, inputs, set, constants);
  } else {
    p.recordFragment(cmd, inputs, pipeline, set, constants);
  }
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, p.queries, firstQuery + 1);
  p.lastSlot = inputs.frameSlot;
  return true;
}

namespace {

const VkImageSubresourceRange kDepthRange{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
const VkImageSubresourceRange kColorRange{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
constexpr VkPipelineStageFlags kDepthStages =
    VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;

// Depth: written by the host's G-buffer pass, read by the floor in `readStage`.
VkImageMemoryBarrier depthToRead(const host::PostProcessInputs& inputs) {
  return {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
          VK_ACCESS_SHADER_READ_BIT, inputs.depth.layout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
          VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, inputs.depth.image, kDepthRange};
}

// Depth back to the attachment layout the host expects once `readStage` is done with it.
void depthBack(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, VkPipelineStageFlags readStage) {
  VkImageMemoryBarrier after{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, 0,
                             VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                             VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, inputs.depth.layout,
                             VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, inputs.depth.image, kDepthRange};
  vkCmdPipelineBarrier(cmd, readStage, kDepthStages, 0, 0, nullptr, 0, nullptr, 1, &after);
}

}  // namespace

void FloorPass::Impl::recordFragment(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, VkPipeline pipeline,
                                     VkDescriptorSet set, const PushConstants& constants) const {
  // Colour: the host's writes before our blend reads and writes.
  constexpr VkAccessFlags kBlend = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  std::array<VkImageMemoryBarrier, 2> before{};
  before[0] = depthToRead(inputs);
  before[1] = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, kBlend,
               inputs.color.layout, inputs.color.layout, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
               inputs.color.image, kColorRange};
  vkCmdPipelineBarrier(cmd, kDepthStages | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                       nullptr, 0, nullptr, static_cast<std::uint32_t>(before.size()), before.data());

  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = inputs.color.view;
  color.imageLayout = inputs.color.layout;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, inputs.color.extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &rendering);
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(inputs.color.extent.width),
                            static_cast<float>(inputs.color.extent.height), 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &rendering.renderArea);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, pipelineLayout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(constants), &constants);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRendering(cmd);
  depthBack(cmd, inputs, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
}

void FloorPass::Impl::recordCompute(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, VkDescriptorSet set,
                                    const PushConstants& constants) const {
  // Colour: from the host's attachment writes to GENERAL, where the shader samples and stores it,
  // and back to the attachment layout after, as a compute composite does.
  std::array<VkImageMemoryBarrier, 2> before{};
  before[0] = depthToRead(inputs);
  before[1] = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
               VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT, inputs.color.layout, VK_IMAGE_LAYOUT_GENERAL,
               VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, inputs.color.image, kColorRange};
  vkCmdPipelineBarrier(cmd, kDepthStages | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr,
                       static_cast<std::uint32_t>(before.size()), before.data());
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout, 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
  constexpr std::uint32_t kGroup = 8;  // floor.comp's local_size_x and _y
  const VkExtent2D extent = inputs.color.extent;
  vkCmdDispatch(cmd, (extent.width + kGroup - 1) / kGroup, (extent.height + kGroup - 1) / kGroup, 1);
  const VkImageMemoryBarrier colorBack{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                                       VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                       VK_IMAGE_LAYOUT_GENERAL, inputs.color.layout, VK_QUEUE_FAMILY_IGNORED,
                                       VK_QUEUE_FAMILY_IGNORED, inputs.color.image, kColorRange};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &colorBack);
  depthBack(cmd, inputs, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
}

std::optional<double> FloorPass::lastMilliseconds() {
  Impl& p = *impl_;
  if (!p.lastSlot) return std::nullopt;
  std::array<std::uint64_t, 2> stamps{};
  if (vkGetQueryPoolResults(p.device, p.queries, 2 * *p.lastSlot, 2, sizeof(stamps), stamps.data(),
                            sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) != VK_SUCCESS) {
    return std::nullopt;
  }
  const std::uint64_t ticks = (stamps[1] - stamps[0]) & p.timestampMask;
  return static_cast<double>(ticks) * p.timestampPeriodNs * 1e-6;
}

}  // namespace tyndall::samples::bench
