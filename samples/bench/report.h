// tyndall-bench's outputs: the rows as CSV, JSON and a Markdown table; per output and shadow-map
// size the configurations summarised over the scenes and their Pareto front (pareto.json, which
// scripts/plot-pareto.py draws); and the profile choice with the document docs/TRADEOFFS*.md are
// generated from (docs/TRADEOFFS-H200.md's is the profile table).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "profiles.h"
#include "sweep.h"

namespace tyndall::samples::bench {

/// One configuration over the scenes of one output and shadow-map size (medians over the scenes it
/// was measured on: the prefiltered technique runs on directional-light scenes only).
struct Summary {
  std::string configuration, technique, parameters;
  std::size_t scenes = 0;
  double timeRatioToReference = 0.0;  ///< median over the scenes
  double timeRatioToFloor = 0.0;      ///< median
  double relativeRmse = 0.0;          ///< median
  double worstRelativeRmse = 0.0;     ///< max over the scenes
  std::string worstScene;
  double relativeP99 = 0.0;           ///< median
  double temporalRatio = 0.0;         ///< median
  double milliseconds = 0.0;          ///< median total
  double timeSpread = 0.0;            ///< (max − min) / median of the total over the scenes
  std::uint64_t deviceMemoryBytes = 0;  ///< max over the scenes
  std::size_t nonFinite = 0;          ///< sum over the scenes
  std::map<std::string, double> sceneRelativeRmse;  ///< per scene
};

/// The kind of light a row's scene has (Row::light); none for a scene of several lights, which
/// the summaries over every scene count and no kind's choice does.
std::optional<LightClass> lightClassOf(const Row& row);

/// The configurations over the scenes of one output and shadow-map size; with `lights`, over the
/// scenes of that kind of light only (the profile table's rows are chosen per kind).
std::vector<Summary> summarize(const std::vector<Row>& rows, std::uint32_t width, std::uint32_t height,
                               std::uint32_t shadowMap, std::optional<LightClass> lights = std::nullopt);

/// A profile's goals (the issue's, at 1920×1080 with a 2048² map, medians over the scenes) and the
/// configuration picked for it: of those that meet the per-scene bar and the speed goal (and the
/// floor goal), the one with the lowest median relative RMSE — a point of the Pareto front by
/// construction, and distinct tiers where the front allows. If none meets the floor goal too, the
/// most accurate of those that meet the speedup goal; if none is fast enough, the fastest (a
/// miss). Whether it meets the error goal is reported.
struct ProfileGoal {
  Profile profile;             ///< High, Balanced, Performance
  double maxRelativeRmse;      ///< 0.02, 0.04, 0.08
  double minSpeedup;           ///< 12, 25, 50 (Reference time / time)
  double maxTimeOverFloor;     ///< 4 for Performance, 0: none
  /// The bar the profile's tests hold it to on every scene (the epipolar issue's: High 3%,
  /// Balanced 6% at 640×360; Performance twice its goal, 16%, as in the extremes suite), 0: none.
  /// A scene on which no configuration meets it does not decide between them (stained-glass: a
  /// documented miss of every configuration).
  double maxSceneRelativeRmse;

