// The forward pass of translucent objects (passes.h, ForwardPass).
#include "host_shaders.h"
#include "passes.h"

namespace tyndall::host::detail {

bool ForwardPass::create(const vk::GpuContext& gpu, VkFormat colorFormat, VkCompareOp depthCompare,
                         std::string& error) {
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                 sizeof(gpu::ForwardPush)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  if (!vk::check(vkCreatePipelineLayout(gpu.device, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout", error))
    return false;
  layout_ = vk::UniquePipelineLayout(gpu.device, layout);

  vk::GraphicsPipelineDesc desc;
  desc.layout = layout;
  desc.vertexShader = shaders::forward_vert();
  desc.fragmentShader = shaders::forward_frag();
  desc.bindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                     {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                     {2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, albedo)},
                     {3, 0, VK_FORMAT_R32_SFLOAT, offsetof(Vertex, opacity)}};
  desc.colorFormats = {colorFormat};
  desc.depthFormat = kDepthFormat;
  desc.depthCompare = depthCompare;
  desc.depthWrite = false;
  desc.alphaBlend = true;
  return vk::createGraphicsPipeline(gpu.device, desc, pipeline_, error);
}

void ForwardPass::record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& target,
                         const vk::Image& depth, const gpu::ForwardPush& push) const {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = target.view();
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthAttachment.imageView = depth.view();
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;

  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, target.extent()};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  rendering.pDepthAttachment = &depthAttachment;
  vkCmdBeginRendering(cmd, &rendering);
  vk::setViewport(cmd, target.extent());
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                     &push);
  // Both sides of every surface: glass is seen through.
  drawTranslucentGeometry(cmd, geometry);
  vkCmdEndRendering(cmd);
}

}  // namespace tyndall::host::detail
