// tyndall-soak: one Tyndall context records frame after frame while everything an engine may
// change between frames changes: profile and technique, L_in resolution, light type, medium (the
// extremes suite's values included), light-colour texture, AOVs, debug views, output size and
// back-buffer format.
// On the validated device (synchronization validation on) it asserts, and exits non-zero at the
// first failure: no validation message; no error from the context; L_in and T finite (read back
// every few frames); device memory flat after the first lap; host RSS growth within a bound;
// timings keep arriving.
//
//     tyndall-soak [--frames N] [--seed S] [--lap N] [--rss-bound-mib M] [--verbose]
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <unistd.h>
#include <vector>

#include "tyndall/tuning.h"
#include "tyndall/tyndall.h"
#include "tyndall_effect.h"
#include "tyndall_host/renderer.h"
#include "tyndall_host/scene.h"

namespace tyndall::samples {
namespace {

// The scenes each frame picks from: every light type, with and without a light-colour texture, and
// translucent occluders (depth-peeled layers; the profiles hand over to the Reference).
constexpr std::array<const char*, 6> kScenes = {"pillars", "stained-glass-sun", "spot-lamp", "stained-glass",
                                                "point-lamp", "analytic-glass"};
// Back buffers an engine may switch between (HDR toggle, a compute or a fragment post-process chain):
// the format and whether it has STORAGE usage (which picks the composite's compute path).
struct BackBuffer {
  VkFormat format;
  bool storage;
};
constexpr std::array<BackBuffer, 4> kBackBuffers = {BackBuffer{VK_FORMAT_R16G16B16A16_SFLOAT, true},
                                                    BackBuffer{VK_FORMAT_R16G16B16A16_SFLOAT, false},
                                                    BackBuffer{VK_FORMAT_B8G8R8A8_SRGB, false},
                                                    BackBuffer{VK_FORMAT_A2B10G10R10_UNORM_PACK32, true}};
// Small sizes keep lavapipe fast; odd ones and one under the epipolar technique's 2×2 included.
constexpr std::array<VkExtent2D, 5> kSizes = {VkExtent2D{64, 36}, VkExtent2D{48, 48}, VkExtent2D{33, 19},
                                              VkExtent2D{80, 45}, VkExtent2D{1, 1}};
constexpr std::uint32_t kShadowMapSize = 256;

// The extremes suite's media (integration-tests/extremes/test_medium_extremes.cpp): σ_t per
// channel, albedo σ_s / σ_t and the asymmetry g.
struct MediumCase {
  std::array<float, 3> extinction;
  float albedo;
  float g;
};
constexpr std::array<MediumCase, 10> kExtremeMedia = {
    MediumCase{{0.0f, 0.0f, 0.0f}, 0.8f, 0.3f},      MediumCase{{1e-6f, 1e-6f, 1e-6f}, 0.8f, 0.3f},
    MediumCase{{1e-3f, 1e-3f, 1e-3f}, 0.8f, 0.3f},   MediumCase{{0.1f, 0.1f, 0.1f}, 0.8f, 0.3f},
    MediumCase{{10.0f, 10.0f, 10.0f}, 0.8f, 0.3f},   MediumCase{{1e3f, 1e3f, 1e3f}, 0.8f, 0.3f},
    MediumCase{{0.0f, 0.05f, 0.1f}, 0.8f, 0.3f},     MediumCase{{0.05f, 0.05f, 0.05f}, 0.8f, -0.99f},
    MediumCase{{0.05f, 0.05f, 0.05f}, 0.8f, 0.0f},   MediumCase{{0.05f, 0.05f, 0.05f}, 0.8f, 0.99f}};

constexpr std::array<Profile, 5> kProfiles = {Profile::Reference, Profile::High, Profile::Balanced,
                                              Profile::Performance, Profile::Auto};

// What one frame asks of Tyndall beyond what the host's scene says.
struct FrameChoice {
  Profile profile = Profile::Balanced;
  Technique technique = Technique::None;
  std::optional<std::vector<MediumComponent>> medium;  // empty: the scene's
  float intensityScale = 1.0f;                         // 0 turns the light off
  bool lightColor = true;                              // keep the scene's colour texture
  bool scatteringAov = false;
  bool transmittanceAov = false;
  DebugView debugView = DebugView::None;
  std::optional<ScatteringResolution> resolution;      // empty: the profile's
};

// The effect in the host's post-process stack: the engine's FrameDesc, changed as `next` says.
class SoakEffect final : public host::PostProcessEffect {
 public:
  static std::unique_ptr<SoakEffect> create(host::Device& device, const host::RenderSettings& settings,
                                            std::string& error) {
    auto effect = std::unique_ptr<SoakEffect>(new SoakEffect());
    ContextDesc desc = contextDescFor(device, settings);
    desc.messageCallback = &SoakEffect::onMessage;
    desc.messageUserData = effect.get();
    Result<std::unique_ptr<Context>> context = Context::create(desc);
    if (!context) {
      error = "create: " + context.outcome().message;
      return nullptr;
    }
    effect->context_ = std::move(context).value();
    return effect;
  }

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string& error) override {
    FrameStorage storage;
    FrameDesc frame = makeFrameDesc(inputs, next.profile, storage);
    frame.technique = next.technique;
    frame.resolution = next.resolution;
    if (next.medium) frame.medium = *next.medium;
    frame.light.intensity *= next.intensityScale;
    if (!next.lightColor) frame.lightColor = {};
    if (!next.scatteringAov) frame.scatteringOutput = {};
    if (!next.transmittanceAov) frame.transmittanceOutput = {};
    if (next.debugView != DebugView::None) {
      frame.debugView = next.debugView;
      frame.debugOutput = {inputs.aovDebug.image, inputs.aovDebug.view, inputs.aovDebug.format, 0,
                           inputs.aovDebug.extent, inputs.aovDebug.layout};
    }
    if (Outcome outcome = context_->record(cmd, frame); !outcome) {
      error = std::string("record: ") + to_string(outcome.status) + ": " + outcome.message;
      return false;
    }
    return true;
  }
  bool resize(VkExtent2D extent, std::string& error) override {
    if (Outcome outcome = context_->resize(extent); !outcome) {
      error = "resize: " + outcome.message;
      return false;
    }
    return true;
  }

