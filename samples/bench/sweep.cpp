#include "sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "error_metrics.h"
#include "floor_pass.h"
#include "render_job.h"
#include "settings_text.h"
#include "tyndall_effect.h"

namespace tyndall::samples::bench {

const char* lightName(host::LightType type) {
  switch (type) {
    case host::LightType::Directional: return "directional";
    case host::LightType::Spot: return "spot";
    case host::LightType::Point: return "point";
  }
  return "point";
}

std::string configurationName(const std::string& technique, const std::string& parameters) {
  return technique == to_string(Technique::Reference) ? technique : technique + " " + parameters;
}

std::string Configuration::techniqueName() const { return to_string(technique); }

std::string Configuration::parameters() const {
  if (technique == Technique::Epipolar) return describe(epipolar.value_or(EpipolarSettings{}));
  if (technique == Technique::Prefiltered) return describe(prefiltered.value_or(PrefilteredSettings{}));
  return "-";
}

std::string Configuration::name() const { return configurationName(techniqueName(), parameters()); }

bool parseConfiguration(const std::string& text, Configuration& out, std::string& error) {
  const std::size_t colon = text.find(':');
  const std::string technique = text.substr(0, colon);
  const std::string parameters = colon == std::string::npos ? std::string() : text.substr(colon + 1);
  Configuration c;
  if (technique == "reference" && parameters.empty()) {
    c.technique = Technique::Reference;
  } else if (technique == "epipolar") {
    c.technique = Technique::Epipolar;
    EpipolarSettings s;
    if (!parameters.empty() && !parseEpipolarSettings(parameters, s, error)) return false;
    c.epipolar = s;
  } else if (technique == "prefiltered") {
    c.technique = Technique::Prefiltered;
    PrefilteredSettings s;
    if (!parameters.empty() && !parsePrefilteredSettings(parameters, s, error)) return false;
    c.prefiltered = s;
  } else {
    error = "a configuration is reference, epipolar:KEY=VALUE,... or prefiltered:KEY=VALUE,... (got '" + text + "')";
    return false;
  }
  out = c;
  return true;
}

bool builtInGrid(const std::string& name, std::vector<Configuration>& out, std::string& error) {
  std::vector<std::string> texts;
  if (name == "default" || name == "full") {
    // Epipolar: slices set the resolution across shafts, samples along them, the intensity
    // refinement how many extra samples shaft edges get (docs/EPIPOLAR.md); "full" adds a longer
    // initial step. 128 slices go with 128 or 256 samples (the cheapest corner, for Performance),
    // the others with 256 or 512.
    for (const char* slices : {"128", "256", "512", "1024"}) {
      const bool cheapest = std::string(slices) == "128";
      for (const char* samples : {cheapest ? "128" : "256", cheapest ? "256" : "512"}) {
        std::vector<const char*> marches{"intensity-refinement=0.2", "intensity-refinement=0.15"};
        if (name == "full") marches.push_back("initial-step=32,intensity-refinement=0.2");
        for (const char* march : marches) {
          texts.push_back(std::string("epipolar:slices=") + slices + ",samples=" + samples + "," + march);
        }
      }
    }
    // The fix-up's stepped march (fixup-steps) on the cheaper corners, where the exact walk of the
    // fixed-up pixels is a large part of the frame (forest's fix-up at Performance).
    for (const char* stepped : {"slices=128,samples=128,intensity-refinement=0.15,fixup-steps=32",
                                "slices=128,samples=128,intensity-refinement=0.15,fixup-steps=64",
                                "slices=256,samples=256,intensity-refinement=0.15,fixup-steps=64"}) {
      texts.push_back(std::string("epipolar:") + stepped);
    }
    // L_in at reduced resolution (upsampled by the composite): the unwarp, the fix-up and the
    // prefiltered evaluation run per 2×2 or 4×4 block, for shafts wider than a block.
    for (const char* reduced : {"slices=128,samples=128,intensity-refinement=0.15,fixup-steps=64,resolution=half",
                                "slices=128,samples=128,intensity-refinement=0.15,fixup-steps=64,resolution=quarter",
                                "slices=256,samples=256,intensity-refinement=0.15,resolution=half",
                                "slices=512,samples=256,intensity-refinement=0.15,resolution=half"}) {
      texts.push_back(std::string("epipolar:") + reduced);
    }
    // Prefiltered: the recommended 6-moment variant, the cheapest 4-moment one and the Fourier
    // baseline at the default rectified size, the default at a quarter of the texels, and two
    // segments with 16 walk steps (as accurate as the defaults for 15% less evaluation on lavapipe,
    // docs/PREFILTERED.md "Fewer taps, more steps": a candidate default for a GPU's sweep to
    // weigh); "full": every storage variant and a sixteenth.
    std::vector<const char*> prefiltered{"basis=moments6_64", "basis=moments4_64", "basis=fourier32",
                                         "rows=512,columns=512", "taps=2,texel-walk=16", "resolution=half"};
    if (name == "full") {
      for (const char* more : {"basis=moments4_128", "basis=moments6_96", "basis=moments6_192", "rows=256,columns=256"}) {
        prefiltered.push_back(more);
      }
    }
    for (const char* p : prefiltered) texts.push_back(std::string("prefiltered:") + p);
  } else if (name == "quick") {
    texts = {"epipolar:slices=256,samples=256", "prefiltered:rows=256,columns=256"};
  } else if (name != "none") {
    error = "--grid must be default, full, quick or none (got '" + name + "')";
    return false;
  }
  for (const std::string& text : texts) {
    Configuration c;
    if (!parseConfiguration(text, c, error)) return false;
    out.push_back(c);
  }
  return true;
}

namespace {

// Mean |a − b| over the RGB values of two images of one size.
double meanAbsoluteChange(const host::ImageRgba32f& a, const host::ImageRgba32f& b) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = static_cast<double>(a.pixels[i]) - static_cast<double>(b.pixels[i]);
    if (std::isfinite(d)) {
      sum += std::abs(d);
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

// The scene's camera turned by `degrees` about the vertical axis through its target: a slow orbit.
host::Camera orbit(const host::Camera& camera, double degrees) {
  const double a = degrees * M_PI / 180.0;
  const glm::dvec3 axis = glm::normalize(camera.up);
  const glm::dvec3 v = camera.position - camera.target;
  // Rodrigues' rotation of v about the axis.
  const glm::dvec3 rotated =
      v * std::cos(a) + glm::cross(axis, v) * std::sin(a) + axis * glm::dot(axis, v) * (1.0 - std::cos(a));
  host::Camera out = camera;
  out.position = camera.target + rotated;
  return out;
}

// What one configuration (or a floor pass) produced on one scene.
struct Measurement {
  std::vector<double> totals;
  std::map<std::string, std::vector<double>> passes;
  Stats stats;
  host::ImageRgba32f scattering;  // L_in of the last timed frame (the scene's camera)
  double temporalChange = 0.0;    // mean |ΔL_in| per orbit frame (absolute)
};

// One thing measured in a group: a floor pass (no configuration), the Reference or a
// configuration, each with its own renderer and effect (a Tyndall context per configuration: its
// memory and pipelines are the configuration's alone), open from its first frame to its last.
struct Subject {
  std::string name;
  std::optional<Configuration> configuration;
  FloorKind floorKind = FloorKind::Fragment;  // without a configuration: which floor
  std::unique_ptr<FloorPass> floor;
  std::unique_ptr<TyndallEffect> tyndall;
  std::unique_ptr<host::Renderer> renderer;
  Measurement run;
};

class Sweep {
 public:
  Sweep(const SweepOptions& options, host::Device& device) : options_(options), device_(device) {}

  bool run(std::vector<Row>& rows, std::string& error) {
    // Progress in frames of every subject, the readbacks and orbits counted as one frame each.
    const std::size_t groups = options_.scenes.size() * options_.sizes.size() * options_.shadowMaps.size();
    unitsTotal_ = groups * (options_.configurations.size() + 3) * (options_.warmUpFrames + options_.frames + 1);
    start_ = std::chrono::steady_clock::now();
    for (const std::string& path : options_.scenes) {
      host::SceneLoadResult loaded = host::loadScene(path);
      if (!loaded.scene) {
        error = path + ": " + loaded.error;
        return false;
      }
      const std::string stem = std::filesystem::path(path).stem().string();
      for (const auto& [width, height] : options_.sizes) {
        for (std::uint32_t map : options_.shadowMaps) {
          if (!runGroup(*loaded.scene, stem, width, height, map, rows, error)) return false;
          if (options_.groupDone) options_.groupDone(rows);
        }
      }
    }
    return true;
  }

 private:
  bool runGroup(const host::Scene& scene, const std::string& stem, std::uint32_t width, std::uint32_t height,
                std::uint32_t map, std::vector<Row>& rows, std::string& error) {
    RenderOptions render;
    render.width = width;
    render.height = height;
    render.shadowMapSize = map;
    render.pipelineCreation = PipelineCreation::OnFirstUse;  // a context per configuration compiles only its own
    render.storageBackBuffer = options_.storageBackBuffer;
    const host::RenderSettings settings = renderSettingsFor(render, true);
    const std::string computeFloorNote = computeFloorUnavailable(device_, settings);
    const std::string where = stem + " " + std::to_string(width) + "x" + std::to_string(height) + " " +
                              std::to_string(map) + "²";

    const Configuration referenceConfig;
    Row base;
    base.scene = stem;
    // A scene of several lights belongs to neither kind's profile row: "several".
    base.light = scene.additionalLights.empty() ? lightName(scene.light.type) : "several";
    base.width = width;
    base.height = height;
    base.shadowMap = map;

    // Subject 0: the fragment floor, the cheapest fragment post-process at this size; 1: the
    // Reference; then the compute floor where the back buffer allows it (computeFloor); then the
    // configurations this scene's light allows (`configurations[k]` is subject measured[k], or
    // none when skipped).
    std::vector<Subject> subjects(2);
    subjects[0].name = "floor pass";
    subjects[1].name = referenceConfig.name();
    subjects[1].configuration = referenceConfig;
    std::optional<std::size_t> computeFloor;
    if (computeFloorNote.empty()) {
      computeFloor = subjects.size();
      subjects.emplace_back();
      subjects.back().name = "compute floor pass";
      subjects.back().floorKind = FloorKind::Compute;
    } else {
      unitsDone_ += options_.warmUpFrames + options_.frames + 1;
    }
    // The prefiltered technique takes directional lights only: every light of the scene must be one.
    bool onlyDirectional = scene.light.type == host::LightType::Directional;
    for (const host::Light& light : scene.additionalLights) {
      onlyDirectional = onlyDirectional && light.type == host::LightType::Directional;
    }
    std::vector<std::optional<std::size_t>> measured;
    for (const Configuration& config : options_.configurations) {
      if (config.technique == Technique::Prefiltered && !onlyDirectional) {
        measured.emplace_back();
        unitsDone_ += options_.warmUpFrames + options_.frames + 1;
        continue;
      }
      measured.emplace_back(subjects.size());
      subjects.emplace_back();
      subjects.back().name = config.name();
      subjects.back().configuration = config;
    }
    if (options_.interleaved) {
      // Every subject alive at once: the group's memory is the sum of theirs.
      for (Subject& subject : subjects) {
        if (!open(scene, settings, subject, error)) {
          error = where + " " + subject.name + ": " + error + " (" + std::to_string(subjects.size()) +
                  " contexts at once; --sequential keeps one alive at a time)";
          return false;
        }
      }
      std::vector<Subject*> all;
      for (Subject& subject : subjects) all.push_back(&subject);
      if (!timeFrames(where, all, error)) return false;
      for (Subject& subject : subjects) {
        if (!finish(where, scene, subject, error)) return false;
      }
    } else {
      for (Subject& subject : subjects) {
        std::vector<Subject*> one{&subject};
        if (!open(scene, settings, subject, error)) {
          error = where + " " + subject.name + ": " + error;
          return false;
        }
        if (!timeFrames(where, one, error) || !finish(where, scene, subject, error)) return false;
      }
    }

    base.floorMilliseconds = median(subjects[0].run.totals);
    progress(where + " floor pass: " + formatMs(base.floorMilliseconds));
    if (computeFloor) {
      base.computeFloorMilliseconds = median(subjects[*computeFloor].run.totals);
      progress(where + " compute floor pass: " + formatMs(base.computeFloorMilliseconds));
    } else {
      base.computeFloorNote = "compute floor not measured: " + computeFloorNote;
      progress(where + " " + base.computeFloorNote);
    }
    const Measurement& reference = subjects[1].run;
    base.referenceMilliseconds = median(reference.totals);
    const ErrorStats referenceScale = compareRgb(reference.scattering, reference.scattering);
    const double meanReference = referenceScale.meanReference;
    const double referenceChange = meanReference > 0.0 ? reference.temporalChange / meanReference : 0.0;
    {
      Row row = base;
      fill(row, referenceConfig, reference);
      row.temporalChange = referenceChange;
      row.temporalRatio = 1.0;
      rows.push_back(row);
      progress(where + " " + describeRow(row));
    }

    for (std::size_t k = 0; k < options_.configurations.size(); ++k) {
      const Configuration& config = options_.configurations[k];
      Row row = base;
      row.configuration = config.name();
      row.technique = config.techniqueName();
      row.parameters = config.parameters();
      if (!measured[k]) {
        row.note = "prefiltered: directional lights only (a profile runs the epipolar technique for this light)";
        rows.push_back(row);
        progress(where + " " + row.configuration + ": skipped, " + row.note);
        continue;
      }
      const Measurement& run = subjects[*measured[k]].run;
      fill(row, config, run);
      const ErrorStats e = compareRgb(run.scattering, reference.scattering);
      row.relativeRmse = e.relativeRmse;
      row.relativeP99 = e.relativeP99;
      row.relativeMax = e.relativeMax;
      row.nonFinite = e.nonFinite;
      row.temporalChange = meanReference > 0.0 ? run.temporalChange / meanReference : 0.0;
      row.temporalRatio = referenceChange > 0.0 ? row.temporalChange / referenceChange : 0.0;
      rows.push_back(row);
      progress(where + " " + describeRow(row));
    }
    return true;
  }

  // Creates the subject's effect (the floor pass or a Tyndall context) and its renderer.
  bool open(const host::Scene& scene, const host::RenderSettings& settings, Subject& subject, std::string& error) {
    if (!subject.configuration) {
      subject.floor = FloorPass::create(device_, subject.floorKind, error);
      if (!subject.floor) return false;
    } else {
      const Configuration& config = *subject.configuration;
      subject.tyndall = TyndallEffect::create(device_, settings, Profile::Balanced, error, PipelineCreation::OnFirstUse);
      if (!subject.tyndall) return false;
      subject.tyndall->setTechnique(config.technique);
      subject.tyndall->setEpipolarSettings(config.epipolar);
      subject.tyndall->setPrefilteredSettings(config.prefiltered);
      // Timed frames run as an engine runs them, without copying L_in out; one more frame copies it.
      subject.tyndall->setAovOutputs(false);
    }
    subject.renderer = host::Renderer::create(device_, scene, settings, error);
    if (!subject.renderer) return false;
    subject.renderer->addPostProcess(subject.floor ? static_cast<host::PostProcessEffect*>(subject.floor.get())
                                                   : subject.tyndall.get());
    return true;
  }

  // The warm-up and timed frames of every subject, each frame alone on the device (waited for
  // before the next is recorded, so that neither another subject's frame nor the recording of the
  // next one runs beside it: on a CPU driver both take the same cores).
  // Given several subjects (SweepOptions::interleaved), one frame of every subject per round, the
  // round's first subject rotating, so that whatever else the machine does during the group slows
  // every subject alike and the ratios between them hold.
  bool timeFrames(const std::string& where, const std::vector<Subject*>& subjects, std::string& error) {
    const std::uint32_t frames = options_.warmUpFrames + options_.frames;
    const std::size_t n = subjects.size();
    auto renderOne = [&](Subject& subject, std::uint32_t frame) {
      if (!subject.renderer->renderFrame(error)) {
        subject.renderer->waitIdle();
        error = where + " " + subject.name + ": " + error;
        return false;
      }
      subject.renderer->waitIdle();
      ++unitsDone_;
      if (!subject.floor) return true;
      // The floor pass keeps one pair of stamps: read each frame's before the next.
      const std::optional<double> ms = subject.floor->lastMilliseconds();
      if (!ms) {
        error = "the floor pass's timestamps could not be read";
        return false;
      }
      if (frame >= options_.warmUpFrames) subject.run.totals.push_back(*ms);
      return true;
    };
    for (std::uint32_t frame = 0; frame < frames; ++frame) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!renderOne(*subjects[(frame + i) % n], frame)) return false;
      }
      if (n > 1) {
        progress(where + ": round " + std::to_string(frame + 1) + " of " + std::to_string(frames) + " (" +
                 std::to_string(n) + " subjects, " + std::to_string(options_.warmUpFrames) + " rounds of warm-up)");
      }
    }
    if (n == 1) progress(where + " " + subjects[0]->name + ": " + std::to_string(frames) + " frames");
    return true;
  }

