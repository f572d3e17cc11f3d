// The camera, the merged scene geometry and the G-buffer pass.
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "host_shaders.h"
#include "passes.h"

namespace tyndall::host::detail {

namespace {

// Copies `bytes` into a new device-local buffer through a staging buffer, and makes the copy
// visible to `dstStages`/`dstAccess` before the call returns (it waits for the upload).
bool uploadBuffer(const vk::GpuContext& gpu, VkCommandPool pool, const void* data, VkDeviceSize bytes,
                  VkBufferUsageFlags usage, VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess,
                  vk::Buffer& out, std::string& error) {
  vk::Buffer staging;
  if (!staging.create(gpu, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, error) ||
      !out.create(gpu, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                  VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, error)) {
    return false;
  }
  std::memcpy(staging.mapped(), data, static_cast<std::size_t>(bytes));
  return vk::submitAndWait(gpu, pool, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, staging.buffer(), out.buffer(), 1, &region);
    vk::Barriers()
        .buffer(out.buffer(), {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT},
                {dstStages, dstAccess})
        .record(cmd);
  }, error);
}

}  // namespace

bool makeCamera(const Camera& camera, std::uint32_t width, std::uint32_t height,
                DepthConvention depth, bool infiniteFar, CameraSetup& out, std::string& error) {
  const double n = camera.nearPlane;
  const double f = camera.farPlane;
  if (width == 0 || height == 0) {
    error = "image size must be at least 1x1";
    return false;
  }
  if (!isFinite(camera.position) || !isFinite(camera.target) || !isFinite(camera.up) || !std::isfinite(n) ||
      !std::isfinite(f) || !(n > 0.0) || !(f > n)) {
    error = "camera: needs finite vectors and 0 < near < far";
    return false;
  }
  if (!(camera.fovYDegrees > 0.0 && camera.fovYDegrees < 180.0)) {
    error = "camera: fovYDegrees must be in (0, 180)";
    return false;
  }
  const glm::dvec3 toTarget = camera.target - camera.position;
  const glm::dvec3 side = glm::cross(toTarget, camera.up);
  if (glm::length(toTarget) <= 0.0 || glm::length(side) <= 1e-9 * glm::length(toTarget) * glm::length(camera.up)) {
    error = "camera: target equals position, or up is parallel to the view direction";
    return false;
  }

  out.view = glm::lookAt(camera.position, camera.target, camera.up);

  // Built by hand rather than with glm::perspective so that GL's [−1, 1] depth cannot leak in.
  const double tanHalf = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  glm::dmat4 p(0.0);
  p[0][0] = 1.0 / (aspect * tanHalf);
  p[1][1] = -1.0 / tanHalf;  // y flipped: image row 0 is the top of the picture
  p[2][3] = -1.0;            // clip w = distance in front of the camera
  // clip z = A·z_view + B; depth = A·z/−z + B/−z, solved for depth(near) and depth(far).
  double a = 0.0;
  double b = 0.0;
  if (depth == DepthConvention::Standard) {  // near → 0, far → 1
    a = infiniteFar ? -1.0 : -f / (f - n);
    b = infiniteFar ? -n : -n * f / (f - n);
    out.depthClear = 1.0f;
    out.depthCompare = VK_COMPARE_OP_LESS;
  } else {  // near → 1, far → 0
    a = infiniteFar ? 0.0 : n / (f - n);
    b = infiniteFar ? n : n * f / (f - n);
    out.depthClear = 0.0f;
    out.depthCompare = VK_COMPARE_OP_GREATER;
  }
  p[2][2] = a;
  p[3][2] = b;
  out.projection = p;

  // The same basis as glm::lookAt, so the frustum matches the rays of the rendered image.
  const glm::dvec3 forward = glm::normalize(toTarget);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  out.position = camera.position;
  out.forward = forward;
  out.nearDepth = n;
  out.farDepth = f;
  out.tanHalfFov = {tanHalf * aspect, tanHalf};
  int corner = 0;
  for (double distance : {n, f}) {
    for (double sy : {-1.0, 1.0}) {
      for (double sx : {-1.0, 1.0}) {
        out.frustumCorners[static_cast<std::size_t>(corner++)] =
            camera.position + distance * (forward + right * (sx * tanHalf * aspect) + up * (sy * tanHalf));
      }
    }
  }
  return true;
}