  Context& context() { return *context_; }
  /// Errors the context reported through its callback (warnings, e.g. a composite pipeline built
  /// for a back-buffer format met during a frame, are expected).
  std::vector<std::string> errors;
  FrameChoice next;

 private:
  static void onMessage(Severity severity, const char* message, void* user) {
    if (severity == Severity::Error) static_cast<SoakEffect*>(user)->errors.emplace_back(message);
  }
  std::unique_ptr<Context> context_;
};

std::uint64_t residentBytes() {
  std::FILE* file = std::fopen("/proc/self/statm", "r");
  if (file == nullptr) return 0;
  unsigned long long pages = 0, resident = 0;
  const int read = std::fscanf(file, "%llu %llu", &pages, &resident);
  std::fclose(file);
  return read == 2 ? resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE)) : 0;
}

double mib(std::uint64_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); }

struct Options {
  std::uint64_t frames = 300;
  std::uint64_t seed = 1;
  std::uint64_t lap = 100;          // frames per lap; device memory is compared lap to lap
  // Host RSS growth allowed after the first lap. The host stub on lavapipe grows by itself, by
  // about 0.85 MiB a frame with Tyndall or without it (scripts/soak.sh), so this bound, meant for
  // a few hundred frames, is generous; the long run passes its own.
  double rssBoundMiB = 1024.0;
  bool verbose = false;
  bool validation = true;           // off only to tell the layer's memory from Tyndall's
};

class Soak {
 public:
  explicit Soak(const Options& options) : options_(options), random_(options.seed) {}

