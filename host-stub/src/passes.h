// Internal to the stub host: the camera and shadow-frustum set-up (CPU, double precision), the
// merged scene geometry, and the three render passes the Renderer records every frame.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "host_shared.glsl"
#include "tyndall_host/renderer.h"
#include "vk_util.h"

namespace tyndall::host::detail {

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;
// Linear albedo in 8 bits loses the darks; the sRGB encoding stores it perceptually and the
// sampler decodes it back to linear for free.
inline constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_SRGB;
inline constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kAovFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

inline bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// ---------------------------------------------------------------------------------------------
// Camera
// ---------------------------------------------------------------------------------------------

struct CameraSetup {
  glm::dmat4 view{1.0};        // glm::lookAt(position, target, up)
  glm::dmat4 projection{1.0};  // Vulkan clip, depth [0, 1], y flipped (row 0 = top of the picture)
  // World-space corners of the view frustum: near plane (4), then far plane (4).
  std::array<glm::dvec3, 8> frustumCorners{};
  // The frustum again, as the cascades split it: frustumCorners' planes lie at view depths
  // nearDepth and farDepth (the camera's far plane, with an infinite-far projection too), and a
  // point at view depth d along `forward` from `position` is within ±d·tanHalfFov of the axis.
  glm::dvec3 position{0.0};
  glm::dvec3 forward{0.0, 0.0, -1.0};
  double nearDepth = 0.0;
  double farDepth = 0.0;
  glm::dvec2 tanHalfFov{0.0};  // x: horizontal, y: vertical
  float depthClear = 1.0f;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
};

/// Builds the camera for a `width`×`height` image; fails on a degenerate camera.
bool makeCamera(const Camera& camera, std::uint32_t width, std::uint32_t height,
                DepthConvention depth, bool infiniteFar, CameraSetup& out, std::string& error);

// ---------------------------------------------------------------------------------------------
// Geometry: every object triangulated once and merged into one vertex and one index buffer
// (one draw call for the whole scene: the forest has ~2,000 boxes).
// ---------------------------------------------------------------------------------------------

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 albedo;
  float opacity;  // Object::opacity: below 1 in the translucent range only
};

struct SceneGeometry {
  vk::Buffer vertices;
  vk::Buffer indices;
  // Closed meshes (boxes, spheres) first, drawn with back-face culling: for a closed mesh the
  // nearest surface is always front-facing, so culling changes no depth and halves the triangles.
  // Then open ones (plane quads, glTF meshes of unknown topology), drawn two-sided.
  std::uint32_t closedIndexCount = 0;
  std::uint32_t openIndexCount = 0;
  // Then the translucent objects (Object::opacity < 1): not in the depth buffer or the opaque
  // shadow maps, only in the translucent peel pass, drawn two-sided (each surface crossed counts).
  std::uint32_t translucentIndexCount = 0;
  // Positions of the finite objects (not infinite planes), one range per object: the shadow
  // frusta are fitted to them.
  std::vector<glm::vec3> casterPositions;
  std::vector<std::array<std::uint32_t, 2>> casterRanges;  // {first, count}
};

bool buildSceneGeometry(const vk::GpuContext& gpu, VkCommandPool pool, const Scene& scene,
                        SceneGeometry& out, std::string& error);

/// Binds the geometry and draws it (pipeline and push constants already bound). `frontFace` is
/// the winding of front faces in the framebuffer: counter-clockwise for the y-flipped camera
/// projection, clockwise for the shadow projections, which do not flip y.
void drawSceneGeometry(VkCommandBuffer cmd, const SceneGeometry& geometry, VkFrontFace frontFace);
/// Binds the geometry and draws its translucent range two-sided (pipeline and push constants bound).
void drawTranslucentGeometry(VkCommandBuffer cmd, const SceneGeometry& geometry);
/// The pipeline layout of the passes that draw the scene geometry: one MeshPush constant block.
bool createMeshPipelineLayout(const vk::GpuContext& gpu, vk::UniquePipelineLayout& out, std::string& error);

// ---------------------------------------------------------------------------------------------
// Shadow frusta
// ---------------------------------------------------------------------------------------------

// One shadow map of a light: what HostShadowMap hands effects and the lighting pass reads.
struct ShadowView {
  glm::dmat4 worldToShadowClip{1.0};
  // World size of one texel: directional, in scene units; spot/point, per unit of distance along
  // the frustum axis (2 tan(fov/2) / N).
  double footprint = 0.0;
  // A directional light's cascade: the view depths [viewDepthNear, viewDepthFar) it serves (the
  // first also nearer ones, the last farther ones). 0 and 0 for a single map, spot and point lights.
  float viewDepthNear = 0.0f;
  float viewDepthFar = 0.0f;
};

// 1 (directional, spot), 2..kMaxSceneCascades (a directional light's cascades, finest first) or
// 6 (point: +X −X +Y −Y +Z −Z).
using ShadowViews = std::vector<ShadowView>;

/// Fits the light's shadow frusta to the casters and the visible volume (see renderer.h).
/// `cascades` > 1 splits a directional light's map into that many by `cascadeSplit` (λ in
/// [0, 1]); spot and point lights ignore both.
ShadowViews fitShadowViews(const Light& light, const CameraSetup& camera, const SceneGeometry& geometry,
                           std::uint32_t mapSize, std::uint32_t cascades, double cascadeSplit);

