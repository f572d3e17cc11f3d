// The stub host on lavapipe under the Khronos validation layer with synchronization validation:
// device, the four passes against an analytic shading of the same scenes, the frame loop and the
// post-process contract, resize, back-buffer formats, display transform and image files.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <OpenColorIO/OpenColorIO.h>

#include "tyndall_host/renderer.h"
#include "tyndall_host/scene.h"
#include "test_support.h"

// stb_image reads the PNGs back; static so that no other translation unit can clash with it.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace {

using namespace tyndall::host;

// ---------------------------------------------------------------------------------------------
// Scenes built in code, and their analytic shading
// ---------------------------------------------------------------------------------------------

constexpr double kGroundAlbedo = 0.5;

Object groundPlane() {
  Object plane;
  plane.type = ObjectType::Plane;
  plane.point = {0.0, 0.0, 0.0};
  plane.normal = {0.0, 1.0, 0.0};
  plane.albedo = glm::dvec3(kGroundAlbedo);
  return plane;
}

Object box(const glm::dvec3& center, const glm::dvec3& halfExtents) {
  Object object;
  object.type = ObjectType::Box;
  object.center = center;
  object.halfExtents = halfExtents;
  object.albedo = glm::dvec3(0.8);
  return object;
}

Object sphere(const glm::dvec3& center, double radius) {
  Object object;
  object.type = ObjectType::Sphere;
  object.center = center;
  object.radius = radius;
  object.albedo = glm::dvec3(0.7);
  return object;
}

// Ground, a box standing on it and a sphere; the camera looks down steeply enough that every
// pixel sees the ground within the far plane (so finite and infinite far draw the same image).
Scene directionalScene() {
  Scene scene;
  scene.camera.position = {0.0, 8.0, 8.0};
  scene.camera.target = {0.0, 0.0, 0.0};
  scene.camera.up = {0.0, 1.0, 0.0};
  scene.camera.fovYDegrees = 60.0;
  scene.camera.nearPlane = 0.1;
  scene.camera.farPlane = 50.0;
  scene.light.type = LightType::Directional;
  scene.light.direction = glm::normalize(glm::dvec3(1.0, -1.2, 0.4));
  scene.light.color = {1.0, 1.0, 1.0};
  scene.light.intensity = 2.0;
  scene.objects = {groundPlane(), box({0.0, 1.0, 0.0}, {1.0, 1.0, 1.0}), sphere({-3.0, 1.0, -1.5}, 1.0)};
  scene.shadowMapSize = 512;
  return scene;
}

// A spot light above the ground with a floating box beside its axis and a sphere in its cone.
Scene spotScene() {
  Scene scene;
  scene.camera.position = {0.0, 8.0, 10.0};
  scene.camera.target = {0.0, 0.0, 0.0};
  scene.camera.farPlane = 100.0;
  scene.light.type = LightType::Spot;
  scene.light.position = {0.0, 6.0, 0.0};
  scene.light.direction = {0.0, -1.0, 0.0};
  scene.light.color = {1.0, 1.0, 1.0};
  scene.light.intensity = 60.0;
  scene.light.innerConeDegrees = 30.0;
  scene.light.outerConeDegrees = 35.0;
  scene.objects = {groundPlane(), box({1.5, 1.5, 0.0}, {0.5, 0.5, 0.5}), sphere({-1.0, 0.8, 1.5}, 0.5)};
  scene.shadowMapSize = 512;
  return scene;
}

// A point light with one occluder shadowing the ground through the −Y cube face and one through −X.
Scene pointScene() {
  Scene scene;
  scene.camera.position = {0.0, 8.0, 10.0};
  scene.camera.target = {0.0, 0.0, 0.0};
  scene.camera.farPlane = 100.0;
  scene.light.type = LightType::Point;
  scene.light.position = {0.0, 4.0, 0.0};
  scene.light.color = {1.0, 1.0, 1.0};
  scene.light.intensity = 40.0;
  scene.objects = {groundPlane(), box({1.2, 2.0, 0.0}, {0.4, 0.4, 0.4}), box({-4.0, 1.0, 0.0}, {0.5, 0.5, 0.5})};
  scene.shadowMapSize = 512;
  return scene;
}

