// Shadow frusta fitted to the scene, and the depth-only shadow pass.
//
// Conventions every consumer relies on (tyndall::ShadowMapDesc): worldToShadowClip = proj · view
// with clip depth in [0, 1], 0 nearest the light; x, y ∈ [−1, 1] cover the map with
// u = (x + 1) / 2 → texel column u·N and v = (y + 1) / 2 → texel row v·N. Rendering with a
// positive-height viewport produces exactly that, so no y flip here.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "host_shaders.h"
#include "passes.h"

namespace tyndall::host::detail {

namespace {

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void add(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  bool overlapsXY(const Box& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y;
  }
};

// A view basis looking along `forward` with an up vector that is never parallel to it.
glm::dmat4 lookAlong(const glm::dvec3& eye, const glm::dvec3& forward) {
  const glm::dvec3 up = std::abs(forward.y) < 0.99 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
  return glm::lookAt(eye, eye + forward, up);
}

// Perspective with clip depth [0, 1], 0 at `n` (standard, finite), aspect 1, no y flip.
glm::dmat4 perspectiveZeroToOne(double fovY, double n, double f) {
  const double t = std::tan(fovY * 0.5);
  glm::dmat4 p(0.0);
  p[0][0] = 1.0 / t;
  p[1][1] = 1.0 / t;
  p[2][2] = -f / (f - n);
  p[2][3] = -1.0;
  p[3][2] = -n * f / (f - n);
  return p;
}

// Light-space boxes: x, y in the light's view, z = distance along the light direction.
Box lightSpaceBox(const glm::dmat4& view, const glm::vec3* points, std::size_t count) {
  Box box;
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec4 v = view * glm::dvec4(glm::dvec3(points[i]), 1.0);
    box.add(glm::dvec3(v.x, v.y, -v.z));
  }
  return box;
}

ShadowViews fitDirectional(const Light& light, const CameraSetup& camera, const SceneGeometry& geometry,
                           std::uint32_t mapSize) {
  const glm::dmat4 view = lookAlong(glm::dvec3(0.0), glm::normalize(light.direction));

  Box frustum;
  for (const glm::dvec3& corner : camera.frustumCorners) {
    const glm::dvec4 v = view * glm::dvec4(corner, 1.0);
    frustum.add(glm::dvec3(v.x, v.y, -v.z));
  }
  std::vector<Box> casters;
  Box allCasters;
  for (const auto& [first, count] : geometry.casterRanges) {
    casters.push_back(lightSpaceBox(view, geometry.casterPositions.data() + first, count));
    allCasters.add(casters.back());
  }

  // Only casters inside the frustum's light-space footprint can shadow a visible point (light
  // travels along z), and visible points outside every caster's footprint are lit: the window
  // is the intersection of both footprints.
  Box window = frustum;
  if (!allCasters.empty()) {
    Box both;
    both.lo = glm::max(frustum.lo, allCasters.lo);
    both.hi = glm::min(frustum.hi, allCasters.hi);
    if (both.lo.x <= both.hi.x && both.lo.y <= both.hi.y) {
      window.lo.x = both.lo.x;
      window.lo.y = both.lo.y;
      window.hi.x = both.hi.x;
      window.hi.y = both.hi.y;
    }
  }
  // Depth: from the nearest caster that reaches the window (points nearer than it are lit;
  // depth clamp keeps anything nearer, planes included, at 0) to the farthest visible point or caster.
  double zNear = std::numeric_limits<double>::infinity();
  double zFar = frustum.hi.z;
  for (const Box& caster : casters) {
    if (!caster.overlapsXY(window)) continue;
    zNear = std::min(zNear, caster.lo.z);
    zFar = std::max(zFar, caster.hi.z);
  }
  if (!std::isfinite(zNear)) zNear = frustum.lo.z;

  // Pads: two texels around the window (PCF and the receiver bias read one texel beyond a
  // caster's edge), 1% of the depth range so the farthest casters do not sit exactly at 1.
  const double size = static_cast<double>(mapSize);
  const double extent = std::max({window.hi.x - window.lo.x, window.hi.y - window.lo.y, 1e-3});
  const double padXY = 2.0 * extent / size;
  window.lo -= glm::dvec3(padXY);
  window.hi += glm::dvec3(padXY);
  const double padZ = 0.01 * (zFar - zNear) + 1e-3;
  zNear -= padZ;
  zFar += padZ;

  // Orthographic, built by hand: x, y to [−1, 1], distance along the light to [0, 1].
  glm::dmat4 ortho(1.0);
  ortho[0][0] = 2.0 / (window.hi.x - window.lo.x);
  ortho[1][1] = 2.0 / (window.hi.y - window.lo.y);
  ortho[2][2] = -1.0 / (zFar - zNear);  // view z is −distance
  ortho[3][0] = -(window.hi.x + window.lo.x) / (window.hi.x - window.lo.x);
  ortho[3][1] = -(window.hi.y + window.lo.y) / (window.hi.y - window.lo.y);
  ortho[3][2] = -zNear / (zFar - zNear);

  ShadowViews views;
  views.worldToShadowClip.push_back(ortho * view);
  views.footprint = std::max(window.hi.x - window.lo.x, window.hi.y - window.lo.y) / size;
  return views;
}

// Near and far distances from a spot or point light that enclose every finite caster and the
// visible volume. Planes are unbounded; depth clamp keeps their nearer parts at depth 0.
void fitRange(const glm::dvec3& position, const CameraSetup& camera, const SceneGeometry& geometry,
              double& nearOut, double& farOut) {
  Box bounds;
  for (const glm::dvec3& corner : camera.frustumCorners) bounds.add(corner);
  for (const glm::vec3& p : geometry.casterPositions) bounds.add(glm::dvec3(p));
  double farthest = 0.0;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 corner((i & 1) ? bounds.hi.x : bounds.lo.x, (i & 2) ? bounds.hi.y : bounds.lo.y,
                            (i & 4) ? bounds.hi.z : bounds.lo.z);
    farthest = std::max(farthest, glm::length(corner - position));
  }
  const double nearest = glm::length(glm::clamp(position, bounds.lo, bounds.hi) - position);
  farOut = farthest * 1.01 + 1e-3;
  // Nothing lies nearer than `nearest`; 1e-3·far keeps the depth precision usable.
  nearOut = std::max(1e-3 * farOut, 0.99 * nearest);
}

}  // namespace