  // A subject's timings from its context, L_in of one more frame at the scene's camera and the
  // orbit; then its renderer and effect are released.
  bool finish(const std::string& where, const host::Scene& scene, Subject& subject, std::string& error) {
    const bool ok = collect(scene, subject, error);
    if (!ok) error = where + " " + subject.name + ": " + error;
    subject.renderer.reset();
    subject.tyndall.reset();
    subject.floor.reset();
    ++unitsDone_;
    return ok;
  }

  bool collect(const host::Scene& scene, Subject& subject, std::string& error) {
    Measurement& out = subject.run;
    host::Renderer& renderer = *subject.renderer;
    if (TyndallEffect* tyndall = subject.tyndall.get()) {
      const std::uint32_t frames = options_.warmUpFrames + options_.frames;
      tyndall->context().collectTimings();
      std::vector<FrameTimings> timings = tyndall->context().takeCompletedTimings();
      std::sort(timings.begin(), timings.end(),
                [](const FrameTimings& a, const FrameTimings& b) { return a.frameIndex < b.frameIndex; });
      if (timings.size() < frames) {
        error = "timestamps of " + std::to_string(timings.size()) + " of " + std::to_string(frames) +
                " frames came back (does the device support timestamps?)";
        return false;
      }
      for (std::size_t i = options_.warmUpFrames; i < timings.size(); ++i) {
        out.totals.push_back(timings[i].totalMilliseconds);
        for (const PassTiming& pass : timings[i].passes) out.passes[pass.name].push_back(pass.milliseconds);
      }
      out.stats = tyndall->context().stats();
    }
    if (!checkValidation(error)) return false;
    if (!subject.tyndall) return true;
    subject.tyndall->setAovOutputs(true);
    if (!renderer.renderFrame(error)) {
      renderer.waitIdle();
      return false;
    }
    renderer.waitIdle();
    if (!renderer.readAovScattering(out.scattering, error)) return false;

    host::ImageRgba32f previous = out.scattering;
    host::ImageRgba32f current;
    double change = 0.0;
    for (std::uint32_t k = 1; k <= options_.orbitFrames; ++k) {
      if (!renderer.setCamera(orbit(scene.camera, options_.orbitDegreesPerFrame * k), error) ||
          !renderer.renderFrame(error)) {
        renderer.waitIdle();
        return false;
      }
      renderer.waitIdle();
      if (!renderer.readAovScattering(current, error)) return false;
      change += meanAbsoluteChange(current, previous);
      std::swap(previous, current);
    }
    out.temporalChange = options_.orbitFrames > 0 ? change / options_.orbitFrames : 0.0;
    return checkValidation(error);
  }