bool buildSceneGeometry(const vk::GpuContext& gpu, VkCommandPool pool, const Scene& scene,
                        SceneGeometry& out, std::string& error) {
  // Infinite planes become quads large enough to reach past the far plane in every direction
  // the camera can see, and to cover the region any shadow frustum is fitted to.
  const double planeHalfSize = 4.0 * scene.camera.farPlane;
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> closedIndices;
  std::vector<std::uint32_t> openIndices;
  std::vector<std::uint32_t> translucentIndices;
  out.casterPositions.clear();
  out.casterRanges.clear();

  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    std::vector<TriangleMesh> meshes;
    std::string meshError;
    if (!triangulate(object, planeHalfSize, scene.camera.position, meshes, meshError)) {
      error = "objects[" + std::to_string(i) + "]: " + meshError;
      return false;
    }
    const auto casterFirst = static_cast<std::uint32_t>(out.casterPositions.size());
    for (const TriangleMesh& mesh : meshes) {
      if (mesh.normals.size() != mesh.positions.size() || mesh.indices.size() % 3 != 0) {
        error = "objects[" + std::to_string(i) + "]: malformed mesh (normals or indices)";
        return false;
      }
      if (vertices.size() + mesh.positions.size() > UINT32_MAX) {
        error = "scene has more than 2^32 vertices";
        return false;
      }
      const bool closed = object.type == ObjectType::Box || object.type == ObjectType::Sphere;
      std::vector<std::uint32_t>& indices =
          object.translucent() ? translucentIndices : closed ? closedIndices : openIndices;
      const auto base = static_cast<std::uint32_t>(vertices.size());
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        vertices.push_back({mesh.positions[v], mesh.normals[v], mesh.albedo, static_cast<float>(object.opacity)});
      }
      for (std::uint32_t index : mesh.indices) {
        if (index >= mesh.positions.size()) {
          error = "objects[" + std::to_string(i) + "]: mesh index out of range";
          return false;
        }
        indices.push_back(base + index);
      }
      if (object.type != ObjectType::Plane) {
        out.casterPositions.insert(out.casterPositions.end(), mesh.positions.begin(), mesh.positions.end());
      }
    }
    const auto casterCount = static_cast<std::uint32_t>(out.casterPositions.size()) - casterFirst;
    if (casterCount > 0) out.casterRanges.push_back({casterFirst, casterCount});
  }

  out.closedIndexCount = static_cast<std::uint32_t>(closedIndices.size());
  out.openIndexCount = static_cast<std::uint32_t>(openIndices.size());
  out.translucentIndexCount = static_cast<std::uint32_t>(translucentIndices.size());
  std::vector<std::uint32_t> indices = std::move(closedIndices);
  indices.insert(indices.end(), openIndices.begin(), openIndices.end());
  indices.insert(indices.end(), translucentIndices.begin(), translucentIndices.end());
  if (indices.empty()) return true;  // an empty scene draws nothing
  return uploadBuffer(gpu, pool, vertices.data(), vertices.size() * sizeof(Vertex),
                      VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT,
                      VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, out.vertices, error) &&
         uploadBuffer(gpu, pool, indices.data(), indices.size() * sizeof(std::uint32_t),
                      VK_BUFFER_USAGE_INDEX_BUFFER_BIT, VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT,
                      VK_ACCESS_2_INDEX_READ_BIT, out.indices, error);
}

