#include "render_job.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "error_metrics.h"
#include "settings_text.h"
#include "tyndall_effect.h"

namespace tyndall::samples {

namespace {

// An option's names for the values it picks: the library's where it has them.
const char* optionName(Profile profile) { return to_string(profile); }
const char* optionName(Technique technique) { return to_string(technique); }
const char* optionName(ScatteringResolution resolution) { return to_string(resolution); }
const char* optionName(PipelineCreation creation) {
  return creation == PipelineCreation::AtCreate ? "at-create" : "on-first-use";
}

// The value among `values` named `name`, for the options that pick one by name.
template <typename E>
bool parseName(const std::string& name, std::initializer_list<E> values, E& out) {
  for (E value : values) {
    if (name == optionName(value)) {
      out = value;
      return true;
    }
  }
  return false;
}

}  // namespace

std::string usage() {
  return "usage: tyndall-render SCENE.json [--profile reference|high|balanced|performance|auto] [--budget-ms B]\n"
         "         [--technique reference|epipolar|prefiltered] [--width W] [--height H] [--shadow-map-size N]\n"
         "         [--cascades K] [--translucent-layers N]\n"
         "         [--output FILE.png] [--output-hdr FILE.exr] [--aov-scattering FILE.exr]\n"
         "         [--aov-transmittance FILE.exr] [--timings FILE.json] [--frames N]\n"
         "         [--reverse-z] [--infinite-far] [--validation] [--no-effect] [--no-storage-back-buffer]\n"
         "         [--epipolar KEY=VALUE[,KEY=VALUE...]] [--prefiltered KEY=VALUE[,KEY=VALUE...]]\n"
         "         [--debug-view samples|fixup FILE.png] [--march-threads N] [--pipelines at-create|on-first-use]\n"
         "         [--resolution full|half|quarter]\n"
         "  --resolution: compute L_in at full, half or quarter resolution instead of the profile's (the\n"
         "    composite upsamples it; the Reference always runs at full)\n"
         "  --cascades: shadow maps per directional light, 1 to 4 cascades splitting the view depths\n"
         "    (overrides the scene's \"shadowMap\": {\"cascades\": K}; spot and point lights keep one map)\n"
         "  --translucent-layers: depth-peeled layers of translucent objects per shadow map, 1 to 8\n"
         "    (default 4; a texel with more surfaces sets stats.translucentLayersOverflowed)\n"
         "  --budget-ms: Tyndall's GPU-time budget for --profile auto in milliseconds (default 4)\n"
         "  --no-storage-back-buffer: create the back buffer without STORAGE usage, so Tyndall composites\n"
         "    with a fragment pass instead of a compute pass writing the back buffer in place\n"
         "  --pipelines: compile every technique's pipelines when the context is created (at-create, the\n"
         "    default: no frame compiles one) or each technique's in the first frame that runs it\n"
         "    (on-first-use: a faster start for scripts that render one technique; GPU timings unchanged,\n"
         "    the compile is on the CPU before the frame is submitted)\n"
         "  --march-threads: threads per marched epipolar sample, a power of two up to 64 (default: 1 on a\n"
         "    CPU driver, 8 on a GPU; ContextDesc::marchThreadsPerSample); with 1 the fix-up walks a\n"
         "    directional light's pixels one per thread, otherwise each in a workgroup of 64\n"
         "  --epipolar sets the epipolar technique's parameters (the rest keep EpipolarSettings' defaults):\n"
         "    " + std::string(kEpipolarKeys) + "\n"
         "  --prefiltered sets the prefiltered technique's parameters (the rest keep PrefilteredSettings' defaults):\n"
         "    " + kPrefilteredKeys + "\n";
}

bool parseCommandLine(int argc, const char* const* argv, RenderOptions& options, bool& help, std::string& error) {
  help = false;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= args.size()) {
        error = arg + " needs a value";
        return false;
      }
      out = args[++i];
      return true;
    };
    std::string v;
    if (arg == "--help" || arg == "-h") {
      help = true;
      return true;
    } else if (arg == "--profile") {
      if (!value(v)) return false;
      if (!parseName(v, {Profile::Reference, Profile::High, Profile::Balanced, Profile::Performance, Profile::Auto},
                     options.profile)) {
        error = "--profile must be one of reference, high, balanced, performance, auto (got '" + v + "')";
        return false;
      }
    } else if (arg == "--budget-ms") {
      if (!value(v)) return false;
      if (!parseFloat(v, options.autoBudgetMilliseconds) || !(options.autoBudgetMilliseconds > 0.0f) ||
          !std::isfinite(options.autoBudgetMilliseconds)) {
        error = "--budget-ms must be a number > 0 (got '" + v + "')";
        return false;
      }
    } else if (arg == "--technique") {
      if (!value(v)) return false;
      if (!parseName(v, {Technique::Reference, Technique::Epipolar, Technique::Prefiltered}, options.technique)) {
        error = "--technique must be one of: reference, epipolar, prefiltered (got '" + v + "')";
        return false;
      }
    } else if (arg == "--width" || arg == "--height") {
      if (!value(v)) return false;
      std::uint32_t& target = arg == "--width" ? options.width : options.height;
      if (!parseUint(v, 1, 16384, target)) {
        error = arg + " must be an integer in [1, 16384] (got '" + v + "')";
        return false;
      }
    } else if (arg == "--shadow-map-size") {
      if (!value(v)) return false;
      if (!parseUint(v, 16, 16384, options.shadowMapSize) || (options.shadowMapSize & (options.shadowMapSize - 1)) != 0) {
        error = "--shadow-map-size must be a power of two in [16, 16384] (got '" + v + "')";
        return false;
      }
    } else if (arg == "--cascades") {
      if (!value(v)) return false;
      if (!parseUint(v, 1, host::kMaxSceneCascades, options.cascades)) {
        error = "--cascades must be an integer in [1, 4] (got '" + v + "')";
        return false;
      }
    } else if (arg == "--translucent-layers") {
      if (!value(v)) return false;
      if (!parseUint(v, 1, host::kMaxTranslucentLayers, options.translucentLayers)) {
        error = "--translucent-layers must be an integer in [1, 8] (got '" + v + "')";
        return false;
      }
    } else if (arg == "--resolution") {
      if (!value(v)) return false;
      ScatteringResolution resolution{};
      if (!parseName(v, {ScatteringResolution::Full, ScatteringResolution::Half, ScatteringResolution::Quarter},
                     resolution)) {
        error = "--resolution must be one of: full, half, quarter (got '" + v + "')";
        return false;
      }
      options.resolution = resolution;
    } else if (arg == "--march-threads") {
      if (!value(v)) return false;
      if (!parseUint(v, 1, 64, options.marchThreadsPerSample) ||
          (options.marchThreadsPerSample & (options.marchThreadsPerSample - 1)) != 0) {
        error = "--march-threads must be a power of two in [1, 64] (got '" + v + "')";
        return false;
      }
    } else if (arg == "--pipelines") {
      if (!value(v)) return false;
      if (!parseName(v, {PipelineCreation::AtCreate, PipelineCreation::OnFirstUse}, options.pipelineCreation)) {
        error = "--pipelines must be at-create or on-first-use (got '" + v + "')";
        return false;
      }
    } else if (arg == "--frames") {
      if (!value(v)) return false;
      if (!parseUint(v, 1, 100000, options.frames)) {
        error = "--frames must be an integer in [1, 100000] (got '" + v + "')";
        return false;
      }
    } else if (arg == "--output") {
      if (!value(options.outputPng)) return false;
    } else if (arg == "--output-hdr") {
      if (!value(options.outputExr)) return false;
    } else if (arg == "--aov-scattering") {
      if (!value(options.aovScattering)) return false;
    } else if (arg == "--aov-transmittance") {
      if (!value(options.aovTransmittance)) return false;
    } else if (arg == "--timings") {
      if (!value(options.timings)) return false;
    } else if (arg == "--reverse-z") {
      options.depth = host::DepthConvention::Reverse;
    } else if (arg == "--infinite-far") {
      options.infiniteFar = true;
    } else if (arg == "--validation") {
      options.validation = true;
    } else if (arg == "--epipolar") {
      if (!value(v)) return false;
      EpipolarSettings settings;
      if (!parseEpipolarSettings(v, settings, error)) return false;
      options.epipolar = settings;
    } else if (arg == "--debug-view") {
      if (!value(v)) return false;
      if (v == "samples") {
        options.debugView = DebugView::EpipolarSamples;
      } else if (v == "fixup") {
        options.debugView = DebugView::FixedUpPixels;
      } else {
        error = "--debug-view must be one of: samples, fixup (got '" + v + "')";
        return false;
      }
      if (!value(options.debugViewPng)) return false;
    } else if (arg == "--prefiltered") {
      if (!value(v)) return false;
      PrefilteredSettings settings;
      if (!parsePrefilteredSettings(v, settings, error)) return false;
      options.prefiltered = settings;
    } else if (arg == "--no-effect") {
      options.noEffect = true;
    } else if (arg == "--no-storage-back-buffer") {
      options.storageBackBuffer = false;
    } else if (!arg.empty() && arg[0] == '-') {
      error = "unknown option " + arg;
      return false;
    } else if (options.scenePath.empty()) {
      options.scenePath = arg;
    } else {
      error = "only one scene file may be given (got '" + options.scenePath + "' and '" + arg + "')";
      return false;
    }
  }
  if (options.scenePath.empty()) {
    error = "no scene file given";
    return false;
  }
  return true;
}