  // The row's measurements from `run`; its floors and the Reference's time are set already.
  static void fill(Row& row, const Configuration& config, const Measurement& run) {
    row.configuration = config.name();
    row.technique = config.techniqueName();
    row.parameters = config.parameters();
    row.techniqueUsed = to_string(run.stats.technique);
    row.measured = true;
    row.passOrder = run.stats.passesRecorded;
    for (const auto& [name, values] : run.passes) row.passMilliseconds[name] = median(values);
    row.totalMilliseconds = median(run.totals);
    row.timeRatioToReference =
        row.referenceMilliseconds > 0.0 ? row.totalMilliseconds / row.referenceMilliseconds : 0.0;
    row.composite = to_string(run.stats.composite);
    if (run.stats.resolutionChange != ResolutionChange::None) {
      row.note = std::string("L_in at full resolution (") + to_string(run.stats.resolutionChange) + ")";
    }
    const double floorMs = compositeFloorMilliseconds(row);
    row.timeRatioToFloor = floorMs > 0.0 ? row.totalMilliseconds / floorMs : 0.0;
    row.dispatches = run.stats.dispatches;
    row.barriers = run.stats.barriers;
    row.deviceMemoryBytes = run.stats.deviceMemoryBytes;
    if (run.stats.epipolarCounts) {
      row.marchedSamples = run.stats.epipolarCounts->marchedSamples;
      row.fixedUpPixelFraction = run.stats.epipolarCounts->fixedUpPixelFraction;
    }
  }

