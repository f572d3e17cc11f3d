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
template <typename Point>
Box lightSpaceBox(const glm::dmat4& view, const Point* points, std::size_t count) {
  Box box;
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec4 v = view * glm::dvec4(glm::dvec3(points[i]), 1.0);
    box.add(glm::dvec3(v.x, v.y, -v.z));
  }
  return box;
}

// One light-space box per finite object: the casters the directional maps are fitted to.
std::vector<Box> casterBoxes(const glm::dmat4& view, const SceneGeometry& geometry) {
  std::vector<Box> casters;
  for (const auto& [first, count] : geometry.casterRanges) {
    casters.push_back(lightSpaceBox(view, geometry.casterPositions.data() + first, count));
  }
  return casters;
}

struct DepthRange {
  double zNear = 0.0;
  double zFar = 0.0;
};

// Depth: from the nearest caster that reaches the window (points nearer than it are lit; depth
// clamp keeps anything nearer, planes included, at 0) to the farthest visible point or caster,
// padded by 1% of the range so the farthest casters do not sit exactly at 1.
DepthRange lightDepthRange(const std::vector<Box>& casters, const Box& window, const Box& visible) {
  double zNear = std::numeric_limits<double>::infinity();
  double zFar = visible.hi.z;
  for (const Box& caster : casters) {
    if (!caster.overlapsXY(window)) continue;
    zNear = std::min(zNear, caster.lo.z);
    zFar = std::max(zFar, caster.hi.z);
  }
  if (!std::isfinite(zNear)) zNear = visible.lo.z;
  const double padZ = 0.01 * (zFar - zNear) + 1e-3;
  return {zNear - padZ, zFar + padZ};
}

// Orthographic, built by hand: light-space x, y in centre ± halfExtent to [−1, 1], distance along
// the light in [zNear, zFar] to [0, 1].
glm::dmat4 orthographic(const glm::dvec2& centre, const glm::dvec2& halfExtent, const DepthRange& depth) {
  glm::dmat4 ortho(1.0);
  ortho[0][0] = 1.0 / halfExtent.x;
  ortho[1][1] = 1.0 / halfExtent.y;
  ortho[2][2] = -1.0 / (depth.zFar - depth.zNear);  // view z is −distance
  ortho[3][0] = -centre.x / halfExtent.x;
  ortho[3][1] = -centre.y / halfExtent.y;
  ortho[3][2] = -depth.zNear / (depth.zFar - depth.zNear);
  return ortho;
}

// One map over the whole visible volume, as tight as the casters allow.
ShadowViews fitDirectional(const Light& light, const CameraSetup& camera, const SceneGeometry& geometry,
                           std::uint32_t mapSize) {
  const glm::dmat4 view = lookAlong(glm::dvec3(0.0), glm::normalize(light.direction));
  const Box frustum = lightSpaceBox(view, camera.frustumCorners.data(), camera.frustumCorners.size());
  const std::vector<Box> casters = casterBoxes(view, geometry);
  Box allCasters;
  for (const Box& caster : casters) allCasters.add(caster);

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
  const DepthRange depth = lightDepthRange(casters, window, frustum);

  // Two texels around the window: PCF and the receiver bias read one texel beyond a caster's edge.
  const double size = static_cast<double>(mapSize);
  const double extent = std::max({window.hi.x - window.lo.x, window.hi.y - window.lo.y, 1e-3});
  const double padXY = 2.0 * extent / size;
  window.lo -= glm::dvec3(padXY);
  window.hi += glm::dvec3(padXY);

  const glm::dvec2 lo(window.lo);
  const glm::dvec2 hi(window.hi);
  ShadowView map;
  map.worldToShadowClip = orthographic(0.5 * (hi + lo), 0.5 * (hi - lo), depth) * view;
  map.footprint = std::max(window.hi.x - window.lo.x, window.hi.y - window.lo.y) / size;
  return {map};
}

// The split depths of [n, f] into `count` cascades by Zhang et al. 2006, "Parallel-split shadow
// maps for large-scale virtual environments" (§3.2, the practical split scheme):
// d_i = λ·n·(f/n)^(i/K) + (1 − λ)·(n + (f − n)·i/K). Floats, as ShadowMapDesc carries them, so
// that a cascade's far and the next one's near are the same value; d_0 is 0, since the first
// cascade also serves whatever is nearer than n, and d_K is f.
std::vector<float> cascadeSplits(double n, double f, std::uint32_t count, double lambda) {
  std::vector<float> splits(count + 1, 0.0f);
  for (std::uint32_t i = 1; i < count; ++i) {
    const double x = static_cast<double>(i) / count;
    splits[i] = static_cast<float>(lambda * n * std::pow(f / n, x) + (1.0 - lambda) * (n + (f - n) * x));
  }
  splits[count] = static_cast<float>(f);
  return splits;
}

