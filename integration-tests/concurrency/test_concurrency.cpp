// Two Tyndall contexts on one device, each created and recording on a thread of its own into its
// own command buffers (an engine with a render thread per view), submitting to the shared queue
// under the host's queue mutex. Each view's L_in must be what the same view renders alone, with no
// validation message (the layer's thread-safety checks included). scripts/tsan.sh builds and runs
// this test under ThreadSanitizer.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "tyndall_effect.h"
#include "tyndall_host/renderer.h"
#include "tyndall_host/scene.h"

namespace tyndall::test {
namespace {

constexpr int kFrames = 6;

// One view: its scene, its renderer (command buffers, fences, images), its Tyndall context.
struct View {
  std::string scene;
  Profile profile = Profile::Balanced;
  host::ImageRgba32f scattering;
  Stats stats;
  std::vector<std::string> messages;
  std::string error;

  // Creates everything on the calling thread, renders kFrames frames and reads L_in back.
  void render() {
    host::Device& device = validatedDevice();
    host::SceneLoadResult loaded = host::loadScene(std::string(TYNDALL_SCENES_DIR) + "/" + scene + ".json");
    if (!loaded.scene) {
      error = loaded.error;
      return;
    }
    host::RenderSettings settings;
    settings.width = 64;
    settings.height = 36;
    settings.shadowMapSize = 256;
    settings.aovImages = true;
    std::unique_ptr<samples::TyndallEffect> effect =
        samples::TyndallEffect::create(device, settings, profile, error, PipelineCreation::OnFirstUse);
    if (!effect) return;
    std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, *loaded.scene, settings, error);
    if (!renderer) return;
    renderer->addPostProcess(effect.get());
    for (int frame = 0; frame < kFrames; ++frame) {
      if (!renderer->renderFrame(error)) return;
      effect->context().collectTimings();
    }
    if (!renderer->readAovScattering(scattering, error)) return;
    renderer->waitIdle();
    effect->context().collectTimings();
    stats = effect->context().stats();
    for (const std::string& message : effect->messages()) {
      if (message.rfind("error: ", 0) == 0) messages.push_back(message);
    }
  }
};

TEST(Concurrency, TwoContextsRecordingOnTwoThreadsRenderWhatEachRendersAlone) {
  host::Device& device = validatedDevice();
  std::vector<View> alone = {{"pillars", Profile::Balanced}, {"spot-lamp", Profile::High}};
  for (View& view : alone) {
    view.render();
    ASSERT_TRUE(view.error.empty()) << view.scene << " alone: " << view.error;
  }
  ASSERT_TRUE(device.validationMessages().empty()) << device.validationMessages().front();

  std::vector<View> together = {{"pillars", Profile::Balanced}, {"spot-lamp", Profile::High}};
  {
    std::vector<std::thread> threads;
    for (View& view : together) threads.emplace_back([&view] { view.render(); });
    for (std::thread& thread : threads) thread.join();
  }
  for (std::size_t i = 0; i < together.size(); ++i) {
    const View& view = together[i];
    ASSERT_TRUE(view.error.empty()) << view.scene << " on its thread: " << view.error;
    EXPECT_TRUE(view.messages.empty()) << view.scene << ": " << view.messages.front();
    EXPECT_EQ(view.stats.frameIndex, static_cast<std::uint64_t>(kFrames)) << view.scene;
    EXPECT_EQ(view.stats.technique, Technique::Epipolar) << view.scene << ": " << view.stats.techniqueNote;
    EXPECT_TRUE(view.stats.timingsValid) << view.scene;
    ASSERT_EQ(view.scattering.pixels.size(), alone[i].scattering.pixels.size()) << view.scene;
    // The same commands on the same inputs: the same L_in, to the bit, whatever ran beside it.
    std::size_t differing = 0;
    for (std::size_t p = 0; p < view.scattering.pixels.size(); ++p) {
      if (view.scattering.pixels[p] != alone[i].scattering.pixels[p]) ++differing;
    }
    EXPECT_EQ(differing, 0u) << view.scene << ": L_in differs from the view rendered alone";
    float peak = 0.0f;
    for (float v : view.scattering.pixels) peak = std::max(peak, v);
    EXPECT_GT(peak, 0.0f) << view.scene << ": no in-scattering at all";
  }
  const std::vector<std::string>& messages = device.validationMessages();
  EXPECT_TRUE(messages.empty()) << messages.size() << " validation message(s); first: "
                                << (messages.empty() ? "" : messages.front());
}

}  // namespace
}  // namespace tyndall::test