// Ray–object tests for the analytic classification; `grow` inflates (> 0) or deflates (< 0) the
// object. Hits count for t in (1e-6, tMax).
bool rayHitsObject(const Object& object, const glm::dvec3& o, const glm::dvec3& d, double grow, double tMax) {
  if (object.type == ObjectType::Box) {
    double t0 = 1e-6;
    double t1 = tMax;
    for (int a = 0; a < 3; ++a) {
      const double lo = object.center[a] - object.halfExtents[a] - grow;
      const double hi = object.center[a] + object.halfExtents[a] + grow;
      if (std::abs(d[a]) < 1e-12) {
        if (o[a] < lo || o[a] > hi) return false;
        continue;
      }
      double ta = (lo - o[a]) / d[a];
      double tb = (hi - o[a]) / d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 <= t1;
  }
  if (object.type == ObjectType::Sphere) {
    const double r = object.radius + grow;
    const glm::dvec3 oc = o - object.center;
    const double a = glm::dot(d, d);
    const double b = glm::dot(oc, d);
    const double c = glm::dot(oc, oc) - r * r;
    const double disc = b * b - a * c;
    if (disc < 0.0) return false;
    const double s = std::sqrt(disc);
    const double ta = (-b - s) / a;
    const double tb = (-b + s) / a;
    return (ta > 1e-6 && ta < tMax) || (tb > 1e-6 && tb < tMax) || (ta <= 1e-6 && tb >= tMax);
  }
  return false;  // the ground plane itself is handled by the caller
}

// The ray of pixel (px, py) exactly as renderer.h defines it.
glm::dvec3 pixelRay(const Camera& camera, std::uint32_t width, std::uint32_t height, std::uint32_t px,
                    std::uint32_t py) {
  const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const double t = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
  const double aspect = static_cast<double>(width) / height;
  return forward + right * ((2.0 * (px + 0.5) / width - 1.0) * t * aspect) +
         up * ((1.0 - 2.0 * (py + 0.5) / height) * t);
}

struct GroundCheck {
  int lit = 0;       // pixels surely lit, compared with the analytic value
  int shadowed = 0;  // pixels surely in shadow
  int failures = 0;
  std::string firstFailure;
};

// Classifies every ground pixel whose classification is robust (camera and light rays clear of
// object silhouettes by `margin`) and compares it with albedo · E · cos θ (lit) or ~ambient
// (shadowed). Tolerance: 5% + 0.03 absolute (the host's small ambient term is below 0.03).
GroundCheck checkGround(const Scene& scene, const ImageRgba32f& image, double margin = 0.1) {
  GroundCheck check;
  const Light& light = scene.light;
  for (std::uint32_t py = 0; py < image.height; ++py) {
    for (std::uint32_t px = 0; px < image.width; ++px) {
      const glm::dvec3 o = scene.camera.position;
      const glm::dvec3 d = pixelRay(scene.camera, image.width, image.height, px, py);
      if (d.y >= 0.0) continue;
      const double tGround = -o.y / d.y;
      bool nearObject = false;
      for (const Object& object : scene.objects) nearObject |= rayHitsObject(object, o, d, margin, tGround);
      if (nearObject) continue;
      const glm::dvec3 p = o + tGround * d;

      glm::dvec3 toLight;
      double tMax = 0.0;
      double irradiance = light.intensity;
      if (light.type == LightType::Directional) {
        toLight = -glm::normalize(light.direction) * 1e3;
        tMax = 1.0;
      } else {
        toLight = light.position - p;
        tMax = 1.0;
        const double distance = glm::length(toLight);
        irradiance /= distance * distance;
        if (light.type == LightType::Spot) {
          const double cosAngle = glm::dot(glm::normalize(light.direction), -toLight / distance);
          const double e0 = std::cos(glm::radians(light.outerConeDegrees));
          const double e1 = std::cos(glm::radians(light.innerConeDegrees));
          const double x = std::clamp((cosAngle - e0) / (e1 - e0), 0.0, 1.0);
          irradiance *= x * x * (3.0 - 2.0 * x);
        }
      }
      const double cosTheta = std::max(0.0, glm::normalize(toLight).y);
      bool surelyShadowed = false;
      bool maybeShadowed = false;
      for (const Object& object : scene.objects) {
        surelyShadowed |= rayHitsObject(object, p, toLight, -margin, tMax);
        maybeShadowed |= rayHitsObject(object, p, toLight, margin, tMax);
      }
      const float* rgba = &image.pixels[(static_cast<std::size_t>(py) * image.width + px) * 4];
      double expected = 0.0;
      if (surelyShadowed) {
        ++check.shadowed;
      } else if (!maybeShadowed) {
        ++check.lit;
        expected = kGroundAlbedo * irradiance * cosTheta;
      } else {
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        if (std::abs(rgba[c] - expected) > 0.05 * expected + 0.03) {
          if (check.failures++ == 0) {
            std::ostringstream s;
            s << "pixel (" << px << ", " << py << ") channel " << c << ": " << rgba[c] << ", expected "
              << expected << (surelyShadowed ? " (shadowed)" : " (lit)");
            check.firstFailure = s.str();
          }
        }
      }
    }
  }
  return check;
}

// The top face of an axis-aligned box under a directional light: pixels whose ray hits it well
// inside its edges must show albedo · E · n·l. Catches a wrong winding/culling in the G-buffer,
// which would show the inside of the box instead.
int checkBoxTop(const Scene& scene, const Object& box, const ImageRgba32f& image, std::string& failure) {
  int checked = 0;
  const double top = box.center.y + box.halfExtents.y;
  const double expected = box.albedo.x * scene.light.intensity * std::max(0.0, -glm::normalize(scene.light.direction).y);
  for (std::uint32_t py = 0; py < image.height; ++py) {
    for (std::uint32_t px = 0; px < image.width; ++px) {
      const glm::dvec3 o = scene.camera.position;
      const glm::dvec3 d = pixelRay(scene.camera, image.width, image.height, px, py);
      if (d.y >= 0.0) continue;
      const glm::dvec3 p = o + (top - o.y) / d.y * d;
      const double margin = 0.15;
      if (std::abs(p.x - box.center.x) > box.halfExtents.x - margin ||
          std::abs(p.z - box.center.z) > box.halfExtents.z - margin) {
        continue;
      }
      ++checked;
      const float* rgba = &image.pixels[(static_cast<std::size_t>(py) * image.width + px) * 4];
      if (std::abs(rgba[1] - expected) > 0.05 * expected + 0.03 && failure.empty()) {
        failure = "box top pixel (" + std::to_string(px) + ", " + std::to_string(py) + "): " +
                  std::to_string(rgba[1]) + ", expected " + std::to_string(expected);
      }
    }
  }
  return checked;
}

// ---------------------------------------------------------------------------------------------
// Fixture: one validated device for the suite
// ---------------------------------------------------------------------------------------------

class HostStub : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // Lavapipe unless the caller picked another device (the environment is restored after).
    const bool chosen = std::getenv("TYNDALL_DEVICE") != nullptr;
    requestedDevice_ = chosen ? std::getenv("TYNDALL_DEVICE") : "llvmpipe";
    if (!chosen) setenv("TYNDALL_DEVICE", "llvmpipe", 1);
    std::string error;
    device_ = Device::create(DeviceOptions{true, true}, error).release();
    deviceError_ = error;
    if (!chosen) unsetenv("TYNDALL_DEVICE");
  }
  static void TearDownTestSuite() {
    delete device_;
    device_ = nullptr;
  }
  void SetUp() override {
    ASSERT_NE(device_, nullptr) << deviceError_;
    device_->clearValidationMessages();
  }
  void TearDown() override {
    if (device_ != nullptr && expectNoValidation_) expectNoValidationMessages();
  }
  static void expectNoValidationMessages() {
    const std::vector<std::string>& messages = device_->validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: " << messages.front();
    device_->clearValidationMessages();
  }

  static RenderSettings smallSettings() {
    RenderSettings settings;
    settings.width = 64;
    settings.height = 36;
    settings.framesInFlight = 2;
    return settings;
  }

  // Renders `frames` frames and reads the back buffer of the last one.
  static ImageRgba32f render(const Scene& scene, const RenderSettings& settings, int frames = 3,
                             const std::vector<PostProcessEffect*>& effects = {}) {
    std::string error;
    std::unique_ptr<Renderer> renderer = Renderer::create(*device_, scene, settings, error);
    ImageRgba32f image;
    EXPECT_NE(renderer, nullptr) << error;
    if (!renderer) return image;
    for (PostProcessEffect* effect : effects) renderer->addPostProcess(effect);
    for (int i = 0; i < frames; ++i) EXPECT_TRUE(renderer->renderFrame(error)) << error;
    renderer->waitIdle();
    EXPECT_TRUE(renderer->readBackBuffer(image, error)) << error;
    return image;
  }

  static Device* device_;
  static std::string deviceError_;
  static std::string requestedDevice_;
  bool expectNoValidation_ = true;
};

Device* HostStub::device_ = nullptr;
std::string HostStub::deviceError_;
std::string HostStub::requestedDevice_;

bool allFinite(const ImageRgba32f& image) {
  return std::all_of(image.pixels.begin(), image.pixels.end(), [](float v) { return std::isfinite(v); });
}

float maxRgb(const ImageRgba32f& image) {
  float m = 0.0f;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (i % 4 != 3) m = std::max(m, image.pixels[i]);
  }
  return m;
}

// ---------------------------------------------------------------------------------------------
// Device
// ---------------------------------------------------------------------------------------------

TEST_F(HostStub, DeviceIsVulkan13WithOneGraphicsComputeQueue) {
  EXPECT_NE(device_->instance(), VK_NULL_HANDLE);
  EXPECT_NE(device_->device(), VK_NULL_HANDLE);
  EXPECT_NE(device_->queue(), VK_NULL_HANDLE);
  EXPECT_NE(device_->getInstanceProcAddr(), nullptr);
  EXPECT_NE(device_->getDeviceProcAddr(), nullptr);
  EXPECT_NE(device_->name().find(requestedDevice_), std::string::npos) << device_->name();

  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device_->physicalDevice(), &properties);
  EXPECT_GE(properties.apiVersion, VK_API_VERSION_1_3);
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device_->physicalDevice(), &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device_->physicalDevice(), &count, families.data());
  ASSERT_LT(device_->queueFamily(), count);
  const VkQueueFlags flags = families[device_->queueFamily()].queueFlags;
  EXPECT_TRUE((flags & VK_QUEUE_GRAPHICS_BIT) && (flags & VK_QUEUE_COMPUTE_BIT));
  // The device-level entry points resolve through the handed-out getDeviceProcAddr.
  EXPECT_NE(device_->getDeviceProcAddr()(device_->device(), "vkCmdBeginRendering"), nullptr);
  EXPECT_NE(device_->getDeviceProcAddr()(device_->device(), "vkCmdPipelineBarrier2"), nullptr);
}

