// The stub host: a minimal headless deferred renderer that replicates what an engine hands a
// post-process (depth, HDR back buffer, shadow maps) and runs a post-process stack.
// It does not depend on the Tyndall plugin: the plugin is inserted as a PostProcessEffect.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "tyndall_host/scene.h"

namespace tyndall::host {

struct DeviceOptions {
  bool validation = false;       ///< enable VK_LAYER_KHRONOS_validation with synchronization validation
  bool preferDiscreteGpu = true; ///< a discrete GPU if present, else any (lavapipe on a CPU-only machine)
};

/// Instance, physical device, device and one graphics+compute queue, created headless.
/// Enables Vulkan 1.3 features dynamicRendering, synchronization2 and the core features
/// dualSrcBlend, depthClamp (what the plugin and the host need).
class Device {
 public:
  static std::unique_ptr<Device> create(const DeviceOptions& options, std::string& error);
  ~Device();

  VkInstance instance() const;
  VkPhysicalDevice physicalDevice() const;
  VkDevice device() const;
  VkQueue queue() const;
  std::uint32_t queueFamily() const;
  std::string name() const;  ///< physical device name, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  PFN_vkGetInstanceProcAddr getInstanceProcAddr() const;
  PFN_vkGetDeviceProcAddr getDeviceProcAddr() const;
  /// Held around every use of queue(): Vulkan requires a queue's users to synchronise, and
  /// renderers on several threads (a render thread per view) share the one queue.
  std::mutex& queueMutex() const;

  /// Validation messages (warnings and errors) received so far, each one line.
  const std::vector<std::string>& validationMessages() const;
  void clearValidationMessages();

  struct Impl;
 private:
  explicit Device(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

enum class DepthConvention { Standard, Reverse };

struct RenderSettings {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  /// Every light's shadow-map size. 0: each light's own shadowMap.size, else the scene's.
  std::uint32_t shadowMapSize = 0;
  /// Every directional light's cascade count, 1..kMaxSceneCascades. 0: each light's own
  /// shadowMap.cascades, else the scene's.
  std::uint32_t cascades = 0;
  DepthConvention depth = DepthConvention::Standard;
  bool infiniteFar = false;         ///< projection with the far plane at infinity
  std::uint32_t framesInFlight = 2; ///< 1..16; each slot has its own command buffer, fence and images
  /// Colour attachment with blending and a readback path: R16G16B16A16_SFLOAT, R32G32B32A32_SFLOAT,
  /// R8G8B8A8/B8G8R8A8 UNORM or SRGB, A2B10G10R10_UNORM_PACK32.
  VkFormat backBufferFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  bool aovImages = false;           ///< allocate the RGBA32F AOV images handed to effects (L_in, T, debug view)
  /// Give the back buffer STORAGE usage when its format supports storage images (what engines do
  /// for compute post-processes); false never adds it, so effects take their fragment path.
  bool storageBackBuffer = true;
  /// Depth-peeled layers per shadow map of a scene with translucent objects (Object::opacity < 1),
  /// 1..kMaxTranslucentLayers; a texel with more surfaces is flagged by the overflow layer.
  std::uint32_t translucentLayers = 4;
};

/// The most translucent layers RenderSettings::translucentLayers takes (tyndall::kMaxTranslucentLayers).
inline constexpr std::uint32_t kMaxTranslucentLayers = 8;

/// An image of the host as a post-process sees it (mirrors tyndall::ImageRef).
struct HostImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImageUsageFlags usage = 0;  ///< the usage the image was created with; 0: not reported (only the back buffer reports it)
};

struct HostShadowMap {
  HostImage depth;               ///< D32_SFLOAT, SHADER_READ_ONLY_OPTIMAL when effects run
  /// proj · view: clip depth [0, 1] with 0 nearest the light (cleared to 1), x, y ∈ [−1, 1] over
  /// the map, u = (x + 1) / 2 → column u·N, v = (y + 1) / 2 → row v·N. Directional: orthographic,
  /// fitted to the casters that can shadow the visible volume (nearer points clamp to depth 0).
  /// Spot: perspective, fov = 2·(outer cone + 5°). Point: six 90° faces +X −X +Y −Y +Z −Z.
  /// A directional light's cascade: orthographic over the bounding sphere of its slice of the
  /// view frustum, centred on a whole texel of a grid fixed in the world.
  glm::mat4 worldToShadowClip{1.0f};
  /// A directional light's cascade (2..kMaxSceneCascades maps, finest first): the view depths
  /// [viewDepthNear, viewDepthFar) it serves, scene units along the camera's −Z, split by the
  /// light's cascadeSplit (else the scene's) over [camera near, camera far]. Cascade i + 1's
  /// viewDepthNear is cascade i's viewDepthFar (the same float); the first begins at 0, the last
  /// ends at the camera's far plane (also with an infinite-far projection). 0 and 0 for a single
  /// map, spot and point lights.
  float viewDepthNear = 0.0f;
  float viewDepthFar = 0.0f;
  /// With translucent objects in the scene: their surfaces in front of `depth`, depth-peeled
  /// nearest the light first into translucentLayerCount layers of an R32G32_SFLOAT array, (depth,
  /// opacity) per texel, (1, 0) where there are fewer, then the overflow layer (the next peel);
  /// SHADER_READ_ONLY_OPTIMAL, `view` a 2D_ARRAY view of all of them. Empty, count 0, without.
  HostImage translucentLayers;
  std::uint32_t translucentLayerCount = 0;
};

/// A light after the scene's first (Scene::additionalLights), as effects see it.
struct LightInputs {
  const Light* light = nullptr;           ///< into PostProcessInputs::scene->additionalLights
  /// 1 (directional, spot), 1..4 (directional: its cascades) or 6 (point), at the light's size
  std::vector<HostShadowMap> shadowMaps;
  HostImage lightColor;                   ///< as PostProcessInputs::lightColor, for this light
};

/// What the host hands each post-process effect, per frame.
struct PostProcessInputs {
  std::uint64_t frameIndex = 0;
  std::uint32_t frameSlot = 0;       ///< frameIndex % framesInFlight
  glm::mat4 view{1.0f};              ///< world → view (lookAt)
  glm::mat4 projection{1.0f};        ///< Vulkan clip (depth [0,1]), y flipped so image row 0 is the top
  const Scene* scene = nullptr;      ///< light and medium come from here
  /// scene->light's: 1 (directional, spot), 1..4 (directional: its cascades) or 6 (point)
  std::vector<HostShadowMap> shadowMaps;
  HostImage depth;                   ///< D32_SFLOAT, DEPTH_STENCIL_ATTACHMENT_OPTIMAL
  HostImage color;                   ///< back buffer, COLOR_ATTACHMENT_OPTIMAL, with its usage
  HostImage aovScattering;           ///< RGBA32F, TRANSFER_DST_OPTIMAL, only with aovImages
  HostImage aovTransmittance;        ///< RGBA32F, TRANSFER_DST_OPTIMAL, only with aovImages
  HostImage aovDebug;                ///< RGBA32F, TRANSFER_DST_OPTIMAL, only with aovImages (cleared to 0)
  /// The scene light's colour texture (stained glass over shadow map 0's square), R8G8B8A8_SRGB,
  /// SHADER_READ_ONLY_OPTIMAL; empty when the light has none.
  HostImage lightColor;
  /// The scene's second and later lights, in order (empty for a scene with one light).
  std::vector<LightInputs> additionalLights;
};

/// A pass of the post-process stack, inserted exactly as an engine would insert one.
class PostProcessEffect {
 public:
  virtual ~PostProcessEffect() = default;
  /// Records into `cmd`; returns false with `error` to abort the frame.
  virtual bool record(VkCommandBuffer cmd, const PostProcessInputs& inputs, std::string& error) = 0;
  /// The output extent changed; the GPU is idle.
  virtual bool resize(VkExtent2D extent, std::string& error) = 0;
};

/// Float RGBA image read back from the GPU, row 0 at the top.
struct ImageRgba32f {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> pixels;  ///< width · height · 4
};

class Renderer {
 public:
  /// `device` must outlive the renderer. The scene is copied; objects are triangulated once.
  static std::unique_ptr<Renderer> create(Device& device, const Scene& scene,
                                          const RenderSettings& settings, std::string& error);
  ~Renderer();

