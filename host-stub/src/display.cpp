// Display transform through OpenColorIO, with the config shipped in host-stub/ocio/config.ocio.
#include <algorithm>
#include <cmath>
#include <sstream>

#include <OpenColorIO/OpenColorIO.h>

#include "ocio_config.h"
#include "tyndall_host/renderer.h"

namespace OCIO = OCIO_NAMESPACE;

namespace tyndall::host {

namespace {
constexpr const char* kDisplay = "sRGB";
constexpr const char* kView = "Standard";
}  // namespace

bool displayToSrgb8(const ImageRgba32f& linear, std::vector<std::uint8_t>& rgba8, std::string& error) {
  const std::size_t pixelCount = static_cast<std::size_t>(linear.width) * linear.height;
  if (linear.width == 0 || linear.height == 0 || linear.pixels.size() != pixelCount * 4) {
    error = "displayToSrgb8: image is empty or its pixel count does not match width x height";
    return false;
  }
  // OCIO reports every failure (bad config, unknown display or view) by throwing.
  try {
    std::istringstream configText(kOcioConfig);
    const OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromStream(configText);
    config->validate();
    const OCIO::ConstProcessorRcPtr processor =
        config->getProcessor(OCIO::ROLE_SCENE_LINEAR, kDisplay, kView, OCIO::TRANSFORM_DIR_FORWARD);
    const OCIO::ConstCPUProcessorRcPtr cpu = processor->getDefaultCPUProcessor();

    std::vector<float> display = linear.pixels;
    // NaN would pass through the transform; show it as black rather than as an undefined byte.
    for (float& value : display) {
      if (!std::isfinite(value)) value = std::isinf(value) && value > 0.0f ? 1e30f : 0.0f;
    }
    OCIO::PackedImageDesc image(display.data(), static_cast<long>(linear.width),
                                static_cast<long>(linear.height), 4);
    cpu->apply(image);

    rgba8.resize(display.size());
    for (std::size_t i = 0; i < display.size(); ++i) {
      // Alpha is data, not colour: OCIO leaves it as it was; it is clamped the same way.
      const float clamped = std::clamp(display[i], 0.0f, 1.0f);
      rgba8[i] = static_cast<std::uint8_t>(std::lround(clamped * 255.0f));
    }
  } catch (const OCIO::Exception& e) {
    error = std::string("OpenColorIO: ") + e.what();
    return false;
  }
  return true;
}

}  // namespace tyndall::host