void drawSceneGeometry(VkCommandBuffer cmd, const SceneGeometry& geometry, VkFrontFace frontFace) {
  if (geometry.closedIndexCount + geometry.openIndexCount == 0) return;
  const VkBuffer vertexBuffer = geometry.vertices.buffer();
  const VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
  vkCmdBindIndexBuffer(cmd, geometry.indices.buffer(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdSetFrontFace(cmd, frontFace);
  if (geometry.closedIndexCount > 0) {
    vkCmdSetCullMode(cmd, VK_CULL_MODE_BACK_BIT);
    vkCmdDrawIndexed(cmd, geometry.closedIndexCount, 1, 0, 0, 0);
  }
  if (geometry.openIndexCount > 0) {
    vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
    vkCmdDrawIndexed(cmd, geometry.openIndexCount, 1, geometry.closedIndexCount, 0, 0);
  }
}

void drawTranslucentGeometry(VkCommandBuffer cmd, const SceneGeometry& geometry) {
  if (geometry.translucentIndexCount == 0) return;
  const VkBuffer vertexBuffer = geometry.vertices.buffer();
  const VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
  vkCmdBindIndexBuffer(cmd, geometry.indices.buffer(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdSetFrontFace(cmd, VK_FRONT_FACE_CLOCKWISE);
  vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
  vkCmdDrawIndexed(cmd, geometry.translucentIndexCount, 1, geometry.closedIndexCount + geometry.openIndexCount, 0, 0);
}

bool createMeshPipelineLayout(const vk::GpuContext& gpu, vk::UniquePipelineLayout& out, std::string& error) {
  VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(gpu::MeshPush)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  if (!vk::check(vkCreatePipelineLayout(gpu.device, &layoutInfo, nullptr, &layout),
                 "vkCreatePipelineLayout", error)) {
    return false;
  }
  out = vk::UniquePipelineLayout(gpu.device, layout);
  return true;
}

bool GBufferPass::create(const vk::GpuContext& gpu, VkCompareOp depthCompare, std::string& error) {
  if (!createMeshPipelineLayout(gpu, layout_, error)) return false;
  const VkPipelineLayout layout = layout_.get();

  vk::GraphicsPipelineDesc desc;
  desc.layout = layout;
  desc.vertexShader = shaders::gbuffer_vert();
  desc.fragmentShader = shaders::gbuffer_frag();
  desc.bindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                     {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                     {2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, albedo)}};
  desc.colorFormats = {kAlbedoFormat, kNormalFormat};
  desc.depthFormat = kDepthFormat;
  desc.depthCompare = depthCompare;
  return vk::createGraphicsPipeline(gpu.device, desc, pipeline_, error);
}

void GBufferPass::record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& depth,
                         const vk::Image& albedo, const vk::Image& normal, const glm::mat4& clipFromWorld,
                         float depthClear) const {
  VkRenderingAttachmentInfo colors[2]{};
  const vk::Image* colorImages[2] = {&albedo, &normal};
  for (int i = 0; i < 2; ++i) {
    colors[i].sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    colors[i].imageView = colorImages[i]->view();
    colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colors[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
  }
  VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthAttachment.imageView = depth.view();
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depthAttachment.clearValue.depthStencil = {depthClear, 0};

  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, depth.extent()};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 2;
  rendering.pColorAttachments = colors;
  rendering.pDepthAttachment = &depthAttachment;
  vkCmdBeginRendering(cmd, &rendering);
  vk::setViewport(cmd, depth.extent());
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  const gpu::MeshPush push{clipFromWorld};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
  // The projection flips y, which keeps world-space counter-clockwise front faces counter-clockwise
  // in Vulkan's framebuffer convention (gbuffer.frag relies on it for two-sided planes).
  drawSceneGeometry(cmd, geometry, VK_FRONT_FACE_COUNTER_CLOCKWISE);
  vkCmdEndRendering(cmd);
}

}  // namespace tyndall::host::detail