  bool checkValidation(std::string& error) const {
    if (!options_.validation || device_.validationMessages().empty()) return true;
    error = std::to_string(device_.validationMessages().size()) +
            " validation message(s), first: " + device_.validationMessages().front();
    return false;
  }

  static std::string formatMs(double ms) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.3f ms", ms);
    return text;
  }

  static std::string describeRow(const Row& row) {
    char text[256];
    std::snprintf(text, sizeof(text), ": %.3f ms, %.3g x Reference, %.3g x floor, relative RMSE %.2f%%, temporal %.2f",
                  row.totalMilliseconds, row.timeRatioToReference, row.timeRatioToFloor, 100.0 * row.relativeRmse,
                  row.temporalRatio);
    return row.configuration + text;
  }

  // A line with the elapsed time and an estimate of what is left.
  void progress(const std::string& line) const {
    if (!options_.progress) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double left = unitsDone_ > 0 && unitsDone_ < unitsTotal_
                            ? elapsed / static_cast<double>(unitsDone_) * static_cast<double>(unitsTotal_ - unitsDone_)
                            : 0.0;
    char prefix[96];
    std::snprintf(prefix, sizeof(prefix), "[%.0f s, about %.0f s left] ", elapsed, left);
    options_.progress(prefix + line);
  }

  const SweepOptions& options_;
  host::Device& device_;
  std::size_t unitsTotal_ = 0;
  std::size_t unitsDone_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

double compositeFloorMilliseconds(const Row& row) {
  // Against what the cheapest post-process of the same kind costs: a compute composite skips the
  // rasteriser and the blender, so its floor differs from the fragment one.
  const bool compute = row.composite == to_string(CompositePath::Compute) && row.computeFloorMilliseconds > 0.0;
  return compute ? row.computeFloorMilliseconds : row.floorMilliseconds;
}

bool runSweep(const SweepOptions& options, std::vector<Row>& rows, std::string& deviceName, std::string& error) {
  host::DeviceOptions deviceOptions;
  deviceOptions.validation = options.validation;
  std::unique_ptr<host::Device> device = host::Device::create(deviceOptions, error);
  if (!device) return false;
  deviceName = device->name();
  Sweep sweep(options, *device);
  return sweep.run(rows, error);
}

}  // namespace tyndall::samples::bench
