// tyndall-bench's sweep: scenes × output sizes × shadow-map sizes × configurations (a technique and
// its parameters), each measured against the Reference and against the full-screen floor passes in
// the same run (issue "Quality profiles from a measured speed–accuracy trade").
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tyndall/tuning.h"

namespace tyndall::host {
enum class LightType;  // tyndall_host/scene.h
}

namespace tyndall::samples::bench {

/// "directional", "spot" or "point": a scene's light as Row::light names it.
const char* lightName(host::LightType type);

/// A technique with its parameters. `parameters` is settings_text's describe() of the settings, so
/// equal settings give equal names.
struct Configuration {
  Technique technique = Technique::Reference;
  std::optional<EpipolarSettings> epipolar;
  std::optional<PrefilteredSettings> prefiltered;

  std::string techniqueName() const;  ///< "reference", "epipolar", "prefiltered"
  std::string parameters() const;     ///< "-" for the Reference
  std::string name() const;           ///< "epipolar slices=1024,samples=512"
};

/// A configuration's name from its technique and parameters (Configuration::name, and the rows
/// read back from results.json): the technique alone for the Reference.
std::string configurationName(const std::string& technique, const std::string& parameters);

/// "epipolar:KEY=VALUE,…", "prefiltered:KEY=VALUE,…" (tyndall-render's --epipolar/--prefiltered
/// syntax; "epipolar:" alone: the defaults) or "reference".
bool parseConfiguration(const std::string& text, Configuration& out, std::string& error);

/// The built-in parameter grids: "default" (what docs/TRADEOFFS.md sweeps: 23 epipolar and 6
/// prefiltered configurations, reduced resolutions among them), "full" (41, for a GPU), "quick"
/// (two, for a smoke test) or "none".
bool builtInGrid(const std::string& name, std::vector<Configuration>& out, std::string& error);

struct Row;

struct SweepOptions {
  std::vector<std::string> scenes;  ///< scene JSON paths
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sizes{{640, 360}};
  std::vector<std::uint32_t> shadowMaps{2048};
  std::vector<Configuration> configurations;  ///< the Reference is always measured first
  std::uint32_t warmUpFrames = 3;     ///< rendered and not timed (pipelines, caches)
  std::uint32_t frames = 20;          ///< timed frames; the median is reported
  /// Frames of one scene and size interleaved: each round renders one frame of the floor passes, the
  /// Reference and every configuration (the first rotating), so that the machine's other work slows
  /// them alike and their ratios hold; all their renderers and contexts are alive at once. False:
  /// one subject's frames after another's, one renderer and context alive at a time (for sizes
  /// whose every context at once would not fit). Either way each frame runs alone on the device.
  bool interleaved = true;
  std::uint32_t orbitFrames = 6;      ///< frames of the slow orbit for the temporal stability
  double orbitDegreesPerFrame = 0.25; ///< camera rotation about its target's vertical axis per frame
  bool validation = false;            ///< fail on any validation message
  /// The back buffers get STORAGE usage where their format allows (RenderSettings::storageBackBuffer),
  /// so Tyndall may composite with compute and the compute floor is measured; false: neither.
  bool storageBackBuffer = true;
  std::function<void(const std::string&)> progress;  ///< one line per measured configuration
  /// Called with every row so far after each scene and size, so a long sweep that is stopped
  /// keeps what it measured.
  std::function<void(const std::vector<Row>&)> groupDone;
};

/// One configuration on one scene at one output and shadow-map size.
struct Row {
  std::string scene;  ///< file stem
  /// The scene's light: "directional", "spot" or "point" (the profile table has a row per
  /// LightClass, chosen over that kind's scenes), or "several" for a scene of several lights.
  std::string light;
  std::uint32_t width = 0, height = 0, shadowMap = 0;
  std::string configuration, technique, parameters;
  std::string techniqueUsed;  ///< Stats::technique (a profile or fallback may differ)
  bool measured = false;      ///< false: skipped, `note` says why
  /// Why it was skipped, or for a measured row what Tyndall changed (L_in at full resolution).
  std::string note;
  std::map<std::string, double> passMilliseconds;  ///< median per pass
  std::vector<std::string> passOrder;              ///< recording order of the last frame
  double totalMilliseconds = 0.0;      ///< median over the timed frames (Tyndall's first to last stamp)
  double referenceMilliseconds = 0.0;  ///< the Reference's median, same scene and sizes
  double floorMilliseconds = 0.0;      ///< the fragment floor pass's median, same scene and sizes
  /// The compute floor pass's median, same scene and sizes; 0 when it was not measured
  /// (`computeFloorNote` says why).
  double computeFloorMilliseconds = 0.0;
  std::string computeFloorNote;        ///< empty when the compute floor was measured
  /// to_string(Stats::composite): "fragment" or "compute", the composite this configuration ran
  /// ("none" in rows not measured, and in files written before rows recorded it).
  std::string composite = "none";
  double timeRatioToReference = 0.0;   ///< total / Reference (smaller is faster)
  /// total / the floor of the composite's kind: the compute floor when `composite` is "compute"
  /// and the compute floor was measured, else the fragment floor.
  double timeRatioToFloor = 0.0;
  std::uint32_t dispatches = 0;        ///< Stats::dispatches of the last timed frame
  std::uint32_t barriers = 0;          ///< Stats::barriers of the last timed frame
  std::uint64_t deviceMemoryBytes = 0; ///< Stats::deviceMemoryBytes of a context that ran only this
  double relativeRmse = 0.0, relativeP99 = 0.0, relativeMax = 0.0;  ///< L_in against the Reference
  std::size_t nonFinite = 0;
  double temporalChange = 0.0;  ///< mean |L_in(t) − L_in(t−1)| over the orbit / mean |Reference L_in|
  double temporalRatio = 0.0;   ///< temporalChange / the Reference's own (1: as stable as the Reference)
  std::uint64_t marchedSamples = 0;
  double fixedUpPixelFraction = 0.0;
};

/// The floor `row.timeRatioToFloor` is against: the compute floor when the row's composite was
/// "compute" and the compute floor was measured, else the fragment floor (milliseconds).
double compositeFloorMilliseconds(const Row& row);

/// Runs the sweep. False with `error` when something could not run (a scene does not load, a
/// frame fails, validation spoke); the rows measured so far stay in `rows`.
/// `device` receives the Vulkan device's name.
bool runSweep(const SweepOptions& options, std::vector<Row>& rows, std::string& device, std::string& error);

}  // namespace tyndall::samples::bench