// A cascade serving view depths [a, b]: an orthographic map over the bounding sphere of that slice
// of the frustum. The sphere's radius depends only on a, b and the field of view, so the map's
// size in the world stays the same as the camera turns and moves, and its centre is snapped to
// whole texels in light space, so the texel grid stays fixed in the world too (no shimmering).
ShadowView fitCascade(const glm::dmat4& view, const CameraSetup& camera, const std::vector<Box>& casters,
                      double a, double b, std::uint32_t mapSize) {
  // On the axis at depth z, the sphere through the slice's near and far corners (k = the corners'
  // distance from the axis per unit of depth); past b, the far corners' circle holds them all.
  const double k2 = glm::dot(camera.tanHalfFov, camera.tanHalfFov);
  const double z = std::min(0.5 * (a + b) * (1.0 + k2), b);
  const double radius = std::sqrt(std::max((z - a) * (z - a) + a * a * k2, (b - z) * (b - z) + b * b * k2));

  // Two texels around the sphere, as around the single map's window; snapping moves the centre
  // by at most half a texel.
  const double size = static_cast<double>(mapSize);
  const double halfExtent = radius * (1.0 + 4.0 / size);
  const double texel = 2.0 * halfExtent / size;
  const glm::dvec2 centre = glm::dvec2(view * glm::dvec4(camera.position + camera.forward * z, 1.0));
  const glm::dvec2 snapped = texel * glm::round(centre / texel);

  // The slice's corners, on the lines between the frustum's near and far corners.
  std::array<glm::dvec3, 8> corners{};
  for (std::size_t i = 0; i < 4; ++i) {
    const glm::dvec3 nearCorner = camera.frustumCorners[i];
    const glm::dvec3 farCorner = camera.frustumCorners[i + 4];
    const double span = camera.farDepth - camera.nearDepth;
    corners[i] = nearCorner + (farCorner - nearCorner) * ((a - camera.nearDepth) / span);
    corners[i + 4] = nearCorner + (farCorner - nearCorner) * ((b - camera.nearDepth) / span);
  }
  const Box slice = lightSpaceBox(view, corners.data(), corners.size());
  Box window;
  window.add(glm::dvec3(snapped - halfExtent, 0.0));
  window.add(glm::dvec3(snapped + halfExtent, 0.0));

  ShadowView map;
  map.worldToShadowClip = orthographic(snapped, glm::dvec2(halfExtent), lightDepthRange(casters, window, slice)) * view;
  map.footprint = texel;
  return map;
}

ShadowViews fitCascades(const Light& light, const CameraSetup& camera, const SceneGeometry& geometry,
                        std::uint32_t mapSize, std::uint32_t count, double lambda) {
  const glm::dmat4 view = lookAlong(glm::dvec3(0.0), glm::normalize(light.direction));
  const std::vector<Box> casters = casterBoxes(view, geometry);
  const std::vector<float> splits = cascadeSplits(camera.nearDepth, camera.farDepth, count, lambda);
  ShadowViews views;
  for (std::uint32_t i = 0; i < count; ++i) {
    const double a = std::max(static_cast<double>(splits[i]), camera.nearDepth);
    ShadowView& map = views.emplace_back(fitCascade(view, camera, casters, a, splits[i + 1], mapSize));
    map.viewDepthNear = splits[i];
    map.viewDepthFar = splits[i + 1];
  }
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
                           std::uint32_t mapSize, std::uint32_t cascades, double cascadeSplit) {
  if (light.type == LightType::Directional) {
    return cascades > 1 ? fitCascades(light, camera, geometry, mapSize, cascades, cascadeSplit)
                        : fitDirectional(light, camera, geometry, mapSize);
  }

  double n = 0.0;
  double f = 0.0;
  fitRange(light.position, camera, geometry, n, f);
  if (light.type == LightType::Spot) {
    // 5° wider than the cone, so the PCF footprint at the cone's edge stays inside the map.
    const double fov = 2.0 * glm::radians(light.outerConeDegrees + 5.0);
    ShadowView map;
    map.worldToShadowClip =
        perspectiveZeroToOne(fov, n, f) * lookAlong(light.position, glm::normalize(light.direction));
    map.footprint = 2.0 * std::tan(fov * 0.5) / static_cast<double>(mapSize);
    return {map};
  }

  // Point light: six 90° frusta sharing the position (klehm2014 §3.2), order +X −X +Y −Y +Z −Z.
  const glm::dmat4 projection = perspectiveZeroToOne(glm::radians(90.0), n, f);
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  ShadowViews views;
  for (const glm::dvec3& axis : axes) {
    views.push_back({projection * lookAlong(light.position, axis), 2.0 / static_cast<double>(mapSize)});
  }
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
