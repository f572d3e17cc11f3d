#include "test_support.h"

#include <cstdlib>
#include <memory>

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

samples::RenderResult renderWithAovs(const host::Scene& scene, samples::RenderOptions options) {
  samples::RenderResult result;
  std::string error;
  EXPECT_TRUE(samples::renderScene(validatedDevice(), scene, options, true, result, error)) << error;
  return result;
}

}  // namespace tyndall::test
