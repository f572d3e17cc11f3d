// libFuzzer target: frame validation (prepareFrame, then the technique selection a valid frame
// gets) on a FrameDesc built from arbitrary bytes. Every frame comes back as an Outcome: a
// failure with a status and a message, or a frame whose images match the output extent. Nothing
// is recorded: the device behind it has format queries and no other entry point, so a command
// recorded during validation would crash.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "frame_setup.h"
#include "technique_selection.h"

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_frame: %s\n", what);
    std::abort();
  }
}

// Reads the input front to back; past its end every value is zero.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return offset_ < size_ ? data_[offset_++] : 0; }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | byte();
    return v;
  }
  template <class Enum>
  Enum pick(std::uint32_t count) {  // the enum's values and one past them
    return static_cast<Enum>(byte() % (count + 1));
  }
  // Floats where validation has its edges, or raw bits.
  float number() {
    static constexpr std::array<float, 14> kEdges = {0.0f,   -0.0f, 1.0f,  -1.0f,    0.5f,  1e-30f, 1e30f,
                                                     1000.f, 0.1f,  60.0f, 1.5708f, 1e-45f, 3.0f,  -1e-7f};
    const std::uint8_t kind = byte();
    if (kind < 200) return kEdges[kind % kEdges.size()];
    if (kind < 220) return INFINITY * (kind % 2 ? 1.0f : -1.0f);
    if (kind < 230) return NAN;
    const std::uint32_t bits = u32();
    float v = 0.0f;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  }
  tyndall::Float3 float3() { return {number(), number(), number()}; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

constexpr std::array<VkFormat, 9> kFormats = {
    VK_FORMAT_UNDEFINED,          VK_FORMAT_D32_SFLOAT,          VK_FORMAT_D16_UNORM,
    VK_FORMAT_D24_UNORM_S8_UINT,  VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT,
    VK_FORMAT_B8G8R8A8_SRGB,      VK_FORMAT_R8G8B8A8_UINT,       VK_FORMAT_A2B10G10R10_UNORM_PACK32};

// lavapipe's answers, roughly: depth formats sample; float and UNORM/SRGB colour formats do
// everything a colour input needs; integer and undefined formats nothing.
VKAPI_ATTR void VKAPI_CALL formatProperties(VkPhysicalDevice, VkFormat format, VkFormatProperties* properties) {
  *properties = {};
  switch (format) {
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D24_UNORM_S8_UINT:
      properties->optimalTilingFeatures = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT;
      break;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
      properties->optimalTilingFeatures =
          VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
          VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
          VK_FORMAT_FEATURE_BLIT_DST_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
      break;
    default:
      break;
  }
}

tyndall::ImageRef image(Bytes& in, VkExtent2D output) {
  tyndall::ImageRef ref;
  const std::uint8_t handles = in.byte();
  ref.image = (handles & 1) != 0 ? reinterpret_cast<VkImage>(std::uintptr_t{0x1000}) : VK_NULL_HANDLE;
  ref.view = (handles & 2) != 0 ? reinterpret_cast<VkImageView>(std::uintptr_t{0x2000}) : VK_NULL_HANDLE;
  ref.format = kFormats[in.byte() % kFormats.size()];
  // Mostly the output's extent, so that frames get past the extent checks.
  const std::uint8_t extent = in.byte();
  ref.extent = extent < 192 ? output : VkExtent2D{in.byte() * 37u % 4099u, in.byte() * 41u % 4099u};
  constexpr std::array<VkImageLayout, 5> kLayouts = {
      VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  ref.layout = kLayouts[in.byte() % kLayouts.size()];
  ref.usage = in.byte() & 1 ? VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT : 0;
  return ref;
}

tyndall::Mat4 matrix(Bytes& in, bool perspective) {
  glm::mat4 m(1.0f);
  switch (in.byte() % 4) {
    case 0:  // raw
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = in.number();
      break;
    case 1:
      m = perspective ? glm::perspectiveRH_ZO(in.number(), in.number(), in.number(), in.number())
                      : glm::lookAtRH(glm::vec3(in.number(), in.number(), in.number()), glm::vec3(0.0f),
                                      glm::vec3(0.0f, 1.0f, 0.0f));
      break;
    case 2:
      m = perspective ? glm::perspectiveRH_ZO(1.0f, 1.5f, 0.1f, 100.0f)
                      : glm::orthoRH_ZO(-10.0f, 10.0f, -10.0f, 10.0f, 0.0f, in.number());
      break;
    default:
      m = perspective ? glm::perspectiveRH_ZO(1.0f, 1.5f, 100.0f, 0.1f)  // reverse-Z
                      : glm::lookAtRH(glm::vec3(0.0f, 5.0f, 5.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
      break;
  }
  tyndall::Mat4 out{};
  std::memcpy(out.data(), glm::value_ptr(m), sizeof(out));
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tyndall;
  Bytes in(data, size);
  Gpu gpu;
  gpu.vk.vkGetPhysicalDeviceFormatProperties = &formatProperties;

  const VkExtent2D output{1u + in.byte() % 64u, 1u + in.byte() % 64u};
  FrameDesc frame;
  frame.camera.view = matrix(in, false);
  frame.camera.projection = matrix(in, true);
  frame.camera.infiniteFarSkyDistance = in.number();
  const auto readLight = [&in]() {
    LightDesc light;
    light.type = in.pick<LightType>(3);
    light.direction = in.float3();
    light.position = in.float3();
    light.color = in.float3();
    light.intensity = in.number();
    light.innerConeRadians = in.number();
    light.outerConeRadians = in.number();
    return light;
  };
  frame.light = readLight();
  std::vector<MediumComponent> medium(in.byte() % (kMaxMediumComponents + 2));
  for (MediumComponent& component : medium) {
    component.scattering = in.float3();
    component.absorption = in.float3();
    component.phase = in.pick<PhaseFunction>(4);
    component.g = in.number();
  }
  frame.medium = medium;
  const VkExtent2D mapSize{256, 256};
  const auto readShadowMaps = [&]() {
    std::vector<ShadowMapDesc> maps(in.byte() % (kMaxShadowMaps + 2));
    for (ShadowMapDesc& map : maps) {
      map.depth = image(in, mapSize);
      map.worldToShadowClip = matrix(in, in.byte() & 1);
    }
    return maps;
  };
  std::vector<ShadowMapDesc> shadowMaps = readShadowMaps();
  frame.shadowMaps = shadowMaps;
  frame.depth = image(in, output);
  frame.color = image(in, output);
  const std::uint8_t optional = in.byte();
  if (optional & 1) frame.scatteringOutput = image(in, output);
  if (optional & 2) frame.transmittanceOutput = image(in, output);
  if (optional & 4) frame.debugOutput = image(in, output);
  if (optional & 8) frame.lightColor = image(in, VkExtent2D{16, 16});
  frame.debugView = in.pick<DebugView>(3);
  frame.profile = in.pick<Profile>(5);
  frame.autoBudgetMilliseconds = in.number();
  frame.technique = in.pick<Technique>(4);
  // Additional lights last, so that inputs written before they existed decode as before (none).
  std::vector<LightInput> additional(in.byte() % (kMaxLights + 1));
  std::vector<std::vector<ShadowMapDesc>> additionalMaps(additional.size());
  for (std::size_t i = 0; i < additional.size(); ++i) {
    additional[i].light = readLight();
    additionalMaps[i] = readShadowMaps();
    additional[i].shadowMaps = additionalMaps[i];
    if (in.byte() & 1) additional[i].lightColor = image(in, VkExtent2D{16, 16});
  }
  frame.additionalLights = additional;
  // Cascade ranges of the first light's maps, last for the same reason.
  if (in.byte() & 1) {
    for (ShadowMapDesc& map : shadowMaps) {
      map.viewDepthNear = in.number();
      map.viewDepthFar = in.number();
    }
  }

  FrameSetup setup;
  const Outcome outcome = prepareFrame(gpu, output, frame, setup);
  if (!outcome) {
    require(outcome.status != Status::Success, "a failure with status Success");
    require(!outcome.message.empty(), "a failure without a message");
    return 0;
  }
  require(frame.depth.extent.width == output.width && frame.depth.extent.height == output.height,
          "a valid frame whose depth buffer is not the output's size");
  require(!frame.medium.empty() && frame.medium.size() <= kMaxMediumComponents, "a valid frame with a bad medium");
  require(!frame.shadowMaps.empty(), "a valid frame without a shadow map");
  const TechniqueSelection selection =
      selectTechnique({frame.technique == Technique::None ? Technique::Epipolar : frame.technique, frame.light.type,
                       !frame.lightColor.empty(), output, setup.scatters,
                       hasCascades(frame.light.type, frame.shadowMaps.size())});
  require(selection.technique != Technique::Prefiltered || frame.light.type == LightType::Directional,
          "the prefiltered technique chosen for a local light");
  require(selection.technique != Technique::Prefiltered || frame.shadowMaps.size() == 1,
          "the prefiltered technique chosen for cascades");
  require(frame.additionalLights.size() < kMaxLights, "a valid frame with more than kMaxLights lights");
  require(setup.lights.size() == 1 + frame.additionalLights.size(), "a light without its setup");
  for (const LightSetup& light : setup.lights) {
    const std::size_t maps = light.shadowMaps.size();
    require(light.light.type == LightType::Point       ? maps == 6u
            : light.light.type == LightType::Directional ? maps >= 1u && maps <= kMaxCascades
                                                         : maps == 1u,
            "a valid light with the wrong number of shadow maps");
    for (std::size_t i = 1; light.light.type == LightType::Directional && i < maps; ++i) {
      require(light.shadowMaps[i].viewDepthNear == light.shadowMaps[i - 1].viewDepthFar &&
                  light.shadowMaps[i].viewDepthFar > light.shadowMaps[i].viewDepthNear,
              "valid cascades that leave a gap, overlap or run backwards");
    }
    require(light.light.intensity > 0.0f || light.skipped == LightSkipped::Off, "a light without intensity not skipped");
  }
  return 0;
}