// Zero messages only means something if messages are recorded: provoke one core-validation error
// and one synchronization hazard.
TEST_F(HostStub, ValidationMessagesAreRecorded) {
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.anisotropyEnable = VK_TRUE;  // samplerAnisotropy is not enabled on this device
  info.maxAnisotropy = 4.0f;
  VkSampler sampler = VK_NULL_HANDLE;
  vkCreateSampler(device_->device(), &info, nullptr, &sampler);
  if (sampler != VK_NULL_HANDLE) vkDestroySampler(device_->device(), sampler, nullptr);
  ASSERT_FALSE(device_->validationMessages().empty());
  EXPECT_NE(device_->validationMessages().front().find("[ERROR]"), std::string::npos);
  EXPECT_EQ(device_->validationMessages().front().find('\n'), std::string::npos);
  device_->clearValidationMessages();
  EXPECT_TRUE(device_->validationMessages().empty());

  // An effect that writes an AOV without ordering itself after the host's clear of it.
  struct CarelessEffect : PostProcessEffect {
    bool record(VkCommandBuffer cmd, const PostProcessInputs& inputs, std::string&) override {
      const VkClearColorValue red{{1.0f, 0.0f, 0.0f, 1.0f}};
      const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, inputs.aovScattering.image, inputs.aovScattering.layout, &red, 1, &range);
      return true;
    }
    bool resize(VkExtent2D, std::string&) override { return true; }
  } careless;
  RenderSettings settings = smallSettings();
  settings.aovImages = true;
  render(directionalScene(), settings, 1, {&careless});
  bool hazard = false;
  for (const std::string& message : device_->validationMessages()) {
    hazard |= message.find("SYNC-HAZARD-WRITE-AFTER-WRITE") != std::string::npos;
  }
  EXPECT_TRUE(hazard) << "synchronization validation did not report the write-after-write hazard";
  device_->clearValidationMessages();
}

TEST_F(HostStub, DeviceOverrideNamesTheAvailableDevices) {
  const char* previousValue = std::getenv("TYNDALL_DEVICE");
  const std::string previous = previousValue != nullptr ? previousValue : "";
  const bool wasSet = previousValue != nullptr;
  setenv("TYNDALL_DEVICE", "no-such-gpu-xyz", 1);
  std::string error;
  std::unique_ptr<Device> device = Device::create(DeviceOptions{false, true}, error);
  if (wasSet) {
    setenv("TYNDALL_DEVICE", previous.c_str(), 1);
  } else {
    unsetenv("TYNDALL_DEVICE");
  }
  EXPECT_EQ(device, nullptr);
  EXPECT_NE(error.find("no-such-gpu-xyz"), std::string::npos) << error;
  EXPECT_NE(error.find("llvmpipe"), std::string::npos) << error;
}

// ---------------------------------------------------------------------------------------------
// Passes against the analytic shading
// ---------------------------------------------------------------------------------------------

TEST_F(HostStub, DirectionalLightMatchesAnalyticShadingAndShadows) {
  const Scene scene = directionalScene();
  const ImageRgba32f image = render(scene, smallSettings());
  ASSERT_EQ(image.width, 64u);
  ASSERT_EQ(image.height, 36u);
  EXPECT_TRUE(allFinite(image));
  EXPECT_GT(maxRgb(image), 0.1f);
  const GroundCheck check = checkGround(scene, image);
  EXPECT_GE(check.lit, 300);
  EXPECT_GE(check.shadowed, 20);
  EXPECT_EQ(check.failures, 0) << check.firstFailure;
  std::string failure;
  EXPECT_GE(checkBoxTop(scene, scene.objects[1], image, failure), 10);
  EXPECT_TRUE(failure.empty()) << failure;
}

TEST_F(HostStub, SpotLightMatchesAnalyticShadingConeAndShadows) {
  const Scene scene = spotScene();
  const ImageRgba32f image = render(scene, smallSettings());
  EXPECT_TRUE(allFinite(image));
  EXPECT_GT(maxRgb(image), 0.1f);
  const GroundCheck check = checkGround(scene, image);
  EXPECT_GE(check.lit, 300);
  EXPECT_GE(check.shadowed, 10);
  EXPECT_EQ(check.failures, 0) << check.firstFailure;
}

TEST_F(HostStub, PointLightMatchesAnalyticShadingThroughSeveralCubeFaces) {
  const Scene scene = pointScene();
  const ImageRgba32f image = render(scene, smallSettings());
  EXPECT_TRUE(allFinite(image));
  EXPECT_GT(maxRgb(image), 0.1f);
  const GroundCheck check = checkGround(scene, image);
  EXPECT_GE(check.lit, 300);
  EXPECT_GE(check.shadowed, 10);
  EXPECT_EQ(check.failures, 0) << check.firstFailure;
}

TEST_F(HostStub, DepthConventionsProduceTheSameImage) {
  const Scene scene = directionalScene();
  const ImageRgba32f reference = render(scene, smallSettings());
  for (DepthConvention depth : {DepthConvention::Standard, DepthConvention::Reverse}) {
    for (bool infinite : {false, true}) {
      if (depth == DepthConvention::Standard && !infinite) continue;
      RenderSettings settings = smallSettings();
      settings.depth = depth;
      settings.infiniteFar = infinite;
      const ImageRgba32f image = render(scene, settings);
      ASSERT_EQ(image.pixels.size(), reference.pixels.size());
      double maxError = 0.0;
      for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        maxError = std::max(maxError, std::abs(static_cast<double>(image.pixels[i]) - reference.pixels[i]) /
                                          (1.0 + std::abs(reference.pixels[i])));
      }
      EXPECT_LT(maxError, 0.01) << (depth == DepthConvention::Reverse ? "reverse" : "standard")
                                << (infinite ? ", infinite far" : ", finite far");
    }
  }
}