  int run() {
    host::DeviceOptions deviceOptions;
    deviceOptions.validation = options_.validation;
    std::string error;
    device_ = host::Device::create(deviceOptions, error);
    if (!device_) return fail("device: " + error);
    for (const char* name : kScenes) {
      host::SceneLoadResult loaded = host::loadScene(std::string(TYNDALL_SCENES_DIR) + "/" + name + ".json");
      if (!loaded.scene) return fail(std::string(name) + ": " + loaded.error);
      scenes_.push_back(*loaded.scene);
    }
    host::RenderSettings base = settingsFor(kBackBuffers[0]);
    effect_ = SoakEffect::create(*device_, base, error);
    if (!effect_) return fail(error);

    const auto start = std::chrono::steady_clock::now();
    std::uint64_t frame = 0;
    std::uint64_t readBacks = 0;
    for (std::uint64_t lapIndex = 0; frame < options_.frames; ++lapIndex) {
      // Every lap starts with the same frames at the first size and back buffer: each scene with
      // each profile, the prefiltered technique, the reduced resolutions, a debug view and the
      // AOVs. Whatever the context allocates lazily exists after lap 1, so the memory measured
      // after them must not change.
      std::vector<std::tuple<std::size_t, FrameChoice>> fixed;
      for (std::size_t scene = 0; scene < scenes_.size(); ++scene) {
        // First: the maps the prefiltered technique retires here (random frames may have left it
        // with other ones) must be released by the frames of other techniques that follow.
        FrameChoice prefiltered;
        prefiltered.technique = Technique::Prefiltered;
        fixed.emplace_back(scene, prefiltered);
        // The reduced L_in targets (and the full-resolution AOV image they need), kept as spares
        // through the profile frames that follow.
        if (scene == 0) {
          for (ScatteringResolution resolution : {ScatteringResolution::Half, ScatteringResolution::Quarter}) {
            FrameChoice reduced;
            reduced.resolution = resolution;
            reduced.scatteringAov = true;
            fixed.emplace_back(scene, reduced);
          }
        }
        for (Profile profile : kProfiles) {
          FrameChoice c;
          c.profile = profile;
          c.scatteringAov = c.transmittanceAov = true;
          c.debugView = profile == Profile::High ? DebugView::EpipolarSamples : DebugView::None;
          fixed.emplace_back(scene, c);
        }
      }
      size_ = kSizes[0];
      backBuffer_ = 0;
      for (const auto& [scene, choice] : fixed) {
        if (frame >= options_.frames) break;
        if (!renderOne(scene, choice, frame, error)) return fail(error);
        ++frame;
      }
      if (frame >= options_.frames) break;
      const std::uint64_t memory = effect_->context().stats().deviceMemoryBytes;
      if (lapIndex == 1) memoryAfterFirstLap_ = memory;
      if (lapIndex >= 2 && memory != memoryAfterFirstLap_) {
        return fail("lap " + std::to_string(lapIndex + 1) + ": device memory " + std::to_string(memory) +
                    " bytes after the fixed frames, " + std::to_string(memoryAfterFirstLap_) + " in lap 2");
      }

      // The rest of the lap: random frames in one segment per back buffer (each visited once a
      // lap, in turn), each segment at a random size.
      const std::uint64_t lapEnd = std::min<std::uint64_t>(options_.frames, frame + options_.lap - fixed.size());
      const std::uint64_t segment = (options_.lap - fixed.size() + kBackBuffers.size() - 1) / kBackBuffers.size();
      std::size_t scene = pick(scenes_.size());
      for (std::uint64_t i = 0; frame < lapEnd; ++i, ++frame) {
        if (i % segment == 0) {
          backBuffer_ = static_cast<std::size_t>(i / segment) % kBackBuffers.size();
          size_ = kSizes[pick(kSizes.size())];
        }
        // A scene stays a few frames (changing it waits for the GPU: another renderer's frames).
        if (pick(3) == 0) scene = pick(scenes_.size());
        FrameChoice c = randomChoice();
        // Every 8th frame reads L_in and T back.
        const bool readBack = frame % 8 == 0;
        if (readBack) c.scatteringAov = c.transmittanceAov = true;
        if (!renderOne(scene, c, frame, error)) return fail(error);
        if (readBack) {
          if (!checkFinite(error)) return fail("frame " + std::to_string(frame) + ": " + error);
          ++readBacks;
        }
      }

      const std::uint64_t rss = residentBytes();
      std::printf("lap %llu: frame %llu, %.2f MiB device memory after the fixed frames, %.1f MiB RSS at the end\n",
                  static_cast<unsigned long long>(lapIndex + 1), static_cast<unsigned long long>(frame), mib(memory),
                  mib(rss));
      std::fflush(stdout);
      if (lapIndex == 0) rssAfterFirstLap_ = rss;
      if (rss > rssAfterFirstLap_ && mib(rss - rssAfterFirstLap_) > options_.rssBoundMiB) {
        return fail("host RSS grew by " + std::to_string(mib(rss - rssAfterFirstLap_)) + " MiB since lap 1 (bound " +
                    std::to_string(options_.rssBoundMiB) + ")");
      }
      peakRssGrowth_ = std::max<std::uint64_t>(peakRssGrowth_, rss > rssAfterFirstLap_ ? rss - rssAfterFirstLap_ : 0);
    }
    for (auto& [key, renderer] : renderers_) renderer->waitIdle();
    if (!checkValidation("the end", error)) return fail(error);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf(
        "soak: %llu frames in %.1f s (seed %llu): no validation message, %llu read-backs of L_in and T finite, "
        "device memory %.2f MiB after each lap's fixed frames from lap 2 on, host RSS growth after lap 1 at most "
        "%.1f MiB (bound %.0f), timings up to frame %llu\n",
        static_cast<unsigned long long>(frame), seconds, static_cast<unsigned long long>(options_.seed),
        static_cast<unsigned long long>(readBacks), mib(memoryAfterFirstLap_), mib(peakRssGrowth_),
        options_.rssBoundMiB, static_cast<unsigned long long>(timedFrame_));
    return 0;
  }