/// Depth-only rasterisation of the whole scene into one shadow map (depth clamp on).
class ShadowPass {
 public:
  bool create(const vk::GpuContext& gpu, std::string& error);
  /// `target` in DEPTH_STENCIL_ATTACHMENT_OPTIMAL; cleared to 1 and rendered.
  void record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& target,
              const glm::mat4& worldToClip) const;

 private:
  vk::UniquePipelineLayout layout_;
  vk::UniquePipeline pipeline_;
};

/// The translucent objects as seen from one shadow map, depth-peeled into the layers of an
/// R32G32_SFLOAT array (tyndall::ShadowMapDesc::translucentLayers): layer k holds the (depth, α) of
/// the k-th surface from the light in front of the opaque depth, (1, 0) where there is none; the
/// layer after the count is the overflow layer. One descriptor set per (frame slot, map, layer).
class TranslucentPass {
 public:
  static constexpr VkFormat kLayerFormat = VK_FORMAT_R32G32_SFLOAT;
  bool create(const vk::GpuContext& gpu, std::uint32_t setCount, std::string& error);
  /// Points set `set` at the map's opaque depth and the layer before (layer 0: the opaque depth again).
  void bind(std::uint32_t set, VkImageView opaqueDepth, VkImageView previousLayer);
  /// Peels layer `layer` of `layers` with set `set`. The opaque map and the previous layer in
  /// SHADER_READ_ONLY_OPTIMAL, the layer in COLOR_ATTACHMENT_OPTIMAL and `depth` (the map's size,
  /// kShadowFormat) in DEPTH_STENCIL_ATTACHMENT_OPTIMAL; both are cleared.
  void record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& layers, std::uint32_t layer,
              std::uint32_t set, const vk::Image& depth, const glm::mat4& worldToClip) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  vk::UniqueSampler sampler_;
  vk::UniqueDescriptorSetLayout setLayout_;
  vk::UniqueDescriptorPool pool_;
  std::vector<VkDescriptorSet> sets_;
  vk::UniquePipelineLayout layout_;
  vk::UniquePipeline pipeline_;
};

/// The translucent objects forward-shaded and blended over the lit back buffer with their opacity,
/// depth-tested against the G-buffer's depth (not written: they stay out of the depth buffer, as
/// an engine's forward transparency does). Unsorted: overlapping translucent objects blend in draw order.
class ForwardPass {
 public:
  bool create(const vk::GpuContext& gpu, VkFormat colorFormat, VkCompareOp depthCompare, std::string& error);
  /// `target` in COLOR_ATTACHMENT_OPTIMAL, `depth` in DEPTH_STENCIL_ATTACHMENT_OPTIMAL (read only).
  void record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& target, const vk::Image& depth,
              const gpu::ForwardPush& push) const;

 private:
  vk::UniquePipelineLayout layout_;
  vk::UniquePipeline pipeline_;
};

/// G-buffer: depth, albedo, normal.
class GBufferPass {
 public:
  bool create(const vk::GpuContext& gpu, VkCompareOp depthCompare, std::string& error);
  /// Targets in DEPTH_STENCIL_ATTACHMENT_OPTIMAL / COLOR_ATTACHMENT_OPTIMAL.
  void record(VkCommandBuffer cmd, const SceneGeometry& geometry, const vk::Image& depth,
              const vk::Image& albedo, const vk::Image& normal, const glm::mat4& clipFromWorld,
              float depthClear) const;

 private:
  vk::UniquePipelineLayout layout_;
  vk::UniquePipeline pipeline_;
};

/// Full-screen deferred lighting into the back buffer, one full-screen draw per light; one
/// descriptor set per frame slot and light.
class LightingPass {
 public:
  struct SlotInputs {  // of one light in one slot
    VkBuffer params = VK_NULL_HANDLE;  // gpu::LightingParams
    VkImageView depth = VK_NULL_HANDLE;
    VkImageView albedo = VK_NULL_HANDLE;
    VkImageView normal = VK_NULL_HANDLE;
    std::vector<VkImageView> shadowMaps;  // 1, 2..4 (cascades) or 6
    VkImageView lightColor = VK_NULL_HANDLE;  // the light's colour texture (1×1 white without one)
  };

  bool create(const vk::GpuContext& gpu, VkFormat colorFormat, std::uint32_t slotCount,
              std::uint32_t lightCount, std::string& error);
  /// Points the descriptor set of light `light` in slot `slot` at its images (after creation and
  /// after a resize).
  void bindSlot(std::uint32_t slot, std::uint32_t light, const SlotInputs& inputs);
  /// G-buffer and shadow maps in SHADER_READ_ONLY_OPTIMAL, `target` in COLOR_ATTACHMENT_OPTIMAL.
  /// The first light overwrites `target`, the others are blended onto it additively.
  void record(VkCommandBuffer cmd, std::uint32_t slot, const vk::Image& target) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  vk::UniqueSampler pointSampler_;
  vk::UniqueSampler shadowSampler_;
  vk::UniqueSampler linearSampler_;
  vk::UniqueDescriptorSetLayout setLayout_;
  vk::UniqueDescriptorPool pool_;
  std::vector<VkDescriptorSet> sets_;  // slot · lightCount_ + light; freed with the pool
  std::uint32_t lightCount_ = 1;
  vk::UniquePipelineLayout layout_;
  vk::UniquePipeline pipeline_;          // the first light
  vk::UniquePipeline additivePipeline_;  // the others; only with more than one light
};

}  // namespace tyndall::host::detail