host::RenderSettings renderSettingsFor(const RenderOptions& options, bool wantAovs) {
  host::RenderSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  settings.shadowMapSize = options.shadowMapSize;
  settings.cascades = options.cascades;
  settings.translucentLayers = options.translucentLayers;
  settings.depth = options.depth;
  settings.infiniteFar = options.infiniteFar;
  settings.aovImages = wantAovs || !options.aovScattering.empty() || !options.aovTransmittance.empty() ||
                       options.debugView != DebugView::None;
  settings.backBufferFormat = options.backBufferFormat;
  settings.framesInFlight = options.framesInFlight;
  settings.storageBackBuffer = options.storageBackBuffer;
  return settings;
}

namespace {

// renderScene with `effect` (null: none, the host alone), set up from the options.
bool renderSceneWith(host::Device& device, const host::Scene& scene, const RenderOptions& options, bool wantAovs,
                     TyndallEffect* effect, RenderResult& result, std::string& error) {
  const host::RenderSettings settings = renderSettingsFor(options, wantAovs);
  const bool aovs = settings.aovImages;
  std::unique_ptr<host::Renderer> renderer = host::Renderer::create(device, scene, settings, error);
  if (!renderer) return false;
  if (effect) {
    effect->setProfile(options.profile);
    effect->setAutoBudget(options.autoBudgetMilliseconds);
    effect->setTechnique(options.technique);
    effect->setEpipolarSettings(options.epipolar);
    effect->setResolution(options.resolution);
    effect->setDebugView(options.debugView);
    effect->setPrefilteredSettings(options.prefiltered);
    renderer->addPostProcess(effect);
  }

  using Clock = std::chrono::steady_clock;
  Clock::time_point start = Clock::now();
  for (std::uint32_t frame = 0; frame < options.frames; ++frame) {
    // The AOVs are read from the last frame only; the frames before it are timed without the copy.
    if (effect) effect->setAovOutputs(frame + 1 == options.frames);
    if (!renderer->renderFrame(error)) {
      renderer->waitIdle();  // the context and the renderer are destroyed next
      return false;
    }
    if (frame == 0 && options.frames > 1) {
      // Frame 1 pays for first-use costs; the wall clock starts once it is done.
      renderer->waitIdle();
      start = Clock::now();
    }
  }
  renderer->waitIdle();
  const double wallMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  result.wallMillisecondsPerFrame = wallMs / (options.frames > 1 ? options.frames - 1 : 1);
  result.deviceName = device.name();
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device.physicalDevice(), &properties);
  result.cpuDevice = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  if (effect) {
    effect->context().collectTimings();
    result.stats = effect->context().stats();
    result.timings = effect->context().takeCompletedTimings();
  }
  if (!renderer->readBackBuffer(result.color, error)) return false;
  if (aovs) {
    if (!renderer->readAovScattering(result.scattering, error)) return false;
    if (!renderer->readAovTransmittance(result.transmittance, error)) return false;
  }
  if (options.debugView != DebugView::None && !renderer->readAovDebug(result.debugView, error)) return false;
  return true;
}

}  // namespace

