#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "tyndall_effect.h"

namespace tyndall::test {

host::Device& validatedDevice() {
  static std::unique_ptr<host::Device> device = [] {
    host::DeviceOptions options;
    options.validation = true;
    std::string error;
    std::unique_ptr<host::Device> created = host::Device::create(options, error);
    if (!created) {
      std::fprintf(stderr, "cannot create the validated test device: %s\n", error.c_str());
      std::abort();
    }
    return created;
  }();
  return *device;
}

void expectNoValidationMessages() {
  host::Device& device = validatedDevice();
  const std::vector<std::string>& messages = device.validationMessages();
  EXPECT_TRUE(messages.empty()) << messages.size() << " validation message(s); first: "
                                << (messages.empty() ? "" : messages.front());
  device.clearValidationMessages();
}

host::Scene loadTestScene(const std::string& name) {
  const std::string path = std::string(TYNDALL_SCENES_DIR) + "/" + name + ".json";
  host::SceneLoadResult loaded = host::loadScene(path);
  if (!loaded.scene) {
    ADD_FAILURE() << path << ": " << loaded.error;
    return host::Scene{};
  }
  return *loaded.scene;
}

double prefilteredBar(PrefilteredBasis basis) {
  switch (basis) {
    case PrefilteredBasis::Moments4_64:
    case PrefilteredBasis::Moments4_128:
      return 0.08;
    case PrefilteredBasis::Fourier32:
      return INFINITY;
    default:
      return 0.05;
  }
}

ErrorStats compareRgb(const host::ImageRgba32f& measured, const std::vector<double>& referenceRgb,
                      const std::vector<unsigned char>* mask) {
  const std::size_t pixels = static_cast<std::size_t>(measured.width) * measured.height;
  EXPECT_EQ(referenceRgb.size(), pixels * 3);
  if (referenceRgb.size() != pixels * 3) return {};
  return samples::compareRgb(measured, referenceRgb, mask);
}

ErrorStats compareRgb(const host::ImageRgba32f& measured, const host::ImageRgba32f& reference,
                      const std::vector<unsigned char>* mask) {
  const std::size_t pixels = static_cast<std::size_t>(measured.width) * measured.height;
  EXPECT_EQ(reference.pixels.size(), pixels * 4);
  if (reference.pixels.size() != pixels * 4) return {};
  return samples::compareRgb(measured, reference, mask);
}

host::Object planeObject(const glm::dvec3& point, const glm::dvec3& normal) {
  host::Object o;
  o.type = host::ObjectType::Plane;
  o.point = point;
  o.normal = normal;
  return o;
}

host::Object boxObject(const glm::dvec3& center, const glm::dvec3& halfExtents) {
  host::Object o;
  o.type = host::ObjectType::Box;
  o.center = center;
  o.halfExtents = halfExtents;
  return o;
}

host::Scene withEpipoleAt(host::Scene scene, glm::dvec2 ndc, bool behind, std::uint32_t width, std::uint32_t height) {
  const glm::dvec3 toLight = (behind ? 1.0 : -1.0) * glm::normalize(scene.light.direction);
  const double tanHalf = std::tan(glm::radians(scene.camera.fovYDegrees) * 0.5);
  const double aspect = double(width) / height;
  // The light's direction in camera space (x right, y up, looking down −z).
  const glm::dvec3 c = glm::normalize(glm::dvec3(ndc.x * tanHalf * aspect, -ndc.y * tanHalf, -1.0));
  // A camera looking straight at the light, then turned so that the light lands on c.
  const glm::dvec3 worldUp = std::abs(toLight.y) > 0.99 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  const glm::dvec3 r0 = glm::normalize(glm::cross(toLight, worldUp));
  const glm::dvec3 u0 = glm::cross(r0, toLight);
  const glm::dmat3 lookingAtLight(r0, u0, -toLight);
  const glm::dvec3 axis = glm::cross(c, glm::dvec3(0, 0, -1));
  const double angle = std::acos(std::clamp(glm::dot(c, glm::dvec3(0, 0, -1)), -1.0, 1.0));
  glm::dmat3 turn(1.0);
  if (glm::length(axis) > 1e-12) turn = glm::dmat3(glm::rotate(glm::dmat4(1.0), angle, glm::normalize(axis)));
  const glm::dmat3 cameraToWorld = lookingAtLight * turn;
  scene.camera.target = scene.camera.position + cameraToWorld * glm::dvec3(0, 0, -1);
  scene.camera.up = cameraToWorld * glm::dvec3(0, 1, 0);
  return scene;
}

samples::RenderResult renderWithAovs(const host::Scene& scene, samples::RenderOptions options) {
  // A context per render: compiling only the pipelines a test's techniques use keeps the suite
  // fast on lavapipe (every technique's, up front, takes seconds per context).
  options.pipelineCreation = PipelineCreation::OnFirstUse;
  samples::RenderResult result;
  std::string error;
  EXPECT_TRUE(samples::renderScene(validatedDevice(), scene, options, true, result, error)) << error;
  return result;
}

samples::RenderResult renderWithSharedContext(const host::Scene& scene, samples::RenderOptions options) {
  // The device first: function-local statics are destroyed in reverse order, the contexts before it.
  host::Device& device = validatedDevice();
  using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, VkFormat, bool>;
  static std::map<Key, std::unique_ptr<samples::TyndallEffect>> effects;
  samples::RenderResult result;
  std::string error;
  const host::RenderSettings settings = samples::renderSettingsFor(options, true);
  const Key key{settings.width, settings.height, settings.framesInFlight, settings.backBufferFormat,
                options.fullFloatTargets};
  std::unique_ptr<samples::TyndallEffect>& effect = effects[key];
  if (!effect) {
    effect = samples::TyndallEffect::create(device, settings, options.profile, error, PipelineCreation::OnFirstUse, 0,
                                            options.fullFloatTargets);
  }
  if (!effect) {
    ADD_FAILURE() << error;
    return result;
  }
  EXPECT_TRUE(samples::renderScene(device, scene, options, true, *effect, result, error)) << error;
  return result;
}

}  // namespace tyndall::test
