// The stub host's frame loop: frames in flight, per-slot render targets, the barriers between the
// passes, the post-process stack and the readback.
//
// Per frame, in one command buffer:
//   shadow map(s) of every light → G-buffer → lighting, one draw per light (into the back
//   buffer) → post-process effects
// Every image of a slot starts the frame in UNDEFINED (its content is regenerated), so a frame
// never depends on what a previous frame or an effect left in it.
#include <cmath>
#include <cstring>
#include <optional>

#include <glm/gtc/packing.hpp>

#include "passes.h"

namespace tyndall::host {

using detail::CameraSetup;
using detail::ShadowViews;

namespace {

// A dim sky: the radiance of pixels where nothing was drawn, and the ambient light.
constexpr glm::vec3 kSkyRadiance{0.02f, 0.03f, 0.05f};
constexpr glm::vec3 kAmbient{0.02f, 0.03f, 0.05f};
constexpr std::uint32_t kMaxFramesInFlight = 16;
static_assert(gpu::kHostMaxCascades == static_cast<int>(kMaxSceneCascades));

// The stages and accesses the frame's barriers name.
using Scope = vk::Barriers::Scope;
// Whatever touched a slot's image last (our passes, an effect in any stage, a readback) is ordered
// before the frame's first write: execution dependency on all commands for the reads, MEMORY_WRITE
// for the writes. The contents are discarded (UNDEFINED) and regenerated.
const Scope kPreviousUse{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT};
const Scope kDepthAttachment{VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                             VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
const Scope kDepthWritten{kDepthAttachment.stages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
const Scope kColorAttachment{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                             VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
const Scope kColorWritten{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
const Scope kFragmentRead{VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

// What a frame slot holds for one light.
struct LightTargets {
  vk::Buffer params;  // gpu::LightingParams, host-visible
  std::vector<vk::Image> shadowMaps;
  // With translucent objects: per map the peeled layers (layer count + 1 overflow layer), the
  // peel pass's depth and its descriptor sets from firstPeelSet, (map, layer) in order.
  std::vector<vk::Image> translucentLayers;
  vk::Image peelDepth;
  std::uint32_t firstPeelSet = 0;
};

struct FrameSlot {
  VkCommandBuffer cmd = VK_NULL_HANDLE;  // freed with the pool
  vk::UniqueFence fence;
  bool pending = false;  // submitted and not yet waited for
  std::vector<LightTargets> lights;  // as Renderer::Impl::lights
  // Size-dependent.
  vk::Image depth;
  vk::Image albedo;
  vk::Image normal;
  vk::Image color;
  vk::Image aovScattering;
  vk::Image aovTransmittance;
  vk::Image aovDebug;
};

// One light of the scene as the renderer keeps it; lights[0] is Scene::light, then
// Scene::additionalLights in order.
struct LightState {
  const Light* light = nullptr;  // into Renderer::Impl::scene
  std::uint32_t shadowMapSize = 0;
  std::uint32_t cascades = 1;  // a directional light's shadow maps; 1 for spot and point lights
  double cascadeSplit = 0.8;   // λ of the practical split scheme (Scene::cascadeSplit)
  ShadowViews shadowViews;
  vk::Image color;  // the light's colour texture (R8G8B8A8_SRGB), or 1×1 white without one
};

std::uint32_t bytesPerPixel(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
      return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      return 0;  // not readable by this host
  }
}

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Converts tightly packed texels of `format` to float RGBA (sRGB formats decoded to linear).
void decodePixels(VkFormat format, const std::uint8_t* data, std::size_t pixelCount, float* out) {
  for (std::size_t i = 0; i < pixelCount; ++i, out += 4) {
    switch (format) {
      case VK_FORMAT_R32G32B32A32_SFLOAT:
        std::memcpy(out, data + 16 * i, 16);
        break;
      case VK_FORMAT_R16G16B16A16_SFLOAT: {
        std::uint16_t half[4];
        std::memcpy(half, data + 8 * i, 8);
        for (int c = 0; c < 4; ++c) out[c] = glm::unpackHalf1x16(half[c]);
        break;
      }
      case VK_FORMAT_A2B10G10R10_UNORM_PACK32: {
        std::uint32_t packed = 0;
        std::memcpy(&packed, data + 4 * i, 4);
        out[0] = static_cast<float>(packed & 1023u) / 1023.0f;
        out[1] = static_cast<float>((packed >> 10) & 1023u) / 1023.0f;
        out[2] = static_cast<float>((packed >> 20) & 1023u) / 1023.0f;
        out[3] = static_cast<float>(packed >> 30) / 3.0f;
        break;
      }
      default: {  // the four 8-bit formats
        const std::uint8_t* texel = data + 4 * i;
        const bool bgra = format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
        const bool srgb = format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_B8G8R8A8_SRGB;
        const int order[4] = {bgra ? 2 : 0, 1, bgra ? 0 : 2, 3};
        for (int c = 0; c < 4; ++c) {
          const float value = static_cast<float>(texel[order[c]]) / 255.0f;
          out[c] = (srgb && c < 3) ? srgbToLinear(value) : value;
        }
        break;
      }
    }
  }
}

bool inUnitRange(double value) { return value >= 0.0 && value <= 1.0; }

// `name` prefixes the error: "light", or "lights[i]" in a scene with several.
bool validateLight(const Light& light, const std::string& name, std::string& error) {
  if (!detail::isFinite(light.color) || !std::isfinite(light.intensity) || light.intensity < 0.0 ||
      light.color.x < 0.0 || light.color.y < 0.0 || light.color.z < 0.0) {
    error = name + ": colour and intensity must be finite and >= 0";
    return false;
  }
  // What the scene loader checks, again for lights built in code.
  if (light.cascades > kMaxSceneCascades || (light.cascadeSplit && !inUnitRange(*light.cascadeSplit))) {
    error = name + ": shadowMap.cascades must be in [0, 4] (0: the scene's) and shadowMap.cascadeSplit in [0, 1]";
    return false;
  }
  if (light.type == LightType::Directional) {
    if (!detail::isFinite(light.direction) || glm::length(light.direction) <= 0.0) {
      error = name + ": directional light needs a finite, non-zero direction";
      return false;
    }
    return true;
  }
  if (light.cascades > 1 || light.cascadeSplit) {
    error = name + ": only directional lights take cascades (shadowMap.cascades, shadowMap.cascadeSplit)";
    return false;
  }
  if (!detail::isFinite(light.position)) {
    error = name + ": position must be finite";
    return false;
  }
  if (light.type == LightType::Spot) {
    if (!detail::isFinite(light.direction) || glm::length(light.direction) <= 0.0) {
      error = name + ": spot light needs a finite, non-zero direction";
      return false;
    }
    // The shadow frustum is 2·(outer + 5°) wide and must stay below 180°.
    if (!(light.outerConeDegrees > 0.0 && light.outerConeDegrees <= 80.0) ||
        !(light.innerConeDegrees >= 0.0 && light.innerConeDegrees <= light.outerConeDegrees)) {
      error = name + ": spot cones need 0 <= inner <= outer <= 80 degrees (outer > 0)";
      return false;
    }
  }
  return true;
}

}  // namespace

struct Renderer::Impl {
  Device& device;
  vk::GpuContext gpu;
  Scene scene;
  RenderSettings settings;
  VkImageUsageFlags colorUsage = 0;
  VkImageUsageFlags aovUsage = 0;

  vk::UniqueCommandPool pool;
  detail::SceneGeometry geometry;
  detail::ShadowPass shadowPass;
  detail::GBufferPass gbufferPass;
  detail::LightingPass lightingPass;
  detail::TranslucentPass translucentPass;
  detail::ForwardPass forwardPass;
  std::uint32_t nextPeelSet = 0;   // the next one createSlot hands out
  CameraSetup camera;
  std::vector<LightState> lights;
  std::vector<FrameSlot> slots;

  std::vector<PostProcessEffect*> effects;  // not owned
  std::uint64_t frameIndex = 0;
  std::optional<std::uint32_t> lastSlot;  // slot of the last submitted frame
  std::string brokenReason;               // set when a resize failed half-way

  explicit Impl(Device& d) : device(d) {}
  ~Impl() {
    // Members are destroyed after this body, in reverse order: nothing may still be in use.
    if (gpu.device != VK_NULL_HANDLE) {
      std::lock_guard<std::mutex> lock(device.queueMutex());  // waiting idle uses the queue too
      vkDeviceWaitIdle(gpu.device);
    }
  }

  bool init(const Scene& sceneIn, const RenderSettings& settingsIn, std::string& error);
  bool checkFormats(std::string& error);
  bool createSlot(FrameSlot& slot, std::string& error);
  bool createSizeDependent(std::string& error);
  bool updateViews(std::string& error);
  void writeParams(FrameSlot& slot) const;
  void recordFrame(FrameSlot& slot, std::uint32_t slotIndex) const;
  void recordTranslucentLayers(VkCommandBuffer cmd, const FrameSlot& slot) const;
  bool waitSlot(FrameSlot& slot, std::string& error);
  bool waitAll(std::string& error);
  bool readImage(const vk::Image& image, VkImageLayout layout, ImageRgba32f& out, std::string& error);
  bool createLightColor(const Light& light, vk::Image& lightColor, std::string& error);
};

// Uploads a light's colour texture once (a white texel when it has none, so the lighting pass
// always has one to sample), SHADER_READ_ONLY_OPTIMAL from then on.
bool Renderer::Impl::createLightColor(const Light& light, vk::Image& lightColor, std::string& error) {
  std::uint32_t width = 1, height = 1;
  std::vector<std::uint8_t> rgba8{255, 255, 255, 255};
  if (!light.colorTexture.empty() && !readPng(light.colorTexture.string(), width, height, rgba8, error)) {
    return false;
  }
  if (!lightColor.create(gpu, {VK_FORMAT_R8G8B8A8_SRGB, {width, height},
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "light colour"},
                         error)) {
    return false;
  }
  vk::Buffer staging;
  if (!staging.create(gpu, rgba8.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, error)) {
    return false;
  }
  std::memcpy(staging.mapped(), rgba8.data(), rgba8.size());
  return vk::submitAndWait(gpu, pool.get(), [&](VkCommandBuffer cmd) {
    const vk::Barriers::Scope copyWrite{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
    vk::Barriers()
        .image(lightColor.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE}, copyWrite)
        .record(cmd);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer(), lightColor.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
    vk::Barriers()
        .image(lightColor.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, copyWrite,
               {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT})
        .record(cmd);
  }, error);
}

bool Renderer::Impl::init(const Scene& sceneIn, const RenderSettings& settingsIn, std::string& error) {
  scene = sceneIn;
  settings = settingsIn;
  gpu.physicalDevice = device.physicalDevice();
  gpu.device = device.device();
  gpu.queue = device.queue();
  gpu.queueMutex = &device.queueMutex();
  gpu.queueFamily = device.queueFamily();
  vkGetPhysicalDeviceMemoryProperties(gpu.physicalDevice, &gpu.memory);

  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(gpu.physicalDevice, &properties);
  const std::uint32_t maxSize = properties.limits.maxImageDimension2D;
  if (settings.framesInFlight < 1 || settings.framesInFlight > kMaxFramesInFlight) {
    error = "framesInFlight must be in [1, " + std::to_string(kMaxFramesInFlight) + "]";
    return false;
  }
  if (settings.width < 1 || settings.height < 1 || settings.width > maxSize || settings.height > maxSize) {
    error = "image size must be in [1, " + std::to_string(maxSize) + "] in both directions";
    return false;
  }
  if (settings.cascades > kMaxSceneCascades) {
    error = "cascades must be in [0, 4] (0: each light's own)";
    return false;
  }
  if (settings.translucentLayers < 1 || settings.translucentLayers > kMaxTranslucentLayers) {
    error = "translucentLayers must be in [1, " + std::to_string(kMaxTranslucentLayers) + "]";
    return false;
  }
  if (scene.cascades < 1 || scene.cascades > kMaxSceneCascades || !inUnitRange(scene.cascadeSplit)) {
    error = "shadowMap: cascades must be in [1, 4] and cascadeSplit in [0, 1]";
    return false;
  }
  lights.resize(1 + scene.additionalLights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    LightState& state = lights[i];
    state.light = i == 0 ? &scene.light : &scene.additionalLights[i - 1];
    // The command line's size (RenderSettings) overrides every light's, a light's its scene's.
    state.shadowMapSize = settings.shadowMapSize != 0       ? settings.shadowMapSize
                          : state.light->shadowMapSize != 0 ? state.light->shadowMapSize
                                                            : scene.shadowMapSize;
    const std::string name = lights.size() == 1 ? "light" : "lights[" + std::to_string(i) + "]";
    if (state.shadowMapSize < 1 || state.shadowMapSize > maxSize) {
      error = (lights.size() == 1 ? std::string() : name + ": ") + "shadow map size must be in [1, " +
              std::to_string(maxSize) + "]";
      return false;
    }
    if (!validateLight(*state.light, name, error)) return false;
    // The same order of precedence for the cascades, which only directional lights take.
    const Light& light = *state.light;
    state.cascades = light.type != LightType::Directional ? 1
                     : settings.cascades != 0             ? settings.cascades
                     : light.cascades != 0                ? light.cascades
                                                          : scene.cascades;
    state.cascadeSplit = light.cascadeSplit.value_or(scene.cascadeSplit);
    // The colour texture lies over one map's square (Tyndall's FrameDesc::lightColor likewise).
    if (state.cascades > 1 && !light.colorTexture.empty()) {
      error = name + ": a colour texture needs one shadow map, not " + std::to_string(state.cascades) + " cascades";
      return false;
    }
  }
  if (!checkFormats(error)) return false;

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  // Each slot re-records its command buffer every frame.
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = gpu.queueFamily;
  VkCommandPool rawPool = VK_NULL_HANDLE;
  if (!vk::check(vkCreateCommandPool(gpu.device, &poolInfo, nullptr, &rawPool), "vkCreateCommandPool", error))
    return false;
  pool = vk::UniqueCommandPool(gpu.device, rawPool);

  // The shadow frusta are fitted to the geometry: build it first.
  if (!detail::buildSceneGeometry(gpu, pool.get(), scene, geometry, error) || !updateViews(error)) return false;
  for (LightState& state : lights) {
    if (!createLightColor(*state.light, state.color, error)) return false;
  }
  // One peel descriptor set per frame slot, light, map and layer (the overflow layer included).
  std::uint32_t peelSetCount = 0;
  if (geometry.translucentIndexCount > 0) {
    for (const LightState& state : lights) {
      peelSetCount += static_cast<std::uint32_t>(state.shadowViews.size()) * (settings.translucentLayers + 1);
    }
    peelSetCount *= settings.framesInFlight;
  }
  if (!translucentPass.create(gpu, peelSetCount, error) ||
      !forwardPass.create(gpu, settings.backBufferFormat, camera.depthCompare, error)) {
    return false;
  }
  if (!shadowPass.create(gpu, error) || !gbufferPass.create(gpu, camera.depthCompare, error) ||
      !lightingPass.create(gpu, settings.backBufferFormat, settings.framesInFlight,
                           static_cast<std::uint32_t>(lights.size()), error)) {
    return false;
  }

  slots.resize(settings.framesInFlight);
  nextPeelSet = 0;
  for (FrameSlot& slot : slots) {
    if (!createSlot(slot, error)) return false;
  }
  return createSizeDependent(error);
}

bool Renderer::Impl::checkFormats(std::string& error) {
  const VkFormat format = settings.backBufferFormat;
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(gpu.physicalDevice, format, &properties);
  const VkFormatFeatureFlags features = properties.optimalTilingFeatures;
  // Effects composite into the back buffer with blending (tyndall::FrameDesc::color).
  const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                                      VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
                                      VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
  if (bytesPerPixel(format) == 0 || (features & needed) != needed) {
    error = "back buffer format " + std::to_string(static_cast<int>(format)) +
            " is not supported (needs colour attachment with blending, sampling, transfer source and "
            "a host readback path: RGBA16F, RGBA32F, RGBA8/BGRA8 UNORM or SRGB, A2B10G10R10)";
    return false;
  }
  colorUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  // Engines make the back buffer storage-capable where the format allows, for compute post-processes;
  // the setting turns it off so the fragment paths can be exercised on the same format.
  if (settings.storageBackBuffer && (features & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0) {
    colorUsage |= VK_IMAGE_USAGE_STORAGE_BIT;
  }

  vkGetPhysicalDeviceFormatProperties(gpu.physicalDevice, detail::kAovFormat, &properties);
  const VkFormatFeatureFlags aovFeatures = properties.optimalTilingFeatures;
  if (settings.aovImages) {
    const VkFormatFeatureFlags aovNeeded =
        VK_FORMAT_FEATURE_TRANSFER_DST_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT;
    if ((aovFeatures & aovNeeded) != aovNeeded) {
      error = "R32G32B32A32_SFLOAT lacks transfer/blit support for the AOV images";
      return false;
    }
  }
  aovUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  if ((aovFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0) aovUsage |= VK_IMAGE_USAGE_STORAGE_BIT;
  if ((aovFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) != 0) aovUsage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  return true;
}

bool Renderer::Impl::createSlot(FrameSlot& slot, std::string& error) {
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool.get();
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  if (!vk::check(vkAllocateCommandBuffers(gpu.device, &allocInfo, &slot.cmd), "vkAllocateCommandBuffers", error))
    return false;
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  if (!vk::check(vkCreateFence(gpu.device, &fenceInfo, nullptr, &fence), "vkCreateFence", error)) return false;
  slot.fence = vk::UniqueFence(gpu.device, fence);
  slot.lights.resize(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    LightTargets& targets = slot.lights[i];
    const std::uint32_t size = lights[i].shadowMapSize;
    if (!targets.params.create(gpu, sizeof(gpu::LightingParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                               VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, error)) {
      return false;
    }
    targets.shadowMaps.resize(lights[i].shadowViews.size());
    for (vk::Image& map : targets.shadowMaps) {
      const vk::Image::Desc desc{detail::kShadowFormat, {size, size},
                                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                     VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 "shadow map"};
      if (!map.create(gpu, desc, error)) return false;
    }
    if (geometry.translucentIndexCount == 0) continue;
    const std::uint32_t layers = settings.translucentLayers + 1;
    if (!targets.peelDepth.create(gpu, {detail::kShadowFormat, {size, size},
                                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "translucent peel depth"},
                                  error)) {
      return false;
    }
    targets.firstPeelSet = nextPeelSet;
    targets.translucentLayers.resize(targets.shadowMaps.size());
    for (std::size_t m = 0; m < targets.shadowMaps.size(); ++m) {
      vk::Image& image = targets.translucentLayers[m];
      vk::Image::Desc desc{detail::TranslucentPass::kLayerFormat, {size, size},
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                               VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                           "translucent layers"};
      desc.layers = layers;
      if (!image.create(gpu, desc, error)) return false;
      for (std::uint32_t layer = 0; layer < layers; ++layer) {
        const VkImageView previous = layer == 0 ? targets.shadowMaps[m].view() : image.layerView(layer - 1);
        translucentPass.bind(nextPeelSet++, targets.shadowMaps[m].view(), previous);
      }
    }
  }
  return true;
}

bool Renderer::Impl::createSizeDependent(std::string& error) {
  const VkExtent2D extent{settings.width, settings.height};
  for (std::uint32_t i = 0; i < slots.size(); ++i) {
    FrameSlot& slot = slots[i];
    if (!slot.depth.create(gpu, {detail::kDepthFormat, extent,
                                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                     VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 "depth"}, error) ||
        !slot.albedo.create(gpu, {detail::kAlbedoFormat, extent,
                                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "albedo"},
                            error) ||
        !slot.normal.create(gpu, {detail::kNormalFormat, extent,
                                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "normal"},
                            error) ||
        !slot.color.create(gpu, {settings.backBufferFormat, extent, colorUsage, "back buffer"}, error)) {
      return false;
    }
    if (settings.aovImages) {
      if (!slot.aovScattering.create(gpu, {detail::kAovFormat, extent, aovUsage, "AOV scattering"}, error) ||
          !slot.aovTransmittance.create(gpu, {detail::kAovFormat, extent, aovUsage, "AOV transmittance"}, error) ||
          !slot.aovDebug.create(gpu, {detail::kAovFormat, extent, aovUsage, "AOV debug view"}, error)) {
        return false;
      }
    }
    for (std::uint32_t light = 0; light < lights.size(); ++light) {
      detail::LightingPass::SlotInputs inputs;
      inputs.params = slot.lights[light].params.buffer();
      inputs.depth = slot.depth.view();
      inputs.albedo = slot.albedo.view();
      inputs.normal = slot.normal.view();
      for (const vk::Image& map : slot.lights[light].shadowMaps) inputs.shadowMaps.push_back(map.view());
      inputs.lightColor = lights[light].color.view();
      lightingPass.bindSlot(i, light, inputs);
    }
  }
  return true;
}

bool Renderer::Impl::updateViews(std::string& error) {
  if (!detail::makeCamera(scene.camera, settings.width, settings.height, settings.depth, settings.infiniteFar,
                          camera, error)) {
    return false;
  }
  // Shadow frusta are fitted to the camera frustum too, whose aspect follows the image.
  for (LightState& state : lights) {
    state.shadowViews =
        detail::fitShadowViews(*state.light, camera, geometry, state.shadowMapSize, state.cascades, state.cascadeSplit);
  }
  return true;
}

void Renderer::Impl::writeParams(FrameSlot& slot) const {
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const LightState& state = lights[i];
    const ShadowViews& shadowViews = state.shadowViews;
    gpu::LightingParams p{};
    for (std::size_t m = 0; m < 6; ++m) {
      p.worldToShadowClip[m] = m < shadowViews.size() ? glm::mat4(shadowViews[m].worldToShadowClip) : glm::mat4(1.0f);
    }
    p.viewToWorld = glm::mat4(glm::inverse(camera.view));
    p.projection = glm::vec4(camera.projection[0][0], camera.projection[1][1], camera.projection[2][2],
                             camera.projection[3][2]);
    const Light& light = *state.light;
    p.lightPosition = glm::vec4(glm::vec3(light.position), 1.0f);
    const glm::dvec3 direction =
        glm::length(light.direction) > 0.0 ? glm::normalize(light.direction) : glm::dvec3(0.0, -1.0, 0.0);
    p.lightDirection = glm::vec4(glm::vec3(direction), 0.0f);
    p.lightRadiance = glm::vec4(glm::vec3(light.color * light.intensity), 0.0f);
    p.spotCone = glm::vec4(static_cast<float>(std::cos(glm::radians(light.outerConeDegrees))),
                           static_cast<float>(std::cos(glm::radians(light.innerConeDegrees))), 0.0f, 0.0f);
    p.shadow = glm::vec4(static_cast<float>(shadowViews[0].footprint), static_cast<float>(state.shadowMapSize), 0.0f,
                         0.0f);
    if (light.type == LightType::Directional) {
      for (std::size_t c = 0; c < shadowViews.size(); ++c) {
        const auto element = static_cast<glm::length_t>(c);
        p.cascadeFar[element] = shadowViews[c].viewDepthFar;
        p.cascadeFootprint[element] = static_cast<float>(shadowViews[c].footprint);
      }
    }
    p.sky = glm::vec4(kSkyRadiance, camera.depthClear);
    p.ambient = glm::vec4(kAmbient, 0.0f);
    const int type = light.type == LightType::Directional ? gpu::kHostLightDirectional
                     : light.type == LightType::Spot      ? gpu::kHostLightSpot
                                                          : gpu::kHostLightPoint;
    p.mode = glm::ivec4(type, static_cast<int>(shadowViews.size()),
                        static_cast<int>(settings.width), static_cast<int>(settings.height));
    p.additive = glm::ivec4(i == 0 ? 0 : 1, 0, 0, 0);
    std::memcpy(slot.lights[i].params.mapped(), &p, sizeof(p));  // coherent memory: visible at submission
  }
}

void Renderer::Impl::recordFrame(FrameSlot& slot, std::uint32_t slotIndex) const {
  const VkCommandBuffer cmd = slot.cmd;
  const Scope clearWrite{VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
  constexpr VkImageLayout kUndefined = VK_IMAGE_LAYOUT_UNDEFINED;
  constexpr VkImageLayout kDepthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  constexpr VkImageLayout kColorLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  constexpr VkImageLayout kReadLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  constexpr VkImageLayout kAovLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  constexpr VkImageAspectFlags kDepthAspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  constexpr VkImageAspectFlags kColorAspect = VK_IMAGE_ASPECT_COLOR_BIT;

  vk::Barriers barriers;
  for (const LightTargets& light : slot.lights) {
    for (const vk::Image& map : light.shadowMaps) {
      barriers.image(map.image(), kDepthAspect, kUndefined, kDepthLayout, kPreviousUse, kDepthAttachment);
    }
  }
  barriers.image(slot.depth.image(), kDepthAspect, kUndefined, kDepthLayout, kPreviousUse, kDepthAttachment)
      .image(slot.albedo.image(), kColorAspect, kUndefined, kColorLayout, kPreviousUse, kColorAttachment)
      .image(slot.normal.image(), kColorAspect, kUndefined, kColorLayout, kPreviousUse, kColorAttachment)
      .image(slot.color.image(), kColorAspect, kUndefined, kColorLayout, kPreviousUse, kColorAttachment);
  if (settings.aovImages) {
    barriers.image(slot.aovScattering.image(), kColorAspect, kUndefined, kAovLayout, kPreviousUse, clearWrite)
        .image(slot.aovTransmittance.image(), kColorAspect, kUndefined, kAovLayout, kPreviousUse, clearWrite)
        .image(slot.aovDebug.image(), kColorAspect, kUndefined, kAovLayout, kPreviousUse, clearWrite);
  }
  barriers.record(cmd);

  if (settings.aovImages) {
    // What an effect that writes nothing leaves: no in-scattering, full transmittance.
    const VkImageSubresourceRange range{kColorAspect, 0, 1, 0, 1};
    const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
    const VkClearColorValue one{{1.0f, 1.0f, 1.0f, 1.0f}};
    vkCmdClearColorImage(cmd, slot.aovScattering.image(), kAovLayout, &zero, 1, &range);
    vkCmdClearColorImage(cmd, slot.aovTransmittance.image(), kAovLayout, &one, 1, &range);
    vkCmdClearColorImage(cmd, slot.aovDebug.image(), kAovLayout, &zero, 1, &range);
  }

  for (std::size_t light = 0; light < lights.size(); ++light) {
    const std::vector<vk::Image>& maps = slot.lights[light].shadowMaps;
    for (std::size_t i = 0; i < maps.size(); ++i) {
      shadowPass.record(cmd, geometry, maps[i], glm::mat4(lights[light].shadowViews[i].worldToShadowClip));
    }
  }
  if (geometry.translucentIndexCount > 0) recordTranslucentLayers(cmd, slot);
  gbufferPass.record(cmd, geometry, slot.depth, slot.albedo, slot.normal,
                     glm::mat4(camera.projection * camera.view), camera.depthClear);

  if (geometry.translucentIndexCount == 0) {  // else read by the peel pass already
    for (const LightTargets& light : slot.lights) {
      for (const vk::Image& map : light.shadowMaps) {
        barriers.image(map.image(), kDepthAspect, kDepthLayout, kReadLayout, kDepthWritten, kFragmentRead);
      }
    }
  }
  barriers.image(slot.depth.image(), kDepthAspect, kDepthLayout, kReadLayout, kDepthWritten, kFragmentRead)
      .image(slot.albedo.image(), kColorAspect, kColorLayout, kReadLayout, kColorWritten, kFragmentRead)
      .image(slot.normal.image(), kColorAspect, kColorLayout, kReadLayout, kColorWritten, kFragmentRead)
      .record(cmd);

  lightingPass.record(cmd, slotIndex, slot.color);

  // The depth buffer goes back to where an engine keeps it (attachment, e.g. for a forward pass)
  // once lighting has read it. The back buffer, the shadow maps and the AOVs need no transition;
  // deliberately no extra barrier for them: post-processes order themselves after our writes.
  barriers
      .image(slot.depth.image(), kDepthAspect, kReadLayout, kDepthLayout,
             {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE}, kDepthAttachment)
      .record(cmd);

  // Translucent objects, as an engine draws them after its deferred passes: blended over the lit
  // picture, tested against the depth buffer and left out of it.
  if (geometry.translucentIndexCount > 0) {
    barriers.image(slot.color.image(), kColorAspect, kColorLayout, kColorLayout, kColorWritten, kColorAttachment)
        .record(cmd);
    const Light& light = *lights[0].light;
    gpu::ForwardPush push{};
    push.clipFromWorld = glm::mat4(camera.projection * camera.view);
    push.light = light.type == LightType::Directional ? glm::vec4(glm::vec3(glm::normalize(light.direction)), 0.0f)
                                                      : glm::vec4(glm::vec3(light.position), 1.0f);
    push.radiance = glm::vec4(glm::vec3(light.color * light.intensity), 0.0f);
    push.ambient = glm::vec4(kAmbient, 0.0f);
    forwardPass.record(cmd, geometry, slot.color, slot.depth, push);
  }
}

// The translucent objects peeled from every shadow map, after the shadow passes: the maps are read
// from here on (peels, lighting, effects), and each layer is written, then read by the next peel
// and by effects.
void Renderer::Impl::recordTranslucentLayers(VkCommandBuffer cmd, const FrameSlot& slot) const {
  constexpr VkImageLayout kDepthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  constexpr VkImageLayout kColorLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  constexpr VkImageLayout kReadLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const std::uint32_t layers = settings.translucentLayers + 1;

  vk::Barriers barriers;
  for (const LightTargets& light : slot.lights) {
    for (std::size_t m = 0; m < light.shadowMaps.size(); ++m) {
      barriers.image(light.shadowMaps[m].image(), VK_IMAGE_ASPECT_DEPTH_BIT, kDepthLayout, kReadLayout, kDepthWritten,
                     kFragmentRead);
      barriers.image(light.translucentLayers[m].image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     kColorLayout, kPreviousUse, kColorAttachment, 0, layers);
    }
  }
  barriers.record(cmd);
  for (std::size_t l = 0; l < slot.lights.size(); ++l) {
    const LightTargets& light = slot.lights[l];
    std::uint32_t set = light.firstPeelSet;
    for (std::size_t m = 0; m < light.shadowMaps.size(); ++m) {
      const vk::Image& image = light.translucentLayers[m];
      for (std::uint32_t layer = 0; layer < layers; ++layer) {
        if (layer > 0) {
          barriers.image(image.image(), VK_IMAGE_ASPECT_COLOR_BIT, kColorLayout, kReadLayout, kColorWritten,
                         kFragmentRead, layer - 1);
        }
        barriers.image(light.peelDepth.image(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, kDepthLayout,
                       kDepthAttachment, kDepthAttachment);
        barriers.record(cmd);
        translucentPass.record(cmd, geometry, image, layer, set++, light.peelDepth,
                               glm::mat4(lights[l].shadowViews[m].worldToShadowClip));
      }
      barriers.image(image.image(), VK_IMAGE_ASPECT_COLOR_BIT, kColorLayout, kReadLayout, kColorWritten, kFragmentRead,
                     layers - 1);
    }
  }
  barriers.record(cmd);
}

bool Renderer::Impl::waitSlot(FrameSlot& slot, std::string& error) {
  if (!slot.pending) return true;
  const VkFence fence = slot.fence.get();
  if (!vk::check(vkWaitForFences(gpu.device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences", error))
    return false;
  slot.pending = false;
  return true;
}

bool Renderer::Impl::waitAll(std::string& error) {
  for (FrameSlot& slot : slots) {
    if (!waitSlot(slot, error)) return false;
  }
  return true;
}

bool Renderer::Impl::readImage(const vk::Image& image, VkImageLayout layout, ImageRgba32f& out,
                               std::string& error) {
  if (!waitAll(error)) return false;
  const VkExtent2D extent = image.extent();
  const std::uint32_t texelBytes = bytesPerPixel(image.format());
  const std::size_t pixelCount = static_cast<std::size_t>(extent.width) * extent.height;
  vk::Buffer staging;
  if (!staging.create(gpu, pixelCount * texelBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, error)) {
    return false;
  }
  const bool ok = vk::submitAndWait(gpu, pool.get(), [&](VkCommandBuffer cmd) {
    const VkImageAspectFlags aspect = image.aspect();
    const vk::Barriers::Scope copyRead{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
    vk::Barriers()
        .image(image.image(), aspect, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT}, copyRead)
        .record(cmd);
    VkBufferImageCopy region{};
    region.imageSubresource = {aspect, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer(), 1, &region);
    // Back to the layout the frame left it in, and the copy made visible to the host.
    vk::Barriers()
        .image(image.image(), aspect, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
               {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE},
               {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT})
        .buffer(staging.buffer(), {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT},
                {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT})
        .record(cmd);
  }, error);
  if (!ok) return false;
  out.width = extent.width;
  out.height = extent.height;
  out.pixels.resize(pixelCount * 4);
  decodePixels(image.format(), static_cast<const std::uint8_t*>(staging.mapped()), pixelCount, out.pixels.data());
  return true;
}

// ---------------------------------------------------------------------------------------------
// Renderer
// ---------------------------------------------------------------------------------------------

std::unique_ptr<Renderer> Renderer::create(Device& device, const Scene& scene, const RenderSettings& settings,
                                           std::string& error) {
  auto impl = std::make_unique<Impl>(device);
  if (!impl->init(scene, settings, error)) return nullptr;
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

void Renderer::addPostProcess(PostProcessEffect* effect) {
  if (effect != nullptr) impl_->effects.push_back(effect);
}

bool Renderer::renderFrame(std::string& error) {
  Impl& r = *impl_;
  if (!r.brokenReason.empty()) {
    error = "renderer unusable after a failed resize: " + r.brokenReason;
    return false;
  }
  const auto slotIndex = static_cast<std::uint32_t>(r.frameIndex % r.slots.size());
  FrameSlot& slot = r.slots[slotIndex];
  if (!r.waitSlot(slot, error)) return false;  // the slot's previous frame must be done
  r.writeParams(slot);

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (!vk::check(vkBeginCommandBuffer(slot.cmd, &begin), "vkBeginCommandBuffer", error)) return false;
  r.recordFrame(slot, slotIndex);

  PostProcessInputs inputs;
  inputs.frameIndex = r.frameIndex;
  inputs.frameSlot = slotIndex;
  inputs.view = glm::mat4(r.camera.view);
  inputs.projection = glm::mat4(r.camera.projection);
  inputs.scene = &r.scene;
  auto hostImage = [](const vk::Image& image, VkImageLayout layout, VkImageUsageFlags usage = 0) {
    return HostImage{image.image(), image.view(), image.format(), image.extent(), layout, usage};
  };
  // Light i's shadow maps and colour texture, as effects see them.
  const auto lightImages = [&](std::size_t i, std::vector<HostShadowMap>& maps, HostImage& lightColor) {
    const std::vector<vk::Image>& images = slot.lights[i].shadowMaps;
    for (std::size_t m = 0; m < images.size(); ++m) {
      const detail::ShadowView& view = r.lights[i].shadowViews[m];
      HostShadowMap& map = maps.emplace_back(HostShadowMap{hostImage(images[m], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL),
                                                           glm::mat4(view.worldToShadowClip), view.viewDepthNear,
                                                           view.viewDepthFar});
      if (!slot.lights[i].translucentLayers.empty()) {
        map.translucentLayers = hostImage(slot.lights[i].translucentLayers[m], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        map.translucentLayerCount = r.settings.translucentLayers;
      }
    }
    if (!r.lights[i].light->colorTexture.empty()) {
      lightColor = hostImage(r.lights[i].color, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
  };
  lightImages(0, inputs.shadowMaps, inputs.lightColor);
  for (std::size_t i = 1; i < r.lights.size(); ++i) {
    LightInputs& light = inputs.additionalLights.emplace_back();
    light.light = r.lights[i].light;
    lightImages(i, light.shadowMaps, light.lightColor);
  }
  inputs.depth = hostImage(slot.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
  // Effects choose a compute composite only when the back buffer reports STORAGE usage.
  inputs.color = hostImage(slot.color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, r.colorUsage);
  if (r.settings.aovImages) {
    inputs.aovScattering = hostImage(slot.aovScattering, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    inputs.aovTransmittance = hostImage(slot.aovTransmittance, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    inputs.aovDebug = hostImage(slot.aovDebug, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  }
  for (std::size_t i = 0; i < r.effects.size(); ++i) {
    std::string effectError;
    if (!r.effects[i]->record(slot.cmd, inputs, effectError)) {
      // Abandon the frame: nothing is submitted, the slot's fence and images are untouched.
      vkResetCommandBuffer(slot.cmd, 0);
      error = "post-process effect " + std::to_string(i) + " failed: " + effectError;
      return false;
    }
  }
  if (!vk::check(vkEndCommandBuffer(slot.cmd), "vkEndCommandBuffer", error)) return false;

  const VkFence fence = slot.fence.get();
  if (!vk::check(vkResetFences(r.gpu.device, 1, &fence), "vkResetFences", error)) return false;
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = slot.cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  {
    std::lock_guard<std::mutex> lock(*r.gpu.queueMutex);
    if (!vk::check(vkQueueSubmit2(r.gpu.queue, 1, &submit, fence), "vkQueueSubmit2", error)) return false;
  }
  slot.pending = true;
  r.lastSlot = slotIndex;
  ++r.frameIndex;
  return true;
}

void Renderer::waitIdle() {
  std::string ignored;  // a lost device shows up again on the next call that can report it
  impl_->waitAll(ignored);
}

bool Renderer::resize(std::uint32_t width, std::uint32_t height, std::string& error) {
  Impl& r = *impl_;
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(r.gpu.physicalDevice, &properties);
  const std::uint32_t maxSize = properties.limits.maxImageDimension2D;
  if (width < 1 || height < 1 || width > maxSize || height > maxSize) {
    error = "resize: size must be in [1, " + std::to_string(maxSize) + "] in both directions";
    return false;
  }
  if (!r.waitAll(error)) return false;
  r.settings.width = width;
  r.settings.height = height;
  r.lastSlot.reset();  // the new images hold no frame yet
  // The shadow maps do not depend on the image size and are kept; only the fit changes.
  if (!r.updateViews(error) || !r.createSizeDependent(error)) {
    r.brokenReason = error;
    return false;
  }
  r.brokenReason.clear();
  for (std::size_t i = 0; i < r.effects.size(); ++i) {
    std::string effectError;
    if (!r.effects[i]->resize({width, height}, effectError)) {
      error = "post-process effect " + std::to_string(i) + " failed to resize: " + effectError;
      return false;
    }
  }
  return true;
}

bool Renderer::readBackBuffer(ImageRgba32f& out, std::string& error) {
  if (!impl_->lastSlot) {
    error = "readBackBuffer: no frame has been rendered (since the last resize)";
    return false;
  }
  return impl_->readImage(impl_->slots[*impl_->lastSlot].color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, out,
                          error);
}

bool Renderer::readAovScattering(ImageRgba32f& out, std::string& error) {
  if (!impl_->settings.aovImages || !impl_->lastSlot) {
    error = "readAovScattering: needs RenderSettings::aovImages and a rendered frame";
    return false;
  }
  return impl_->readImage(impl_->slots[*impl_->lastSlot].aovScattering, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, out,
                          error);
}

bool Renderer::readAovTransmittance(ImageRgba32f& out, std::string& error) {
  if (!impl_->settings.aovImages || !impl_->lastSlot) {
    error = "readAovTransmittance: needs RenderSettings::aovImages and a rendered frame";
    return false;
  }
  return impl_->readImage(impl_->slots[*impl_->lastSlot].aovTransmittance, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          out, error);
}

bool Renderer::readAovDebug(ImageRgba32f& out, std::string& error) {
  if (!impl_->settings.aovImages || !impl_->lastSlot) {
    error = "readAovDebug: needs RenderSettings::aovImages and a rendered frame";
    return false;
  }
  return impl_->readImage(impl_->slots[*impl_->lastSlot].aovDebug, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, out, error);
}

const RenderSettings& Renderer::settings() const { return impl_->settings; }
bool Renderer::setCamera(const Camera& camera, std::string& error) {
  Impl& r = *impl_;
  const Camera previous = r.scene.camera;
  r.scene.camera = camera;
  if (!r.updateViews(error)) {
    r.scene.camera = previous;
    std::string unused;
    r.updateViews(unused);  // the previous camera was accepted before
    return false;
  }
  return true;
}

glm::mat4 Renderer::viewMatrix() const { return glm::mat4(impl_->camera.view); }
glm::mat4 Renderer::projectionMatrix() const { return glm::mat4(impl_->camera.projection); }

}  // namespace tyndall::host