bool renderScene(host::Device& device, const host::Scene& scene, const RenderOptions& options, bool wantAovs,
                 RenderResult& result, std::string& error) {
  std::unique_ptr<TyndallEffect> effect;
  if (!options.noEffect) {
    effect = TyndallEffect::create(device, renderSettingsFor(options, wantAovs), options.profile, error,
                                   options.pipelineCreation, options.marchThreadsPerSample, options.fullFloatTargets);
    if (!effect) return false;
  }
  return renderSceneWith(device, scene, options, wantAovs, effect.get(), result, error);
}

bool renderScene(host::Device& device, const host::Scene& scene, const RenderOptions& options, bool wantAovs,
                 TyndallEffect& effect, RenderResult& result, std::string& error) {
  if (options.noEffect) {
    error = "renderScene: an effect was given to a render without one (noEffect)";
    return false;
  }
  return renderSceneWith(device, scene, options, wantAovs, &effect, result, error);
}

std::optional<std::size_t> passLight(const std::string& pass) {
  constexpr std::size_t kDigits = 5;  // after "light"
  const std::size_t slash = pass.find('/');
  if (pass.rfind("light", 0) != 0 || slash == std::string::npos || slash == kDigits) return std::nullopt;
  std::size_t index = 0;
  for (std::size_t i = kDigits; i < slash; ++i) {
    if (pass[i] < '0' || pass[i] > '9') return std::nullopt;
    index = index * 10 + static_cast<std::size_t>(pass[i] - '0');
  }
  return index;
}