ShadowViews fitShadowViews(const Light& light, const CameraSetup& camera, const SceneGeometry& geometry,
                           std::uint32_t mapSize) {
  if (light.type == LightType::Directional) return fitDirectional(light, camera, geometry, mapSize);

  double n = 0.0;
  double f = 0.0;
  fitRange(light.position, camera, geometry, n, f);
  ShadowViews views;
  if (light.type == LightType::Spot) {
    // 5° wider than the cone, so the PCF footprint at the cone's edge stays inside the map.
    const double fov = 2.0 * glm::radians(light.outerConeDegrees + 5.0);
    views.worldToShadowClip.push_back(perspectiveZeroToOne(fov, n, f) *
                                      lookAlong(light.position, glm::normalize(light.direction)));
    views.footprint = 2.0 * std::tan(fov * 0.5) / static_cast<double>(mapSize);
    return views;
  }

  // Point light: six 90° frusta sharing the position (klehm2014 §3.2), order +X −X +Y −Y +Z −Z.
  const glm::dmat4 projection = perspectiveZeroToOne(glm::radians(90.0), n, f);
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::dvec3& axis : axes) {
    views.worldToShadowClip.push_back(projection * lookAlong(light.position, axis));
  }
  views.footprint = 2.0 / static_cast<double>(mapSize);
  return views;
}

bool ShadowPass::create(const vk::GpuContext& gpu, std::string& error) {
  if (!createMeshPipelineLayout(gpu, layout_, error)) return false;
  const VkPipelineLayout layout = layout_.get();

  vk::GraphicsPipelineDesc desc;
  desc.layout = layout;
  desc.vertexShader = shaders::shadow_vert();
  desc.bindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  desc.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)}};
  desc.depthFormat = kShadowFormat;
  desc.depthCompare = VK_COMPARE_OP_LESS;
  desc.depthClamp = true;
  return vk::createGraphicsPipeline(gpu.device, desc, pipeline_, error);
}

void ShadowPass::record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& target,
                        const glm::mat4& worldToClip) const {
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = target.view();
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {1.0f, 0};  // cleared texels are lit

  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, target.extent()};
  rendering.layerCount = 1;
  rendering.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &rendering);
  vk::setViewport(cmd, target.extent());
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  const gpu::MeshPush push{worldToClip};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
  // No y flip in the shadow projections: world-space counter-clockwise faces come out clockwise.
  drawSceneGeometry(cmd, geometry, VK_FRONT_FACE_CLOCKWISE);
  vkCmdEndRendering(cmd);
}

}  // namespace tyndall::host::detail