 private:
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(random_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(random_); }

  host::RenderSettings settingsFor(const BackBuffer& backBuffer) const {
    host::RenderSettings settings;
    settings.width = size_.width;
    settings.height = size_.height;
    settings.shadowMapSize = kShadowMapSize;
    settings.backBufferFormat = backBuffer.format;
    settings.storageBackBuffer = backBuffer.storage;
    settings.aovImages = true;
    return settings;
  }

  FrameChoice randomChoice() {
    FrameChoice c;
    c.profile = kProfiles[pick(kProfiles.size())];
    // Now and then a technique named by the frame (prefiltered falls back for spot and point lights).
    if (chance(0.2)) {
      constexpr std::array<Technique, 3> techniques = {Technique::Reference, Technique::Epipolar,
                                                       Technique::Prefiltered};
      c.technique = techniques[pick(techniques.size())];
    }
    if (chance(0.5)) {
      std::vector<MediumComponent> medium;
      const std::size_t components = 1 + pick(chance(0.7) ? 1 : kMaxMediumComponents);
      for (std::size_t i = 0; i < components; ++i) {
        const MediumCase& m = kExtremeMedia[pick(kExtremeMedia.size())];
        MediumComponent component;
        for (int ch = 0; ch < 3; ++ch) {
          component.scattering[ch] = m.extinction[ch] * m.albedo;
          component.absorption[ch] = m.extinction[ch] - component.scattering[ch];
        }
        component.phase = static_cast<PhaseFunction>(pick(4));
        component.g = m.g;
        medium.push_back(component);
      }
      c.medium = medium;
    }
    c.intensityScale = chance(0.05) ? 0.0f : 1.0f;
    c.lightColor = chance(0.6);
    c.scatteringAov = chance(0.4);
    c.transmittanceAov = chance(0.3);
    if (chance(0.15)) c.debugView = chance(0.5) ? DebugView::EpipolarSamples : DebugView::FixedUpPixels;
    if (chance(0.3)) c.resolution = chance(0.5) ? ScatteringResolution::Half : ScatteringResolution::Quarter;
    return c;
  }

  // The host renderer of a scene and back buffer, created on first use and kept (an engine keeps
  // its scenes loaded), at the current size. Switching renderers waits for the GPU: the context's
  // frame slots are shared by every renderer, whose fences only know their own frames.
  host::Renderer* rendererFor(std::size_t scene, std::string& error) {
    std::unique_ptr<host::Renderer>& renderer = renderers_[{scene, backBuffer_}];
    if (current_ != nullptr && current_ != renderer.get()) current_->waitIdle();
    if (!renderer) {
      renderer = host::Renderer::create(*device_, scenes_[scene], settingsFor(kBackBuffers[backBuffer_]), error);
      if (!renderer) return nullptr;
      renderer->addPostProcess(effect_.get());
    }
    const host::RenderSettings& settings = renderer->settings();
    if (settings.width != size_.width || settings.height != size_.height) {
      if (!renderer->resize(size_.width, size_.height, error)) return nullptr;
    }
    // A renderer created at the current size never resized the context.
    if (Outcome o = effect_->context().resize(size_); !o) {
      error = "resize: " + o.message;
      return nullptr;
    }
    current_ = renderer.get();
    return current_;
  }

