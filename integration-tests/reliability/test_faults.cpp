// Injected faults (fault_injection.h): a Vulkan allocation or pipeline creation failing at the Nth
// call during create, resize, warm-up and record. Every call returns a failing Outcome naming the
// call that failed, nothing leaks (every object the plugin created is destroyed with the context),
// the back buffer is left as the host rendered it, and the next call succeeds. A lost device is
// reported by the next record.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fault_injection.h"
#include "test_support.h"
#include "tyndall/tuning.h"
#include "tyndall_effect.h"

namespace tyndall::test {
namespace {

constexpr VkFormat kBackBufferFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

std::vector<std::string> contextErrors;
void collectErrors(Severity severity, const char* message, void*) {
  if (severity == Severity::Error) contextErrors.emplace_back(message);
}

// A context on the validated device, every device call through the fault injector. Pipelines are
// compiled on first use, so that each phase (warm-up, a frame) compiles its own.
ContextDesc faultyContextDesc(VkExtent2D extent) {
  host::Device& device = validatedDevice();
  ContextDesc desc;
  desc.instance = device.instance();
  desc.physicalDevice = device.physicalDevice();
  desc.device = device.device();
  desc.getInstanceProcAddr = device.getInstanceProcAddr();
  desc.getDeviceProcAddr = FaultInjector::get().install(device.getDeviceProcAddr());
  desc.queueFamilyIndex = device.queueFamily();
  desc.maxFramesInFlight = 2;
  desc.outputExtent = extent;
  desc.backBufferFormat = kBackBufferFormat;
  static const ContextTuning tuning{PipelineCreation::OnFirstUse, 0};
  desc.tuning = &tuning;
  desc.messageCallback = &collectErrors;
  return desc;
}

// The injected failure came back as the Outcome of the call that met it.
void expectFailureNamesTheCall(const Outcome& outcome, const std::string& where) {
  const std::string& call = FaultInjector::get().failedCall();
  ASSERT_FALSE(call.empty()) << where << ": no call was made to fail";
  EXPECT_FALSE(outcome.ok()) << where << ": " << call << " failed and the call succeeded";
  EXPECT_EQ(outcome.status, Status::VulkanError) << where << ": " << outcome.message;
  EXPECT_NE(outcome.vkResult, VK_SUCCESS) << where;
  EXPECT_NE(outcome.message.find(call), std::string::npos) << where << ": the message does not name " << call
                                                           << ": " << outcome.message;
}

void expectNothingLive(const std::string& where) {
  EXPECT_TRUE(FaultInjector::get().liveObjects().empty())
      << where << ": objects created by the plugin and never destroyed: " << FaultInjector::get().describeLiveObjects();
}

// Which of the calls 1..count to fail: all of them up to `most`, else `most` spread evenly
// (first and last included).
std::vector<std::uint64_t> failurePoints(std::uint64_t count, std::uint64_t most) {
  std::set<std::uint64_t> points;
  if (count <= most) {
    for (std::uint64_t n = 1; n <= count; ++n) points.insert(n);
  } else {
    for (std::uint64_t i = 0; i < most; ++i) points.insert(1 + i * (count - 1) / (most - 1));
  }
  return {points.begin(), points.end()};
}

const char* kindName(FaultKind kind) { return kind == FaultKind::Allocation ? "allocation" : "pipeline"; }

class Faults : public ::testing::Test {
 protected:
  void SetUp() override {
    FaultInjector::get().reset();
    contextErrors.clear();
    validatedDevice().clearValidationMessages();
  }
  void TearDown() override {
    FaultInjector::get().reset();
    expectNothingLive("after the test");
    expectNoValidationMessages();
  }
};

TEST_F(Faults, CreateFailsCleanlyAtEveryCall) {
  FaultInjector& injector = FaultInjector::get();
  const ContextDesc desc = faultyContextDesc({64, 36});
  std::uint64_t counts[2] = {};
  {
    Result<std::unique_ptr<Context>> created = Context::create(desc);
    ASSERT_TRUE(created) << created.outcome().message;
    counts[0] = injector.calls(FaultKind::Allocation);
    counts[1] = injector.calls(FaultKind::Pipeline);
  }
  expectNothingLive("a context created and destroyed");
  ASSERT_GT(counts[0], 10u);
  ASSERT_GT(counts[1], 0u);  // the composite for backBufferFormat

  for (FaultKind kind : {FaultKind::Allocation, FaultKind::Pipeline}) {
    for (std::uint64_t n = 1; n <= counts[kind == FaultKind::Pipeline]; ++n) {
      const std::string where = std::string("create, ") + kindName(kind) + " call " + std::to_string(n);
      injector.failAt(n, kind);
      contextErrors.clear();
      Result<std::unique_ptr<Context>> created = Context::create(desc);
      expectFailureNamesTheCall(created.outcome(), where);
      EXPECT_EQ(contextErrors.size(), 1u) << where << ": the message callback is told once";
      expectNothingLive(where);
      injector.reset();
    }
  }
  Result<std::unique_ptr<Context>> created = Context::create(desc);
  EXPECT_TRUE(created) << "after the failures: " << created.outcome().message;
}

TEST_F(Faults, ResizeFailsCleanlyAndTheNextResizeWorks) {
  FaultInjector& injector = FaultInjector::get();
  Result<std::unique_ptr<Context>> created = Context::create(faultyContextDesc({64, 36}));
  ASSERT_TRUE(created) << created.outcome().message;
  Context& context = *created.value();
  injector.reset();
  ASSERT_TRUE(context.resize({48, 48}));
  const std::uint64_t count = injector.calls(FaultKind::Allocation);
  ASSERT_GT(count, 0u);
  const auto liveBefore = injector.liveObjects();

  for (std::uint64_t n = 1; n <= count; ++n) {
    const std::string where = "resize, allocation call " + std::to_string(n);
    injector.failAt(n, FaultKind::Allocation);
    expectFailureNamesTheCall(context.resize({40, 30}), where);
    injector.reset();
    // The same size again: the failed resize built nothing, so this one builds it all.
    const Outcome retried = context.resize({40, 30});
    EXPECT_TRUE(retried) << where << ", then again: " << retried.message;
    EXPECT_EQ(injector.calls(FaultKind::Allocation), count) << where;
    EXPECT_EQ(injector.liveObjects(), liveBefore) << where << ": " << injector.describeLiveObjects();
    ASSERT_TRUE(context.resize({48, 48}));
  }
}

TEST_F(Faults, WarmUpFailsCleanlyAndTheNextWarmUpWorks) {
  FaultInjector& injector = FaultInjector::get();
  const ContextDesc desc = faultyContextDesc({32, 18});
  // A warm-up compiles every technique's pipelines (tens of seconds on lavapipe with validation),
  // so two failure points, both in the middle of the epipolar technique's list (compiled as one
  // list, as the prefiltered technique's): a pipeline, and a shader module.
  std::uint64_t total = 0;  // pipelines in a warm-up
  for (const auto& [kind, n] : {std::pair{FaultKind::Pipeline, 10ull}, std::pair{FaultKind::Allocation, 12ull}}) {
    const std::string where = std::string("warm-up, ") + kindName(kind) + " call " + std::to_string(n);
    {
      Result<std::unique_ptr<Context>> created = Context::create(desc);
      ASSERT_TRUE(created) << created.outcome().message;
      injector.failAt(n, kind);
      expectFailureNamesTheCall(created.value()->warmUp(), where);
      const std::uint64_t compiledBefore =
          injector.calls(FaultKind::Pipeline) - (kind == FaultKind::Pipeline ? 1 : 0);
      injector.reset();
      const Outcome again = created.value()->warmUp();
      EXPECT_TRUE(again) << where << ", then again: " << again.message;
      // The second warm-up compiled only what the first left missing.
      if (total == 0) total = injector.calls(FaultKind::Pipeline) + compiledBefore;
      EXPECT_EQ(injector.calls(FaultKind::Pipeline) + compiledBefore, total) << where;
      injector.reset();
      EXPECT_TRUE(created.value()->warmUp());
      EXPECT_EQ(injector.calls(FaultKind::Pipeline), 0u) << where << ": a third warm-up compiled again";
    }
    expectNothingLive(where);
  }
  EXPECT_GT(total, 10u);
}

// The host's post-process stack with Tyndall in it as an engine inserts it, except that a failed
// record is skipped (an engine renders the frame without the effect) and remembered.
class SkippingEffect final : public host::PostProcessEffect {
 public:
  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string&) override {
    if (context == nullptr) return true;
    samples::FrameStorage storage;
    FrameDesc frame = samples::makeFrameDesc(inputs, Profile::High, storage);
    if (inputs.aovDebug.image != VK_NULL_HANDLE) {
      frame.debugView = DebugView::EpipolarSamples;
      frame.debugOutput = {inputs.aovDebug.image, inputs.aovDebug.view, inputs.aovDebug.format, 0,
                           inputs.aovDebug.extent, inputs.aovDebug.layout};
    }
    FaultInjector::get().takeCommandCount();
    outcome = context->record(cmd, frame);
    commands = FaultInjector::get().takeCommandCount();
    return true;
  }
  bool resize(VkExtent2D extent, std::string& error) override {
    if (context == nullptr) return true;
    const Outcome o = context->resize(extent);
    error = o.message;
    return o.ok();
  }
  Context* context = nullptr;
  Outcome outcome;
  std::uint64_t commands = 0;
};

// The host these tests render with: `scene` at kHostExtent with a 256² map, `effect` in its
// post-process stack; null (and `error`) when it cannot be created.
constexpr VkExtent2D kHostExtent{48, 27};
std::unique_ptr<host::Renderer> hostWith(const char* scene, bool aovImages, SkippingEffect& effect,
                                         std::string& error) {
  host::RenderSettings settings;
  settings.width = kHostExtent.width;
  settings.height = kHostExtent.height;
  settings.shadowMapSize = 256;
  settings.backBufferFormat = kBackBufferFormat;
  settings.aovImages = aovImages;
  std::unique_ptr<host::Renderer> renderer =
      host::Renderer::create(validatedDevice(), loadTestScene(scene), settings, error);
  if (renderer) renderer->addPostProcess(&effect);
  return renderer;
}

TEST_F(Faults, RecordFailsWithNothingRecordedAndTheNextFrameWorks) {
  FaultInjector& injector = FaultInjector::get();
  SkippingEffect effect;
  std::string error;
  std::unique_ptr<host::Renderer> renderer = hostWith("spot-lamp", true, effect, error);
  ASSERT_TRUE(renderer) << error;

  // The back buffer as the host leaves it without Tyndall.
  host::ImageRgba32f hostOnly;
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  ASSERT_TRUE(renderer->readBackBuffer(hostOnly, error)) << error;

  const ContextDesc desc = faultyContextDesc(kHostExtent);
  // A first frame of the epipolar technique with a spot light and a debug view: its pipelines,
  // its textures, the fix-up list, the scattering table and the debug image.
  std::uint64_t counts[2] = {};
  {
    Result<std::unique_ptr<Context>> created = Context::create(desc);
    ASSERT_TRUE(created) << created.outcome().message;
    effect.context = created.value().get();
    injector.reset();
    ASSERT_TRUE(renderer->renderFrame(error)) << error;
    ASSERT_TRUE(effect.outcome) << effect.outcome.message;
    counts[0] = injector.calls(FaultKind::Allocation);
    counts[1] = injector.calls(FaultKind::Pipeline);
    renderer->waitIdle();
    effect.context = nullptr;
  }
  ASSERT_GT(counts[0], 3u);
  ASSERT_GT(counts[1], 3u);

  for (FaultKind kind : {FaultKind::Allocation, FaultKind::Pipeline}) {
    // Each point compiles the frame's pipelines afresh (seconds on lavapipe): a few points per kind.
    for (std::uint64_t n : failurePoints(counts[kind == FaultKind::Pipeline], kind == FaultKind::Allocation ? 6 : 2)) {
      const std::string where = std::string("first frame, ") + kindName(kind) + " call " + std::to_string(n);
      {
        Result<std::unique_ptr<Context>> created = Context::create(desc);
        ASSERT_TRUE(created) << created.outcome().message;
        effect.context = created.value().get();
        injector.failAt(n, kind);
        ASSERT_TRUE(renderer->renderFrame(error)) << error;
        expectFailureNamesTheCall(effect.outcome, where);
        EXPECT_EQ(effect.commands, 0u) << where << ": a failed record recorded commands";
        EXPECT_EQ(created.value()->stats().frameIndex, 0u) << where;
        host::ImageRgba32f color;
        ASSERT_TRUE(renderer->readBackBuffer(color, error)) << error;
        EXPECT_EQ(color.pixels, hostOnly.pixels) << where << ": the back buffer is not the host's";

        // The next frame, nothing failing: recorded, composited, finite.
        injector.reset();
        ASSERT_TRUE(renderer->renderFrame(error)) << error;
        EXPECT_TRUE(effect.outcome) << where << ", the next frame: " << effect.outcome.message;
        ASSERT_TRUE(renderer->readBackBuffer(color, error)) << error;
        EXPECT_NE(color.pixels, hostOnly.pixels) << where << ": the next frame left the back buffer alone";
        EXPECT_TRUE(std::all_of(color.pixels.begin(), color.pixels.end(), [](float v) { return std::isfinite(v); }))
            << where;
        renderer->waitIdle();
        effect.context = nullptr;
      }
      expectNothingLive(where);
      expectNoValidationMessages();
    }
  }
}

TEST_F(Faults, RecordAfterAFailedResizeFailsUntilAResizeWorks) {
  FaultInjector& injector = FaultInjector::get();
  Result<std::unique_ptr<Context>> created = Context::create(faultyContextDesc({64, 36}));
  ASSERT_TRUE(created) << created.outcome().message;
  Context& context = *created.value();
  injector.failAt(1, FaultKind::Allocation);
  expectFailureNamesTheCall(context.resize({48, 27}), "resize");
  injector.reset();

  // Any frame: the context has no output target to record into.
  FrameDesc frame;
  const Outcome outcome = context.record(reinterpret_cast<VkCommandBuffer>(std::uintptr_t{1}), frame);
  EXPECT_FALSE(outcome);
  EXPECT_EQ(outcome.status, Status::VulkanError) << outcome.message;
  EXPECT_NE(outcome.message.find("resize"), std::string::npos) << outcome.message;
  EXPECT_EQ(injector.takeCommandCount(), 0u);
  EXPECT_TRUE(context.resize({48, 27}));
}

TEST_F(Faults, ADeviceLostMidFrameFailsTheNextRecord) {
  FaultInjector& injector = FaultInjector::get();
  SkippingEffect effect;
  std::string error;
  std::unique_ptr<host::Renderer> renderer = hostWith("pillars", false, effect, error);
  ASSERT_TRUE(renderer) << error;
  Result<std::unique_ptr<Context>> created = Context::create(faultyContextDesc(kHostExtent));
  ASSERT_TRUE(created) << created.outcome().message;
  effect.context = created.value().get();
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(renderer->renderFrame(error)) << error;
    ASSERT_TRUE(effect.outcome) << effect.outcome.message;
  }
  renderer->waitIdle();

  // The device is lost while the frames above were on it: the timestamps of the next frame the
  // context reads come back VK_ERROR_DEVICE_LOST.
  injector.loseDevice();
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  EXPECT_FALSE(effect.outcome);
  EXPECT_EQ(effect.outcome.status, Status::VulkanError) << effect.outcome.message;
  EXPECT_EQ(effect.outcome.vkResult, VK_ERROR_DEVICE_LOST) << effect.outcome.message;
  EXPECT_EQ(effect.commands, 0u);
  // And every frame after it: a lost device does not come back.
  injector.reset();
  ASSERT_TRUE(renderer->renderFrame(error)) << error;
  EXPECT_EQ(effect.outcome.vkResult, VK_ERROR_DEVICE_LOST) << effect.outcome.message;
  renderer->waitIdle();
  effect.context = nullptr;
}

}  // namespace
}  // namespace tyndall::test
