// tyndall-render's job, callable from tests: parse the command line (DESIGN.md "The sample
// renderer"), render a scene through the stub host with Tyndall in its post-process stack,
// and write the outputs.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tyndall/tuning.h"
#include "tyndall_host/renderer.h"

namespace tyndall::samples {

class TyndallEffect;

struct RenderOptions {
  std::string scenePath;
  Profile profile = Profile::Balanced;  ///< the default profile
  float autoBudgetMilliseconds = 4.0f;  ///< Profile::Auto's budget (FrameDesc's default)
  Technique technique = Technique::None; ///< --technique: overrides the profile's choice
  std::optional<EpipolarSettings> epipolar;  ///< --epipolar: instead of the profile's
  std::optional<PrefilteredSettings> prefiltered;  ///< --prefiltered: instead of the profile's
  std::optional<ScatteringResolution> resolution;  ///< --resolution: instead of the profile's
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  std::uint32_t shadowMapSize = 0;      ///< 0: the scene's
  std::uint32_t cascades = 0;           ///< --cascades: every directional light's, 1..4; 0: each light's own
  std::uint32_t translucentLayers = 4;  ///< --translucent-layers: peeled layers per shadow map, 1..8
  std::uint32_t frames = 1;
  std::string outputPng;
  std::string outputExr;
  std::string aovScattering;
  std::string aovTransmittance;
  std::string timings;
  // Beyond the contract: conventions of the host's depth buffer, and validation layers.
  host::DepthConvention depth = host::DepthConvention::Standard;
  bool infiniteFar = false;
  bool validation = false;
  bool noEffect = false;  ///< render without Tyndall: the host's own cost, for wall-clock baselines
  DebugView debugView = DebugView::None;  ///< --debug-view samples|fixup FILE.png
  std::string debugViewPng;
  VkFormat backBufferFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  ///< not on the command line
  /// --no-storage-back-buffer sets false: the back buffer lacks STORAGE usage, so Tyndall composites
  /// with its fragment path (RenderSettings::storageBackBuffer).
  bool storageBackBuffer = true;
  std::uint32_t framesInFlight = 2;                           ///< not on the command line
  /// --pipelines at-create|on-first-use: tyndall-render compiles every pipeline up front unless
  /// told otherwise; the tests, which create a context per render and use one or two techniques,
  /// compile on first use.
  PipelineCreation pipelineCreation = PipelineCreation::AtCreate;
  /// --march-threads: ContextDesc::marchThreadsPerSample (0: by device).
  std::uint32_t marchThreadsPerSample = 0;
  /// ContextTuning::fullFloatTargets (not on the command line): for tests that compare the
  /// approximate techniques' passes with the Reference finer than half-float rounding.
  bool fullFloatTargets = false;
};

/// Parses argv. Returns false with a one-line reason; `help` is set for --help.
bool parseCommandLine(int argc, const char* const* argv, RenderOptions& options, bool& help, std::string& error);
std::string usage();

struct RenderResult {
  host::ImageRgba32f color;          ///< back buffer after the post-process stack (scene-linear)
  host::ImageRgba32f scattering;     ///< L_in (only if requested by the options)
  host::ImageRgba32f transmittance;  ///< T (only if requested by the options)
  host::ImageRgba32f debugView;      ///< the debug view (only if the options name one)
  Stats stats;                       ///< after the last frame
  std::vector<FrameTimings> timings; ///< every frame whose timestamps were read
  /// Wall-clock milliseconds per frame, host passes included, over frames 2..N (frame 1 when
  /// N = 1): on a CPU driver such as lavapipe this is the time the device spends.
  double wallMillisecondsPerFrame = 0.0;
  std::string deviceName;
  bool cpuDevice = false;  ///< VK_PHYSICAL_DEVICE_TYPE_CPU (lavapipe): the plugin's criterion for CPU-driver choices
};

/// The stub host's settings for the options (AOV images when the options name an AOV file or
/// `wantAovs` is set).
host::RenderSettings renderSettingsFor(const RenderOptions& options, bool wantAovs);

/// Renders `options.frames` frames of `scene` on `device`. AOVs are read back when the options
/// name an AOV file or `wantAovs` is set.
bool renderScene(host::Device& device, const host::Scene& scene, const RenderOptions& options, bool wantAovs,
                 RenderResult& result, std::string& error);

/// The same through an existing effect instead of a new one, as an engine keeps one Tyndall context
/// while its scenes and settings change: the context (and the pipelines it built when created) serves
/// render after render. The effect must have been created on `device` with the render settings'
/// size, frames in flight and back-buffer format (renderSettingsFor); its profile, technique and
/// settings are set from the options. `result.stats` are the context's: counters such as
/// `frameIndex` run on from the renders before.
bool renderScene(host::Device& device, const host::Scene& scene, const RenderOptions& options, bool wantAovs,
                 TyndallEffect& effect, RenderResult& result, std::string& error);

/// The light a pass belongs to in a frame of several lights, whose passes the context names
/// "lightI/…" (I the light's index); none for a shared pass (the composite, the AOV copies).
std::optional<std::size_t> passLight(const std::string& pass);

/// Median per pass and of the total over the timed frames, as JSON text.
std::string timingsJson(const RenderOptions& options, const RenderResult& result);

/// Writes `text` to `path` through a temporary file and a rename, so the file is whole or absent.
bool writeFileWhole(const std::string& path, const std::string& text, std::string& error);

/// Writes every output the options name (PNG through the OpenColorIO display transform, EXRs,
/// timings JSON). Files are written whole or not at all.
bool writeOutputs(const RenderOptions& options, const RenderResult& result, std::string& error);

/// Parses, loads, renders and writes; returns the process exit status and prints one line on error.
int runTyndallRender(int argc, const char* const* argv);

}  // namespace tyndall::samples