  bool renderOne(std::size_t scene, const FrameChoice& choice, std::uint64_t frame, std::string& error) {
    host::Renderer* renderer = rendererFor(scene, error);
    if (renderer == nullptr) return false;
    effect_->next = choice;
    if (!renderer->renderFrame(error)) {
      error = "frame " + std::to_string(frame) + " (" + kScenes[scene] + "): " + error;
      return false;
    }
    if (!effect_->errors.empty()) {
      error = "frame " + std::to_string(frame) + ": the context reported: " + effect_->errors.front();
      return false;
    }
    if (!checkValidation("frame " + std::to_string(frame) + " (" + kScenes[scene] + ")", error)) return false;
    // Timings keep arriving: every frame collects them; a newer frame's timestamps must have
    // been read within the last 16 frames (frames in flight plus a scene switch's wait).
    Context& context = effect_->context();
    context.collectTimings();
    (void)context.takeCompletedTimings();
    const Stats& stats = context.stats();
    if (!stats.timestampsSupported) {
      error = "the device reports no timestamps";
      return false;
    }
    if (stats.timingsValid && (!timed_ || stats.lastTimings.frameIndex > timedFrame_)) {
      const double total = stats.lastTimings.totalMilliseconds;
      if (!std::isfinite(total) || total < 0.0) {
        error = "frame " + std::to_string(frame) + ": GPU time " + std::to_string(total) + " ms";
        return false;
      }
      timed_ = true;
      timedFrame_ = stats.lastTimings.frameIndex;
      lastNewTimings_ = stats.frameIndex;
    }
    if (stats.frameIndex > lastNewTimings_ + 16) {
      error = "frame " + std::to_string(frame) + ": no new timings since context frame " +
              std::to_string(lastNewTimings_);
      return false;
    }
    if (options_.verbose) {
      std::printf("frame %llu: %s %ux%u fmt %d, %s/%s, %s\n", static_cast<unsigned long long>(frame), kScenes[scene],
                  size_.width, size_.height, static_cast<int>(kBackBuffers[backBuffer_].format),
                  to_string(stats.profileUsed), to_string(stats.technique), stats.techniqueNote.c_str());
    }
    return true;
  }

  bool checkFinite(std::string& error) {
    host::ImageRgba32f scattering, transmittance;
    if (!current_->readAovScattering(scattering, error) || !current_->readAovTransmittance(transmittance, error)) {
      return false;
    }
    for (const host::ImageRgba32f* image : {&scattering, &transmittance}) {
      for (std::size_t i = 0; i < image->pixels.size(); ++i) {
        if (!std::isfinite(image->pixels[i])) {
          error = std::string(image == &scattering ? "L_in" : "T") + " not finite at pixel " + std::to_string(i / 4) +
                  " (" + effect_->context().stats().techniqueNote + ")";
          return false;
        }
      }
    }
    return true;
  }

  bool checkValidation(const std::string& where, std::string& error) {
    const std::vector<std::string>& messages = device_->validationMessages();
    if (messages.empty()) return true;
    error = where + ": " + std::to_string(messages.size()) + " validation message(s); first: " + messages.front();
    return false;
  }

  int fail(const std::string& error) {
    std::fprintf(stderr, "tyndall-soak: %s\n", error.c_str());
    return 1;
  }

  Options options_;
  std::mt19937_64 random_;
  std::unique_ptr<host::Device> device_;
  std::vector<host::Scene> scenes_;
  std::unique_ptr<SoakEffect> effect_;
  std::map<std::tuple<std::size_t, std::size_t>, std::unique_ptr<host::Renderer>> renderers_;
  host::Renderer* current_ = nullptr;
  VkExtent2D size_ = kSizes[0];
  std::size_t backBuffer_ = 0;
  std::uint64_t memoryAfterFirstLap_ = 0;
  std::uint64_t rssAfterFirstLap_ = 0;
  std::uint64_t peakRssGrowth_ = 0;
  bool timed_ = false;
  std::uint64_t timedFrame_ = 0;
  std::uint64_t lastNewTimings_ = 0;
};

bool parse(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--frames" && hasValue) {
      options.frames = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--seed" && hasValue) {
      options.seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--lap" && hasValue) {
      options.lap = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--rss-bound-mib" && hasValue) {
      options.rssBoundMiB = std::strtod(argv[++i], nullptr);
    } else if (arg == "--verbose") {
      options.verbose = true;
    } else if (arg == "--no-validation") {
      options.validation = false;
    } else {
      return false;
    }
  }
  // A lap holds the fixed frames (6 per scene, 2 more for the first) and at least as many random ones.
  return options.frames > 0 && options.lap >= 2 * (6 * kScenes.size() + 2);
}

}  // namespace
}  // namespace tyndall::samples

int main(int argc, char** argv) {
  tyndall::samples::Options options;
  if (!tyndall::samples::parse(argc, argv, options)) {
    std::fprintf(stderr,
                 "usage: tyndall-soak [--frames N] [--seed S] [--lap N (>= 64)] [--rss-bound-mib M] [--verbose]\n");
    return 2;
  }
  return tyndall::samples::Soak(options).run();
}