  /// Appends an effect to the post-process stack (runs after lighting, before display). Not
  /// owned: it must stay alive while the renderer renders or resizes.
  void addPostProcess(PostProcessEffect* effect);

  /// Renders one frame (shadow, G-buffer, lighting, post-process stack), submits it and returns
  /// without waiting for it unless framesInFlight frames are already pending.
  bool renderFrame(std::string& error);
  /// Waits until the GPU finished every submitted frame.
  void waitIdle();
  /// Moves the camera for the frames rendered next (the shadow frusta, fitted to the camera's
  /// frustum, follow); frames already submitted keep theirs. False with `error` for a camera the
  /// scene loader would reject (then nothing changes).
  bool setCamera(const Camera& camera, std::string& error);
  /// Rebuilds size-dependent resources (GPU idle first) and calls every effect's resize.
  bool resize(std::uint32_t width, std::uint32_t height, std::string& error);

  /// After waitIdle: the back buffer of the last frame (scene-linear), and the AOVs.
  bool readBackBuffer(ImageRgba32f& out, std::string& error);
  bool readAovScattering(ImageRgba32f& out, std::string& error);
  bool readAovTransmittance(ImageRgba32f& out, std::string& error);
  bool readAovDebug(ImageRgba32f& out, std::string& error);

  const RenderSettings& settings() const;
  glm::mat4 viewMatrix() const;
  glm::mat4 projectionMatrix() const;

  struct Impl;
 private:
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Display transform with OpenColorIO (config shipped in host-stub/ocio/config.ocio, embedded at
/// build time): scene-linear Rec.709 → sRGB display, 8-bit RGBA, row 0 at the top.
bool displayToSrgb8(const ImageRgba32f& linear, std::vector<std::uint8_t>& rgba8, std::string& error);

/// Image files. PNG through stb_image_write, EXR (RGB float32, scene-linear) through OpenEXR.
/// Both write to a temporary file and rename, so nothing is half-written.
bool writePng(const std::string& path, std::uint32_t width, std::uint32_t height,
              const std::vector<std::uint8_t>& rgba8, std::string& error);
bool writeExr(const std::string& path, const ImageRgba32f& image, std::string& error);
/// Any PNG, expanded to 8-bit RGBA, row 0 at the top.
bool readPng(const std::string& path, std::uint32_t& width, std::uint32_t& height, std::vector<std::uint8_t>& rgba8,
             std::string& error);
bool readExr(const std::string& path, ImageRgba32f& out, std::string& error);

}  // namespace tyndall::host