TEST_F(HostStub, SkyPixelsKeepTheSkyColourInEveryConvention) {
  Scene scene = directionalScene();
  scene.camera.position = {0.0, 1.0, 8.0};
  scene.camera.target = {0.0, 1.0, 0.0};  // horizontal: the upper half is sky
  for (DepthConvention depth : {DepthConvention::Standard, DepthConvention::Reverse}) {
    for (bool infinite : {false, true}) {
      RenderSettings settings = smallSettings();
      settings.depth = depth;
      settings.infiniteFar = infinite;
      const ImageRgba32f image = render(scene, settings, 1);
      ASSERT_EQ(image.height, 36u);
      const float* first = &image.pixels[0];
      for (std::uint32_t i = 0; i < image.width * 4; ++i) {  // the whole top row
        EXPECT_EQ(image.pixels[i], first[i % 4]);
      }
      EXPECT_LT(std::max({first[0], first[1], first[2]}), 0.1f);
      EXPECT_GT(first[2], 0.0f);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Frame loop and the post-process contract
// ---------------------------------------------------------------------------------------------

// Records what it is handed, checks the documented layouts, and writes both the back buffer and
// the scattering AOV with proper barriers (clears stand in for real work).
struct ProbeEffect : PostProcessEffect {
  std::vector<PostProcessInputs> seen;
  std::vector<VkExtent2D> resizes;
  bool failNext = false;
  bool writeOutputs = true;

  bool record(VkCommandBuffer cmd, const PostProcessInputs& inputs, std::string& error) override {
    if (failNext) {
      failNext = false;
      error = "probe refused the frame";
      return false;
    }
    seen.push_back(inputs);
    if (!writeOutputs) return true;
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageMemoryBarrier2 barriers[2]{};
    for (VkImageMemoryBarrier2& b : barriers) {
      b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
      b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b.subresourceRange = range;
      b.dstStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT;
      b.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    }
    barriers[0].image = inputs.color.image;
    barriers[0].srcStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    barriers[0].srcAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    barriers[0].oldLayout = inputs.color.layout;
    barriers[0].newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barriers[1].image = inputs.aovScattering.image;
    barriers[1].srcStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT;
    barriers[1].srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barriers[1].oldLayout = barriers[1].newLayout = inputs.aovScattering.layout;
    VkDependencyInfo dependency{};
    dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
    dependency.imageMemoryBarrierCount = 2;
    dependency.pImageMemoryBarriers = barriers;
    vkCmdPipelineBarrier2(cmd, &dependency);

    const VkClearColorValue color{{0.25f, 0.5f, 0.75f, 1.0f}};
    const VkClearColorValue scattering{{0.125f, 2.0f, 3.5f, 1.0f}};
    vkCmdClearColorImage(cmd, inputs.color.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &color, 1, &range);
    vkCmdClearColorImage(cmd, inputs.aovScattering.image, inputs.aovScattering.layout, &scattering, 1, &range);

    // Back buffer returned in the layout it came in.
    VkImageMemoryBarrier2 back = barriers[0];
    back.srcStageMask = VK_PIPELINE_STAGE_2_CLEAR_BIT;
    back.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    back.dstStageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    back.dstAccessMask = VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    back.newLayout = inputs.color.layout;
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &back;
    vkCmdPipelineBarrier2(cmd, &dependency);
    return true;
  }
  bool resize(VkExtent2D extent, std::string&) override {
    resizes.push_back(extent);
    return true;
  }
};

TEST_F(HostStub, EffectsReceiveTheDocumentedInputsPerFrameSlot) {
  const Scene scene = pointScene();
  RenderSettings settings = smallSettings();
  settings.aovImages = true;
  ProbeEffect probe;
  std::string error;
  std::unique_ptr<Renderer> renderer = Renderer::create(*device_, scene, settings, error);
  ASSERT_NE(renderer, nullptr) << error;
  renderer->addPostProcess(&probe);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();

  ASSERT_EQ(probe.seen.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const PostProcessInputs& in = probe.seen[i];
    EXPECT_EQ(in.frameIndex, i);
    EXPECT_EQ(in.frameSlot, i % 2);
    EXPECT_NE(in.scene, nullptr);
    EXPECT_EQ(in.view, renderer->viewMatrix());
    EXPECT_EQ(in.projection, renderer->projectionMatrix());
    EXPECT_EQ(in.depth.format, VK_FORMAT_D32_SFLOAT);
    EXPECT_EQ(in.depth.layout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(in.color.format, VK_FORMAT_R16G16B16A16_SFLOAT);
    EXPECT_EQ(in.color.layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(in.color.extent.width, 64u);
    EXPECT_EQ(in.color.extent.height, 36u);
    EXPECT_EQ(in.aovScattering.format, VK_FORMAT_R32G32B32A32_SFLOAT);
    EXPECT_EQ(in.aovScattering.layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    EXPECT_EQ(in.aovTransmittance.layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    ASSERT_EQ(in.shadowMaps.size(), 6u);  // point light: six cube faces
    for (const HostShadowMap& map : in.shadowMaps) {
      EXPECT_EQ(map.depth.format, VK_FORMAT_D32_SFLOAT);
      EXPECT_EQ(map.depth.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      EXPECT_EQ(map.depth.extent.width, 512u);
      EXPECT_NE(map.depth.view, VK_NULL_HANDLE);
    }
  }
  // Like a swapchain: consecutive frames get different images, frames two apart the same ones.
  EXPECT_NE(probe.seen[0].color.image, probe.seen[1].color.image);
  EXPECT_NE(probe.seen[0].depth.image, probe.seen[1].depth.image);
  EXPECT_NE(probe.seen[0].shadowMaps[0].depth.image, probe.seen[1].shadowMaps[0].depth.image);
  EXPECT_EQ(probe.seen[0].color.image, probe.seen[2].color.image);

  // What the effect wrote is what the readbacks return; the untouched AOV holds the host's clear.
  ImageRgba32f color;
  ImageRgba32f scattering;
  ImageRgba32f transmittance;
  ASSERT_TRUE(renderer->readBackBuffer(color, error)) << error;
  ASSERT_TRUE(renderer->readAovScattering(scattering, error)) << error;
  ASSERT_TRUE(renderer->readAovTransmittance(transmittance, error)) << error;
  const float expectedColor[4] = {0.25f, 0.5f, 0.75f, 1.0f};
  const float expectedScattering[4] = {0.125f, 2.0f, 3.5f, 1.0f};
  for (std::size_t i = 0; i < color.pixels.size(); ++i) {
    ASSERT_EQ(color.pixels[i], expectedColor[i % 4]) << i;
    ASSERT_EQ(scattering.pixels[i], expectedScattering[i % 4]) << i;
    ASSERT_EQ(transmittance.pixels[i], 1.0f) << i;
  }
}

// The back buffer reports its usage; STORAGE is there exactly when the setting asks for it and the
// format supports storage images (an _SRGB format usually does not), so effects can pick compute.
TEST_F(HostStub, BackBufferUsageFollowsTheStorageSetting) {
  const Scene scene = pointScene();
  for (const VkFormat format : {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_SRGB}) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(device_->physicalDevice(), format, &properties);
    const bool storageFormat = (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0;
    for (const bool storage : {true, false}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(format)) + (storage ? " storage" : " no storage"));
      RenderSettings settings = smallSettings();
      settings.backBufferFormat = format;
      settings.storageBackBuffer = storage;
      ProbeEffect probe;
      probe.writeOutputs = false;
      render(scene, settings, 1, {&probe});
      ASSERT_EQ(probe.seen.size(), 1u);
      const VkImageUsageFlags usage = probe.seen[0].color.usage;
      EXPECT_NE(usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0u);
      EXPECT_EQ((usage & VK_IMAGE_USAGE_STORAGE_BIT) != 0, storage && storageFormat);
    }
  }
}

TEST_F(HostStub, ShadowMatricesFollowTheDocumentedConventions) {
  ProbeEffect probe;
  probe.writeOutputs = false;
  auto project = [](const glm::mat4& m, const glm::dvec3& p) {
    const glm::vec4 c = m * glm::vec4(glm::vec3(p), 1.0f);
    return glm::dvec4(c.x / c.w, c.y / c.w, c.z / c.w, c.w);
  };

  // Directional: every caster inside the map and its depth range, and the map fitted to them.
  const Scene directional = directionalScene();
  render(directional, smallSettings(), 1, {&probe});
  ASSERT_EQ(probe.seen.size(), 1u);
  ASSERT_EQ(probe.seen[0].shadowMaps.size(), 1u);
  const glm::mat4 m = probe.seen[0].shadowMaps[0].worldToShadowClip;
  glm::dvec3 lo(1e9);
  glm::dvec3 hi(-1e9);
  for (const Object& object : directional.objects) {
    if (object.type == ObjectType::Plane) continue;
    // Points on the surface: box corners; on spheres, the 26 directions of a 3×3×3 grid.
    for (int i = 0; i < 27; ++i) {
      const glm::dvec3 s(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1);
      if (i == 13 || (object.type == ObjectType::Box && (s.x == 0 || s.y == 0 || s.z == 0))) continue;
      const glm::dvec3 p = object.type == ObjectType::Box ? object.center + s * object.halfExtents
                                                          : object.center + glm::normalize(s) * object.radius;
      const glm::dvec4 c = project(m, p);
      lo = glm::min(lo, glm::dvec3(c));
      hi = glm::max(hi, glm::dvec3(c));
    }
  }
  EXPECT_GE(lo.x, -1.0);
  EXPECT_GE(lo.y, -1.0);
  EXPECT_LE(hi.x, 1.0);
  EXPECT_LE(hi.y, 1.0);
  EXPECT_GE(lo.z, 0.0);
  EXPECT_LE(hi.z, 1.0);
  EXPECT_GT(std::max(hi.x - lo.x, hi.y - lo.y), 1.8) << "map not fitted to the casters";
  // Depth 0 nearest the light: moving against the light direction lowers the depth.
  const glm::dvec3 probePoint(0.0, 1.0, 0.0);
  EXPECT_LT(project(m, probePoint - directional.light.direction).z, project(m, probePoint).z);

  // Spot: the axis maps to the centre, depth grows with distance, the cone fits inside.
  const Scene spot = spotScene();
  probe.seen.clear();
  render(spot, smallSettings(), 1, {&probe});
  ASSERT_EQ(probe.seen.size(), 1u);
  ASSERT_EQ(probe.seen[0].shadowMaps.size(), 1u);
  const glm::mat4 s = probe.seen[0].shadowMaps[0].worldToShadowClip;
  const glm::dvec4 onAxis = project(s, spot.light.position + spot.light.direction * 3.0);
  EXPECT_NEAR(onAxis.x, 0.0, 1e-5);
  EXPECT_NEAR(onAxis.y, 0.0, 1e-5);
  EXPECT_GT(onAxis.z, 0.0);
  EXPECT_LT(onAxis.z, project(s, spot.light.position + spot.light.direction * 5.0).z);
  const double outer = glm::radians(spot.light.outerConeDegrees);
  const glm::dvec4 coneEdge =
      project(s, spot.light.position + 5.0 * glm::dvec3(std::sin(outer), -std::cos(outer), 0.0));
  EXPECT_LT(std::abs(coneEdge.x) + std::abs(coneEdge.y), 1.0);
  const glm::dvec4 ground = project(s, glm::dvec3(0.0, 0.0, 0.0));
  EXPECT_GT(ground.z, 0.0);
  EXPECT_LT(ground.z, 1.0);

  // Point: six faces +X −X +Y −Y +Z −Z, each centred on its axis.
  const Scene point = pointScene();
  probe.seen.clear();
  render(point, smallSettings(), 1, {&probe});
  ASSERT_EQ(probe.seen.size(), 1u);
  ASSERT_EQ(probe.seen[0].shadowMaps.size(), 6u);
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int face = 0; face < 6; ++face) {
    const glm::dvec4 c = project(probe.seen[0].shadowMaps[static_cast<std::size_t>(face)].worldToShadowClip,
                                 point.light.position + axes[face] * 2.0);
    EXPECT_GT(c.w, 0.0) << face;
    EXPECT_NEAR(c.x, 0.0, 1e-5) << face;
    EXPECT_NEAR(c.y, 0.0, 1e-5) << face;
    EXPECT_GT(c.z, 0.0) << face;
    EXPECT_LT(c.z, 1.0) << face;
  }
}

// The map holds, at the texel the matrix maps a point to, the depth of the surface nearest the
// light: along a light ray through a box, its entry point, not its exit point.
TEST_F(HostStub, ShadowMapHoldsTheNearestSurfaceAtTheDocumentedTexel) {
  struct Case {
    Scene scene;
    std::size_t map;
    glm::dvec3 boxCenter;
  };
  const Case cases[] = {{directionalScene(), 0, {0.0, 1.0, 0.0}},
                        {spotScene(), 0, {1.5, 1.5, 0.0}},
                        {pointScene(), 3, {1.2, 2.0, 0.0}}};  // −Y face
  for (const Case& c : cases) {
    SCOPED_TRACE(static_cast<int>(c.scene.light.type));
    tyndall::test::ShadowMapCopy copy(*device_, c.map);
    render(c.scene, smallSettings(), 1, {&copy});
    ASSERT_TRUE(copy.copied());

    const Object* target = nullptr;
    for (const Object& object : c.scene.objects) {
      if (object.type == ObjectType::Box && object.center == c.boxCenter) target = &object;
    }
    ASSERT_NE(target, nullptr);
    // The light ray through the box centre, and where it enters and leaves the box.
    const glm::dvec3 direction = c.scene.light.type == LightType::Directional
                                     ? glm::normalize(c.scene.light.direction)
                                     : glm::normalize(c.boxCenter - c.scene.light.position);
    double t0 = -1e9;
    double t1 = 1e9;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(direction[a]) < 1e-12) continue;
      double ta = (target->center[a] - target->halfExtents[a] - c.boxCenter[a]) / direction[a];
      double tb = (target->center[a] + target->halfExtents[a] - c.boxCenter[a]) / direction[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    glm::dvec3 entry;
    glm::dvec3 exit;
    float storedAtCentre = 0.0f;
    float storedAtEntry = 0.0f;
    copy.lookup(c.boxCenter + t0 * direction, entry, storedAtEntry);
    copy.lookup(c.boxCenter + t1 * direction, exit, storedAtCentre);
    ASSERT_LT(std::abs(entry.x), 1.0);
    ASSERT_LT(std::abs(entry.y), 1.0);
    EXPECT_LT(entry.z, exit.z);
    EXPECT_NEAR(storedAtEntry, entry.z, 0.1 * (exit.z - entry.z));
    // Ground between the objects: the plane is in the map too.
    glm::dvec3 ground;
    float storedAtGround = 0.0f;
    const glm::dvec3 groundPoint = c.scene.light.type == LightType::Directional ? glm::dvec3(-3.0, 0.0, 3.0)
                                                                                : glm::dvec3(-1.5, 0.0, -1.5);
    copy.lookup(groundPoint, ground, storedAtGround);
    EXPECT_NEAR(storedAtGround, ground.z, 1e-3 + 0.02 * ground.z);
  }
}

// ---------------------------------------------------------------------------------------------
// Cascaded shadow maps (a directional light's "shadowMap": {"cascades": K})
// ---------------------------------------------------------------------------------------------

// samples/scenes/colonnade.json: a 300 m avenue seen from eye height, far plane 400 m, 4 cascades.
Scene colonnadeScene() {
  const SceneLoadResult loaded = loadScene(std::filesystem::path(TYNDALL_SCENES_DIR) / "colonnade.json");
  EXPECT_TRUE(loaded.scene.has_value()) << loaded.error;
  return loaded.scene.value_or(Scene{});
}

// The corners of the view frustum's cross-section at view depth `depth` (pixelRay's basis).
std::vector<glm::dvec3> frustumSection(const Camera& camera, double aspect, double depth) {
  const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const double t = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
  std::vector<glm::dvec3> corners;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      corners.push_back(camera.position + depth * (forward + right * (sx * t * aspect) + up * (sy * t)));
    }
  }
  return corners;
}

TEST_F(HostStub, CascadesSplitTheViewDepthsInOrderAndCoverTheirSlices) {
  const Scene scene = colonnadeScene();
  ASSERT_EQ(scene.cascades, 4u);
  const RenderSettings settings = smallSettings();
  ProbeEffect probe;
  probe.writeOutputs = false;
  render(scene, settings, 1, {&probe});
  ASSERT_EQ(probe.seen.size(), 1u);
  const std::vector<HostShadowMap>& maps = probe.seen[0].shadowMaps;
  ASSERT_EQ(maps.size(), 4u);

  const double n = scene.camera.nearPlane;
  const double f = scene.camera.farPlane;
  const double lambda = scene.cascadeSplit;
  EXPECT_GE(maps[0].viewDepthNear, 0.0f);
  EXPECT_LE(maps[0].viewDepthNear, n);
  EXPECT_EQ(maps[3].viewDepthFar, static_cast<float>(f));
  const double aspect = static_cast<double>(settings.width) / settings.height;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    SCOPED_TRACE("cascade " + std::to_string(i));
    const HostShadowMap& map = maps[i];
    EXPECT_EQ(map.depth.extent.width, scene.shadowMapSize);
    EXPECT_LT(map.viewDepthNear, map.viewDepthFar);
    if (i + 1 < maps.size()) {
      EXPECT_EQ(map.viewDepthFar, maps[i + 1].viewDepthNear);  // the same float: no gap, no overlap
      // Zhang et al. 2006's practical split scheme, in double precision.
      const double x = static_cast<double>(i + 1) / static_cast<double>(maps.size());
      const double split = lambda * n * std::pow(f / n, x) + (1.0 - lambda) * (n + (f - n) * x);
      EXPECT_NEAR(map.viewDepthFar, split, 1e-6 * split);
    }
    // The whole slice of the frustum lies inside the map's square, nearer than its depth 1.
    for (double depth : {std::max<double>(map.viewDepthNear, n), static_cast<double>(map.viewDepthFar)}) {
      for (const glm::dvec3& corner : frustumSection(scene.camera, aspect, depth)) {
        const glm::vec4 clip = map.worldToShadowClip * glm::vec4(glm::vec3(corner), 1.0f);
        EXPECT_LE(std::max(std::abs(clip.x), std::abs(clip.y)), 1.0f) << "depth " << depth;
        EXPECT_LE(clip.z, 1.0f) << "depth " << depth;
      }
    }
  }

  // RenderSettings::cascades (--cascades) overrides a directional light's count; spot lights keep one map.
  RenderSettings three = smallSettings();
  three.cascades = 3;
  probe.seen.clear();
  render(directionalScene(), three, 1, {&probe});
  ASSERT_EQ(probe.seen.size(), 1u);
  ASSERT_EQ(probe.seen[0].shadowMaps.size(), 3u);
  EXPECT_EQ(probe.seen[0].shadowMaps[2].viewDepthFar, static_cast<float>(directionalScene().camera.farPlane));
  probe.seen.clear();
  render(spotScene(), three, 1, {&probe});
  ASSERT_EQ(probe.seen.size(), 1u);
  ASSERT_EQ(probe.seen[0].shadowMaps.size(), 1u);
  EXPECT_EQ(probe.seen[0].shadowMaps[0].viewDepthFar, 0.0f);  // not a cascade
}

// The lighting pass picks each point's cascade by its view depth: the analytic scene's ground, lit
// and shadowed, comes out as with one map.
TEST_F(HostStub, CascadedDirectionalLightMatchesAnalyticShadingAndShadows) {
  const Scene scene = directionalScene();
  RenderSettings settings = smallSettings();
  settings.cascades = 4;
  const ImageRgba32f image = render(scene, settings);
  EXPECT_TRUE(allFinite(image));
  const GroundCheck check = checkGround(scene, image);
  EXPECT_GE(check.lit, 300);
  EXPECT_GE(check.shadowed, 20);
  EXPECT_EQ(check.failures, 0) << check.firstFailure;
}

// Stable cascades: as the camera walks along the avenue, each map's texel grid stays where it is in
// the world. The world → shadow matrices keep their x/y rows (axes and texel size) and their x/y
// offsets change by whole texels only (2/N in clip space).
TEST_F(HostStub, CascadeTexelGridsStayFixedInTheWorldAsTheCameraMoves) {
  const Scene scene = colonnadeScene();
  ProbeEffect probe;
  probe.writeOutputs = false;
  std::string error;
  std::unique_ptr<Renderer> renderer = Renderer::create(*device_, scene, smallSettings(), error);
  ASSERT_NE(renderer, nullptr) << error;
  renderer->addPostProcess(&probe);
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  Camera moved = scene.camera;
  const glm::dvec3 step(0.0, 0.0, -3.3);  // a few strides down the avenue
  moved.position += step;
  moved.target += step;
  ASSERT_TRUE(renderer->setCamera(moved, error)) << error;
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();
  ASSERT_EQ(probe.seen.size(), 2u);
  ASSERT_EQ(probe.seen[0].shadowMaps.size(), 4u);
  ASSERT_EQ(probe.seen[1].shadowMaps.size(), 4u);

  const double halfSize = 0.5 * scene.shadowMapSize;
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE("cascade " + std::to_string(i));
    const glm::mat4& before = probe.seen[0].shadowMaps[i].worldToShadowClip;
    const glm::mat4& after = probe.seen[1].shadowMaps[i].worldToShadowClip;
    double largestShift = 0.0;
    for (glm::length_t row = 0; row < 2; ++row) {
      for (glm::length_t column = 0; column < 3; ++column) EXPECT_EQ(before[column][row], after[column][row]);
      const double texels = (static_cast<double>(after[3][row]) - before[3][row]) * halfSize;
      EXPECT_NEAR(texels, std::round(texels), 1e-3) << (row == 0 ? "x" : "y");
      largestShift = std::max(largestShift, std::abs(texels));
    }
    EXPECT_GE(largestShift, 1.0) << "the map did not follow the camera";
  }
}

// A sanity check of the lit image: cascades move shadow edges, they do not relight the scene. Here
// the one 1024² map has texels of 20 × 5 cm, the four cascades 4 cm near the camera to 75 cm at the
// far end (a sphere's square, not the casters' footprint), and the edges that move shift the mean by
// 2.2% on lavapipe at 160×90.
TEST_F(HostStub, OneAndFourCascadesLightTheColonnadeAlike) {
  const Scene scene = colonnadeScene();
  RenderSettings settings = smallSettings();
  settings.width = 160;
  settings.height = 90;
  settings.cascades = 1;
  const ImageRgba32f one = render(scene, settings, 1);
  settings.cascades = 4;
  const ImageRgba32f four = render(scene, settings, 1);
  ASSERT_EQ(one.pixels.size(), four.pixels.size());
  double sumOne = 0.0;
  double sumFour = 0.0;
  for (std::size_t i = 0; i < one.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    sumOne += one.pixels[i];
    sumFour += four.pixels[i];
  }
  EXPECT_NE(one.pixels, four.pixels) << "the cascades changed nothing";
  const double values = 0.75 * static_cast<double>(one.pixels.size());
  std::printf("[ colonnade, 160x90 ] mean RGB, 1 cascade: %.5f, 4 cascades: %.5f\n", sumOne / values, sumFour / values);
  EXPECT_NEAR(sumFour / sumOne, 1.0, 0.03);
}

TEST_F(HostStub, FramesInFlightCountDoesNotChangeTheImage) {
  const Scene scene = spotScene();
  const ImageRgba32f reference = render(scene, smallSettings(), 3);
  for (std::uint32_t slots : {1u, 3u}) {
    RenderSettings settings = smallSettings();
    settings.framesInFlight = slots;
    ProbeEffect probe;
    probe.writeOutputs = false;
    const ImageRgba32f image = render(scene, settings, 5, {&probe});
    ASSERT_EQ(probe.seen.size(), 5u);
    for (std::size_t i = 0; i < probe.seen.size(); ++i) EXPECT_EQ(probe.seen[i].frameSlot, i % slots);
    EXPECT_EQ(image.pixels, reference.pixels) << slots << " frames in flight";
  }
}

TEST_F(HostStub, AFailingEffectAbortsOnlyItsFrame) {
  const Scene scene = directionalScene();
  ProbeEffect probe;
  probe.writeOutputs = false;
  std::string error;
  std::unique_ptr<Renderer> renderer = Renderer::create(*device_, scene, smallSettings(), error);
  ASSERT_NE(renderer, nullptr) << error;
  renderer->addPostProcess(&probe);
  ASSERT_TRUE(renderer->renderFrame(error)) << error;

  probe.failNext = true;
  error.clear();
  EXPECT_FALSE(renderer->renderFrame(error));
  EXPECT_NE(error.find("probe refused the frame"), std::string::npos) << error;

  // The previous frame is still the last rendered one, and rendering goes on.
  renderer->waitIdle();
  ImageRgba32f image;
  ASSERT_TRUE(renderer->readBackBuffer(image, error)) << error;
  EXPECT_TRUE(allFinite(image));
  EXPECT_GT(maxRgb(image), 0.1f);
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();
  ASSERT_EQ(probe.seen.size(), 3u);
  EXPECT_EQ(probe.seen[1].frameIndex, 1u);  // the aborted frame did not consume an index
  EXPECT_EQ(checkGround(scene, image).failures, 0);
}

TEST_F(HostStub, ResizeRebuildsTargetsAndTellsEffects) {
  const Scene scene = spotScene();
  ProbeEffect probe;
  probe.writeOutputs = false;
  std::string error;
  std::unique_ptr<Renderer> renderer = Renderer::create(*device_, scene, smallSettings(), error);
  ASSERT_NE(renderer, nullptr) << error;
  renderer->addPostProcess(&probe);
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  ASSERT_TRUE(renderer->renderFrame(error)) << error;

  ASSERT_TRUE(renderer->resize(40, 30, error)) << error;
  ASSERT_EQ(probe.resizes.size(), 1u);
  EXPECT_EQ(probe.resizes[0].width, 40u);
  EXPECT_EQ(probe.resizes[0].height, 30u);
  EXPECT_EQ(renderer->settings().width, 40u);
  EXPECT_EQ(renderer->settings().height, 30u);
  ImageRgba32f stale;
  EXPECT_FALSE(renderer->readBackBuffer(stale, error));  // no frame at the new size yet

  for (int i = 0; i < 3; ++i) ASSERT_TRUE(renderer->renderFrame(error)) << error;
  renderer->waitIdle();
  EXPECT_EQ(probe.seen.back().color.extent.width, 40u);
  EXPECT_EQ(probe.seen.back().depth.extent.height, 30u);
  ImageRgba32f resized;
  ASSERT_TRUE(renderer->readBackBuffer(resized, error)) << error;
  ASSERT_EQ(resized.width, 40u);
  ASSERT_EQ(resized.height, 30u);

  // Same as a renderer created at that size.
  RenderSettings settings = smallSettings();
  settings.width = 40;
  settings.height = 30;
  const ImageRgba32f fresh = render(scene, settings);
  ASSERT_EQ(fresh.pixels.size(), resized.pixels.size());
  for (std::size_t i = 0; i < fresh.pixels.size(); ++i) ASSERT_EQ(fresh.pixels[i], resized.pixels[i]) << i;
  EXPECT_EQ(checkGround(scene, resized).failures, 0);

  EXPECT_FALSE(renderer->resize(0, 30, error));
  EXPECT_FALSE(error.empty());
}

TEST_F(HostStub, SrgbBackBufferMatchesTheHalfFloatOneWithinQuantisation) {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(device_->physicalDevice(), VK_FORMAT_B8G8R8A8_SRGB, &properties);
  ASSERT_NE(properties.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT, 0u);
  const Scene scene = directionalScene();
  const ImageRgba32f reference = render(scene, smallSettings());
  RenderSettings settings = smallSettings();
  settings.backBufferFormat = VK_FORMAT_B8G8R8A8_SRGB;
  const ImageRgba32f srgb = render(scene, settings);
  ASSERT_EQ(srgb.pixels.size(), reference.pixels.size());
  // Half a step of 8-bit sRGB is at most 0.0047 in linear (at 1.0): 0.006 covers it.
  for (std::size_t i = 0; i < srgb.pixels.size(); ++i) {
    ASSERT_NEAR(srgb.pixels[i], std::min(reference.pixels[i], 1.0f), 0.006) << i;
  }
  // Not a trivially dark image: the comparison covered a range of values.
  EXPECT_GT(maxRgb(srgb), 0.5f);
}

TEST_F(HostStub, BadSettingsFailWithAReason) {
  const Scene scene = directionalScene();
  std::string error;
  RenderSettings settings = smallSettings();
  settings.framesInFlight = 0;
  EXPECT_EQ(Renderer::create(*device_, scene, settings, error), nullptr);
  EXPECT_NE(error.find("framesInFlight"), std::string::npos) << error;

  settings = smallSettings();
  settings.backBufferFormat = VK_FORMAT_R8_UNORM;
  error.clear();
  EXPECT_EQ(Renderer::create(*device_, scene, settings, error), nullptr);
  EXPECT_NE(error.find("back buffer format"), std::string::npos) << error;

  Scene wideSpot = spotScene();
  wideSpot.light.outerConeDegrees = 85.0;
  error.clear();
  EXPECT_EQ(Renderer::create(*device_, wideSpot, smallSettings(), error), nullptr);
  EXPECT_NE(error.find("80"), std::string::npos) << error;

  settings = smallSettings();
  settings.cascades = 5;
  error.clear();
  EXPECT_EQ(Renderer::create(*device_, scene, settings, error), nullptr);
  EXPECT_NE(error.find("cascades must be in [0, 4]"), std::string::npos) << error;

  Scene noCascade = directionalScene();
  noCascade.cascades = 0;
  error.clear();
  EXPECT_EQ(Renderer::create(*device_, noCascade, smallSettings(), error), nullptr);
  EXPECT_NE(error.find("shadowMap: cascades must be in [1, 4]"), std::string::npos) << error;

  Scene cascadedSpot = spotScene();
  cascadedSpot.light.cascades = 2;
  error.clear();
  EXPECT_EQ(Renderer::create(*device_, cascadedSpot, smallSettings(), error), nullptr);
  EXPECT_NE(error.find("only directional lights take cascades"), std::string::npos) << error;

  // A colour texture lies over one map's square (the file is not read before this check).
  Scene stainedSun = directionalScene();
  stainedSun.light.colorTexture = "stained-glass.png";
  stainedSun.cascades = 2;
  error.clear();
  EXPECT_EQ(Renderer::create(*device_, stainedSun, smallSettings(), error), nullptr);
  EXPECT_NE(error.find("colour texture needs one shadow map"), std::string::npos) << error;

  Scene badCamera = directionalScene();
  badCamera.camera.target = badCamera.camera.position;
  error.clear();
  EXPECT_EQ(Renderer::create(*device_, badCamera, smallSettings(), error), nullptr);
  EXPECT_NE(error.find("camera"), std::string::npos) << error;
}

// ---------------------------------------------------------------------------------------------
// Display transform and image files
// ---------------------------------------------------------------------------------------------

TEST(HostStubDisplay, OcioConfigLoadsAndValidates) {
  // The file shipped in the repository (the build embeds this text).
  const std::filesystem::path path =
      std::filesystem::path(TYNDALL_SCENES_DIR) / ".." / ".." / "host-stub" / "ocio" / "config.ocio";
  std::ifstream file(path);
  ASSERT_TRUE(file) << path;
  namespace OCIO = OCIO_NAMESPACE;
  OCIO::ConstConfigRcPtr config;
  ASSERT_NO_THROW(config = OCIO::Config::CreateFromStream(file));
  EXPECT_NO_THROW(config->validate());
  EXPECT_GE(config->getMajorVersion(), 2u);
  EXPECT_NE(config->getColorSpace(OCIO::ROLE_SCENE_LINEAR), nullptr);
  EXPECT_STREQ(config->getDefaultDisplay(), "sRGB");
  EXPECT_STREQ(config->getDefaultView("sRGB"), "Standard");
}

TEST(HostStubDisplay, SrgbDisplayEncodesMidGreyBlackAndWhite) {
  ImageRgba32f linear;
  linear.width = 5;
  linear.height = 1;
  linear.pixels = {0.18f, 0.18f, 0.18f, 1.0f,  0.0f, 0.0f, 0.0f, 1.0f,  1.0f, 1.0f, 1.0f, 1.0f,
                   4.0f, -1.0f, 0.0031308f, 1.0f,  0.5f, 0.05f, 0.9f, 0.0f};
  std::vector<std::uint8_t> rgba8;
  std::string error;
  ASSERT_TRUE(displayToSrgb8(linear, rgba8, error)) << error;
  ASSERT_EQ(rgba8.size(), 20u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(rgba8[static_cast<std::size_t>(c)], 118) << "0.18 → 1.055·0.18^(1/2.4) − 0.055 = 0.4614";
    EXPECT_EQ(rgba8[static_cast<std::size_t>(4 + c)], 0);
    EXPECT_EQ(rgba8[static_cast<std::size_t>(8 + c)], 255);
  }
  EXPECT_EQ(rgba8[12], 255);  // above 1 clips
  EXPECT_EQ(rgba8[13], 0);    // below 0 clips
  EXPECT_EQ(rgba8[14], 10);   // the linear segment's end: 0.0031308 · 12.92 = 0.04045 → 10.3
  // Against the sRGB formula for arbitrary values.
  auto encode = [](double v) {
    v = std::clamp(v, 0.0, 1.0);
    const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<int>(std::lround(e * 255.0));
  };
  EXPECT_EQ(rgba8[16], encode(0.5));
  EXPECT_EQ(rgba8[17], encode(0.05));
  EXPECT_EQ(rgba8[18], encode(0.9));
  EXPECT_EQ(rgba8[19], 0);  // alpha passes through

  linear.pixels.pop_back();
  EXPECT_FALSE(displayToSrgb8(linear, rgba8, error));
  EXPECT_FALSE(error.empty());
}

class HostStubFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("tyndall_host_stub_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(HostStubFiles, PngRoundTrip) {
  const std::uint32_t width = 7;
  const std::uint32_t height = 3;
  std::vector<std::uint8_t> rgba(width * height * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<std::uint8_t>((i * 37 + 11) % 256);
  const std::string path = (dir_ / "image.png").string();
  std::string error;
  ASSERT_TRUE(writePng(path, width, height, rgba, error)) << error;
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

  int w = 0;
  int h = 0;
  int channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &channels, 4);
  ASSERT_NE(pixels, nullptr);
  EXPECT_EQ(w, 7);
  EXPECT_EQ(h, 3);
  const std::vector<std::uint8_t> read(pixels, pixels + rgba.size());
  stbi_image_free(pixels);
  EXPECT_EQ(read, rgba);  // row 0 first in both
}

TEST_F(HostStubFiles, ExrRoundTripIsExact) {
  ImageRgba32f image;
  image.width = 5;
  image.height = 4;
  for (std::uint32_t i = 0; i < image.width * image.height; ++i) {
    const float f = static_cast<float>(i);
    image.pixels.insert(image.pixels.end(), {f * 0.1f - 0.5f, 1e-7f * f, 1e6f + f * 3.25f, 1.0f});
  }
  image.pixels[4] = std::numeric_limits<float>::denorm_min();
  const std::string path = (dir_ / "image.exr").string();
  std::string error;
  ASSERT_TRUE(writeExr(path, image, error)) << error;
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  ImageRgba32f read;
  ASSERT_TRUE(readExr(path, read, error)) << error;
  EXPECT_EQ(read.width, image.width);
  EXPECT_EQ(read.height, image.height);
  EXPECT_EQ(read.pixels, image.pixels);  // RGB float32 exactly; alpha is not stored and reads as 1
}

TEST_F(HostStubFiles, FailuresLeaveNoFileBehind) {
  std::string error;
  ImageRgba32f read;
  EXPECT_FALSE(readExr((dir_ / "missing.exr").string(), read, error));
  EXPECT_NE(error.find("missing.exr"), std::string::npos) << error;

  ImageRgba32f image;
  image.width = 2;
  image.height = 2;
  image.pixels.assign(16, 0.5f);
  const std::string unwritable = (dir_ / "no-such-dir" / "image.exr").string();
  error.clear();
  EXPECT_FALSE(writeExr(unwritable, image, error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(std::filesystem::exists(unwritable + ".tmp"));

  error.clear();
  EXPECT_FALSE(writePng((dir_ / "short.png").string(), 2, 2, std::vector<std::uint8_t>(15), error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(std::filesystem::exists(dir_ / "short.png"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "short.png.tmp"));

  // Not an EXR: a clear error, no crash.
  const std::string text = (dir_ / "text.exr").string();
  std::ofstream(text) << "not an image";
  error.clear();
  EXPECT_FALSE(readExr(text, read, error));
  EXPECT_FALSE(error.empty());
}

}  // namespace