std::string timingsJson(const RenderOptions& options, const RenderResult& result) {
  std::map<std::string, std::vector<double>> perPass;
  std::vector<double> totals;
  for (const FrameTimings& frame : result.timings) {
    for (const PassTiming& pass : frame.passes) perPass[pass.name].push_back(pass.milliseconds);
    totals.push_back(frame.totalMilliseconds);
  }
  nlohmann::ordered_json json;
  json["device"] = result.deviceName;
  json["scene"] = options.scenePath;
  json["profile"] = to_string(options.profile);
  json["profileUsed"] = to_string(result.stats.profileUsed);
  json["technique"] = to_string(result.stats.technique);
  json["requestedTechnique"] = to_string(result.stats.requestedTechnique);
  json["techniqueChange"] = to_string(result.stats.techniqueChange);
  json["techniqueNote"] = result.stats.techniqueNote;
  json["width"] = options.width;
  json["height"] = options.height;
  json["framesRendered"] = options.frames;
  json["framesTimed"] = result.timings.size();
  json["timestampsSupported"] = result.stats.timestampsSupported;
  json["passesRecorded"] = result.stats.passesRecorded;
  json["composite"] = to_string(result.stats.composite);
  json["scatteringResolution"] = to_string(result.stats.scatteringResolution);
  json["resolutionChange"] = to_string(result.stats.resolutionChange);
  json["scatteringFormat"] = result.stats.scatteringFormat == VK_FORMAT_R16G16B16A16_SFLOAT   ? "R16G16B16A16_SFLOAT"
                             : result.stats.scatteringFormat == VK_FORMAT_R32G32B32A32_SFLOAT ? "R32G32B32A32_SFLOAT"
                                                                                              : "none";
  json["dispatches"] = result.stats.dispatches;
  json["barriers"] = result.stats.barriers;
  if (!result.stats.lights.empty() && result.stats.lights[0].translucentLayers > 0) {
    json["translucentLayers"] = result.stats.lights[0].translucentLayers;
    json["translucentLayersOverflowed"] = result.stats.translucentLayersOverflowed;  // from an earlier frame
  }
  nlohmann::ordered_json passes = nlohmann::ordered_json::object();
  // In recording order of the last frame.
  for (const std::string& name : result.stats.passesRecorded) {
    if (perPass.contains(name)) passes[name] = median(perPass[name]);
  }
  json["passMilliseconds"] = passes;
  // A frame of several lights names each light's passes "lightI/…": each light's share, the sum of
  // its passes' medians (the shared composite and AOV copies belong to none).
  if (result.stats.lights.size() > 1) {
    std::vector<double> perLight(result.stats.lights.size(), 0.0);
    for (const auto& [name, ms] : passes.items()) {
      const std::optional<std::size_t> light = passLight(name);
      if (light && *light < perLight.size()) perLight[*light] += ms.get<double>();
    }
    json["lightMilliseconds"] = perLight;
  }
  if (const std::optional<EpipolarCounts>& counts = result.stats.epipolarCounts;
      result.stats.technique == Technique::Epipolar && counts) {
    json["marchedSamples"] = counts->marchedSamples;
    json["shadowedSamples"] = counts->shadowedSamples;
    json["fixedUpPixelFraction"] = counts->fixedUpPixelFraction;
  }
  json["totalMilliseconds"] = median(totals);
  json["deviceMemoryBytes"] = result.stats.deviceMemoryBytes;
  json["wallMillisecondsPerFrame"] = result.wallMillisecondsPerFrame;
  json["tyndallInserted"] = !options.noEffect;
  return json.dump(2) + "\n";
}