  /// The profile's name as the documents write it: "High", "Balanced", "Performance".
  std::string name() const;
};
const std::vector<ProfileGoal>& profileGoals();
/// The goal of High, Balanced or Performance (the tests' bars read it too); nullptr for the others.
const ProfileGoal* profileGoal(Profile profile);

struct ProfileChoiceResult {
  ProfileGoal goal;
  std::optional<std::size_t> summary;  ///< index into the summaries; empty when there is no candidate
  bool errorMet = false;
  bool speedMet = false;
  bool floorMet = true;
  /// The incumbent's configuration name (as Summary::configuration) when it was measured in this
  /// group; empty otherwise. The choice is it, or a challenger that cleared the margin.
  std::string incumbent;
  /// The kind of light the summaries were of (set by the caller of chooseProfiles).
  LightClass lights = LightClass::Directional;
};

/// The margin a challenger's speed must clear to replace the incumbent, a configuration the profile
/// table already holds: its speedup at least (1 + margin) × the goal, its time over the floor at
/// most the floor goal / (1 + margin). The same lavapipe sweep in TRADEOFFS.md's run of before
/// 2026-11-26 and in that day's rerun gave the epipolar configurations speedups 2–22% apart (with
/// code changes between them), and a configuration measured at 43.9× in one and 52.3× in the
/// next, 5% above Performance's 50×, would have replaced its row: without a margin, a
/// configuration within a run's spread of a goal decides the table by the run's luck. Errors are
/// deterministic (the same to every printed digit in both runs) and get no margin for noise
/// (kChallengerErrorMargin below is against churn).
inline constexpr double kChallengerSpeedMargin = 0.25;

/// The margin a challenger's accuracy must clear to replace an incumbent that meets the same goals:
/// its median relative RMSE at most (1 − margin) × the incumbent's. Errors do not vary between runs,
/// but a row that changes moves every figure the documents and tests quote for that profile, and a
/// challenger barely more accurate is not worth it: the 2026-11-27 sweep would have replaced
/// Balanced's directional row (35.1×, 0.860%) with twice its samples (31.8×, 0.852%), 10% slower
/// for an error 1% lower.
inline constexpr double kChallengerErrorMargin = 0.10;

/// The configuration (Summary::configuration, e.g. "epipolar slices=128,samples=128") each profile
/// of plugin/src/profiles.cpp's table runs for a kind of light at an output of `outputHeight` rows:
/// the row with its resolution floor applied (resolutionForRows) and dropped, so that it names
/// what the sweep measures at that size. The incumbents of the choice.
std::map<Profile, std::string> profileTableConfigurations(LightClass lights, std::uint32_t outputHeight);
using Incumbents = std::map<LightClass, std::map<Profile, std::string>>;
/// Both kinds'.
Incumbents profileTableConfigurations(std::uint32_t outputHeight);

/// Per profile (profileGoals()), of the configurations that meet its per-scene bar and its speed
/// goals, the most accurate. When the profile's incumbent (`incumbents`, e.g.
/// profileTableConfigurations()) was measured, the others' speed must clear the goals by
/// kChallengerSpeedMargin (hysteresis: a run's noise does not move the table), and where the
/// incumbent meets the same goals as the most accurate challenger, the challenger's error must
/// clear kChallengerErrorMargin; if neither the incumbent nor any challenger clears the speed
/// goals so, the plain goals decide.
std::vector<ProfileChoiceResult> chooseProfiles(const std::vector<Summary>& summaries,
                                                const std::map<Profile, std::string>& incumbents = {});

struct ReportContext {
  std::string commandLine;  ///< as run, for the documents
  std::string device;
  std::uint32_t chooseWidth = 0, chooseHeight = 0, chooseShadowMap = 0;  ///< the group the choice is made in
  std::uint32_t frames = 0, warmUpFrames = 0, orbitFrames = 0;
  /// "interleaved" or "sequential" (SweepOptions::interleaved); empty in files written before the
  /// bench recorded it, which measured each configuration's frames in a row.
  std::string schedule;
  double orbitDegreesPerFrame = 0.0;
  /// chooseProfiles' incumbents per kind of light; unset: the profile table's rows as they run at
  /// chooseHeight (profileTableConfigurations).
  std::optional<Incumbents> incumbents;
  /// Where tradeoffs.md links tradeoffs-measurements.md, relative to where tradeoffs.md ends up.
  std::string measurementsLink = "tradeoffs-measurements.md";
};

/// Per-light cost of the rows of scenes with several lights (passes named "lightI/…", Stats'
/// prefix): per row, each light's passes' medians summed, and the shared passes' (the composite).
/// A Markdown table; empty when no row has per-light passes.
std::string perLightMarkdown(const std::vector<Row>& rows);

/// The rows and context of an earlier run's results.json (writeReports writes it), so that the
/// reports can be written again without measuring again (tyndall-bench --from). A file written
/// before the rows recorded their light takes each scene's from samples/scenes/SCENE.json (run from
/// the repository root).
bool readResults(const std::string& path, std::vector<Row>& rows, ReportContext& context, std::string& error);

/// Writes into `directory`: results.csv, results.json, results.md, pareto.json (per group, and per
/// kind of light when the rows have both, the plot pareto-WxH-N[-directional|-local] as data),
/// choice.json (per profile and kind of light, the choice and the configuration it runs as),
/// tradeoffs.md (the choice, the profiles as they run, the plots: pareto.json's files as .svg) and
/// tradeoffs-measurements.md (per scene, per configuration and per measurement). The choice is made per kind of light
/// present in the rows, over that kind's scenes. Files are written whole (temporary file, rename).
bool writeReports(const std::vector<Row>& rows, const ReportContext& context, const std::string& directory,
                  std::string& error);

}  // namespace tyndall::samples::bench