namespace {

void makeParent(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
}

}  // namespace

bool writeFileWhole(const std::string& path, const std::string& text, std::string& error) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream file(tmp, std::ios::binary);
    file << text;
    if (!file) {
      error = "cannot write " + path;
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    error = "cannot write " + path + ": " + ec.message();
    return false;
  }
  return true;
}

bool writeOutputs(const RenderOptions& options, const RenderResult& result, std::string& error) {
  for (const std::string* path : {&options.outputPng, &options.outputExr, &options.aovScattering,
                                  &options.aovTransmittance, &options.timings, &options.debugViewPng}) {
    if (!path->empty()) makeParent(*path);
  }
  if (!options.outputPng.empty()) {
    std::vector<std::uint8_t> rgba8;
    if (!host::displayToSrgb8(result.color, rgba8, error)) return false;
    if (!host::writePng(options.outputPng, result.color.width, result.color.height, rgba8, error)) return false;
  }
  if (!options.outputExr.empty() && !host::writeExr(options.outputExr, result.color, error)) return false;
  if (!options.aovScattering.empty() && !host::writeExr(options.aovScattering, result.scattering, error)) return false;
  if (!options.aovTransmittance.empty() && !host::writeExr(options.aovTransmittance, result.transmittance, error)) {
    return false;
  }
  if (!options.debugViewPng.empty()) {
    // A false-colour chart, not a picture: its values go to 8 bits as they are.
    const host::ImageRgba32f& view = result.debugView;
    std::vector<std::uint8_t> rgba8(view.pixels.size());
    for (std::size_t i = 0; i < rgba8.size(); ++i) {
      rgba8[i] = static_cast<std::uint8_t>(std::lround(std::clamp(view.pixels[i], 0.0f, 1.0f) * 255.0f));
    }
    if (!host::writePng(options.debugViewPng, view.width, view.height, rgba8, error)) return false;
  }
  if (!options.timings.empty() && !writeFileWhole(options.timings, timingsJson(options, result), error)) return false;
  return true;
}

int runTyndallRender(int argc, const char* const* argv) {
  RenderOptions options;
  bool help = false;
  std::string error;
  if (!parseCommandLine(argc, argv, options, help, error)) {
    std::fprintf(stderr, "tyndall-render: %s\n", error.c_str());
    return 2;
  }
  if (help) {
    std::fputs(usage().c_str(), stdout);
    return 0;
  }
  host::SceneLoadResult loaded = host::loadScene(options.scenePath);
  if (!loaded.scene) {
    std::fprintf(stderr, "tyndall-render: %s: %s\n", options.scenePath.c_str(), loaded.error.c_str());
    return 1;
  }
  host::DeviceOptions deviceOptions;
  deviceOptions.validation = options.validation;
  std::unique_ptr<host::Device> device = host::Device::create(deviceOptions, error);
  if (!device) {
    std::fprintf(stderr, "tyndall-render: %s\n", error.c_str());
    return 1;
  }
  RenderResult result;
  if (!renderScene(*device, *loaded.scene, options, false, result, error)) {
    std::fprintf(stderr, "tyndall-render: %s\n", error.c_str());
    return 1;
  }
  if (options.validation && !device->validationMessages().empty()) {
    std::fprintf(stderr, "tyndall-render: %zu validation message(s), first: %s\n",
                 device->validationMessages().size(), device->validationMessages().front().c_str());
    return 1;
  }
  if (!writeOutputs(options, result, error)) {
    std::fprintf(stderr, "tyndall-render: %s\n", error.c_str());
    return 1;
  }
  std::fputs(timingsJson(options, result).c_str(), stdout);
  return 0;
}

}  // namespace tyndall::samples
