// What a frame did, as data (Context::stats()): the profile and technique that ran and why, each
// technique's decisions, GPU timings of an earlier frame, dispatch and memory counts.
// `techniqueNote` summarises it for people. Included at the end of tyndall/tyndall.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tyndall/tyndall.h"

namespace tyndall {

// ----------------------------------------------------------------------------------------------
// Per technique: what it decided (Stats::epipolar, Stats::prefiltered, Stats::epipolarCounts)
// ----------------------------------------------------------------------------------------------

/// How the epipolar technique marched its samples.
enum class EpipolarMarch : std::uint32_t {
  MinMaxTree,          ///< along each slice's 1D min/max tree (yusov2013), one per cascade
  CellsTreeOff,        ///< cell by cell: EpipolarSettings::minMaxTree is off
  CellsMapTooLarge,    ///< cell by cell: the shadow map is larger than the tree supports (4096²)
  PointLightBlockWalk, ///< a point light: the texel walk across blocks of its six maps
};

struct EpipolarStats {
  std::uint32_t slices = 0;           ///< the settings that ran (profile table or FrameDesc::epipolar)
  std::uint32_t samplesPerSlice = 0;
  /// Last / first sample spacing along a slice that ran: the settings' epipoleDensity, or the
  /// light's when that is 0 (1 for a directional light, 16 for a spot or point light).
  float epipoleDensity = 1.0f;
  EpipolarMarch march = EpipolarMarch::MinMaxTree;
  /// Fraction of the screen border the slices' end points cover: 1 for the whole border, less
  /// where only a spot cone's wedge or an off-screen epipole's wedge can hold shafts.
  float sliceBorderFraction = 1.0f;
  bool slicesFitSpotCone = false;        ///< the wedge was narrowed to the spot cone
  bool slicesFitOffScreenEpipole = false;///< the wedge was narrowed to what an off-screen epipole sees
  /// Lines (and trees) per slice: one in each of a directional light's cascades, which march their
  /// stretches of a view ray along their own; 1 for a spot light, 0 for a point light (walked).
  std::uint32_t linesPerSlice = 1;
  /// With a light-colour texture, lit parts of a slice's line are integrated in chunks of this many
  /// cells, each times its mean colour from the slice's prefix sums; 0 without (or a point light).
  std::uint32_t coloredChunkCells = 0;
};

/// Counts read back from an earlier frame of the epipolar technique (the frame of `lastTimings`).
struct EpipolarCounts {
  std::uint64_t marchedSamples = 0;   ///< ray-marched (initial step plus refinements)
  std::uint64_t shadowedSamples = 0;  ///< found wholly in shadow by the min/max tree: zero, not marched
  double fixedUpPixelFraction = 0.0;  ///< of the output's pixels, ray-marched by the fix-up pass
};

enum class Rectification : std::uint32_t {
  Projective,  ///< klehm2014 §4.2: one matrix
  NonLinear,   ///< peters2017 §5.1.1: (r, φ, θ), valid for every view
};

/// Why the prefiltered technique's rectification is the one that ran.
enum class RectificationChoice : std::uint32_t {
  Requested,             ///< the settings asked for it
  Automatic,             ///< chosen by the projective matrix's texel stretch (≤ 2: projective)
  ProjectiveImpossible,  ///< projective asked, but the light axis is in the frustum: non-linear ran
};

struct PrefilteredStats {
  Rectification rectification = Rectification::NonLinear;
  RectificationChoice choice = RectificationChoice::Requested;
  double projectiveTexelStretch = 0.0;  ///< ∞ when no projective matrix exists for the view
  std::uint32_t prefixSumSets = 1;      ///< 1 (grey extinction) to 3 (one per distinct channel)
  bool rowDepthBounds = false;          ///< rays the rows' depth bounds decide skip the reconstruction
  std::uint32_t segments = 0;           ///< reconstructions per pixel with segmented reconstruction; 0 off
  bool trimmedSegments = false;
  std::uint32_t texelWalkSteps = 0;     ///< 0: no texel walk
  std::uint32_t shortRayColumns = 0;    ///< rays ending within these columns are ray-marched; 0 off
  bool epipoleBlockMarched = false;     ///< the epipole's block was on screen and ray-marched
};

// ----------------------------------------------------------------------------------------------
// Per frame
// ----------------------------------------------------------------------------------------------

struct PassTiming {
  std::string name;
  double milliseconds = 0.0;
};

/// GPU timings of one earlier frame, read from timestamp queries without waiting.
struct FrameTimings {
  std::uint64_t frameIndex = 0;    ///< the `Stats::frameIndex` it was recorded as
  std::vector<PassTiming> passes;  ///< in recording order
  double totalMilliseconds = 0.0;  ///< first pass start to last pass end
};

enum class CompositePath : std::uint32_t { None, Fragment, Compute };
const char* to_string(CompositePath path) noexcept;  ///< "none", "fragment", "compute"

/// Why the technique that ran is not the one the profile (or FrameDesc::technique) asked for.
/// Each is a design decision, documented in docs/INTEGRATION.md "Fallbacks".
enum class TechniqueChange : std::uint32_t {
  None,                              ///< the requested technique ran
  NoExtinction,                      ///< σ_t = 0: nothing recorded, the back buffer left as it is
  NothingScatters,                   ///< σ_s = 0 or the light off: L_in cleared, the back buffer attenuated
  PrefilteredNeedsDirectionalLight,  ///< prefiltered asked for a spot or point light: epipolar ran
  PrefilteredHasNoLightColor,        ///< prefiltered asked with a light-colour texture: epipolar ran
  PrefilteredNeedsOneShadowMap,      ///< prefiltered asked for a light with cascades: epipolar ran
  TranslucentNeedsReference,         ///< epipolar or prefiltered asked with translucent layers: the Reference ran
  EpipolarNeeds2x2,                  ///< epipolar asked for an output under 2×2: the Reference ran
};
const char* to_string(TechniqueChange change) noexcept;

/// Why L_in ran at a finer resolution than the frame or the profile asked for (a design decision,
/// docs/INTEGRATION.md "Reduced resolution").
enum class ResolutionChange : std::uint32_t {
  None,              ///< the requested resolution ran
  /// A spot or point light's position projects within 4 target pixels of the view: next to its
  /// image L_in grows as 1/distance from the light and changes many-fold within an upsampling block.
  LocalLightInView,
  /// The output is too small for the resolution asked: its L_in target would have fewer rows than
  /// the settings' `minimumRows`, so a finer resolution (possibly still reduced) ran.
  BelowMinimumRows,
};
/// "none", "local-light-in-view", "below-minimum-rows"
const char* to_string(ResolutionChange change) noexcept;

/// Profile::Auto's estimate of each profile's time: the median of its last measured frames under
/// Auto, in milliseconds; empty while unmeasured.
struct AutoEstimates {
  std::optional<double> high, balanced, performance;
};

/// Why a light of the frame recorded nothing.
enum class LightSkipped : std::uint32_t {
  No,               ///< it ran its technique
  Off,              ///< intensity or colour 0
  OutsideView,      ///< a spot light's cone misses every view ray
  NothingScatters,  ///< σ_s = 0: no light scatters
};
const char* to_string(LightSkipped reason) noexcept;  ///< "no", "off", "outside-view", "nothing-scatters"

/// One light of the frame: FrameDesc::light first, then FrameDesc::additionalLights in order.
struct LightStats {
  LightType type = LightType::Directional;
  Technique requestedTechnique = Technique::None;
  Technique technique = Technique::None;  ///< None when skipped
  TechniqueChange techniqueChange = TechniqueChange::None;
  LightSkipped skipped = LightSkipped::No;
  std::optional<EpipolarStats> epipolar;
  std::optional<PrefilteredStats> prefiltered;
  /// Translucent layers per shadow map the light's technique integrated (ShadowMapDesc); 0: none.
  std::uint32_t translucentLayers = 0;
};

struct Stats {
  std::uint64_t frameIndex = 0;  ///< frames recorded so far by this context
  Profile requestedProfile = Profile::Balanced;
  Profile profileUsed = Profile::Balanced;  ///< the requested one, or the one Auto chose
  /// What the profile table (or FrameDesc::technique) asked for, and what ran. They differ only
  /// with a `techniqueChange`; `technique` is None when nothing was computed.
  Technique requestedTechnique = Technique::None;
  Technique technique = Technique::None;
  TechniqueChange techniqueChange = TechniqueChange::None;
  bool techniqueSetByFrame = false;  ///< FrameDesc::technique chose it, not the profile table
  /// Every light of the last frame, FrameDesc::light first; the fields above and `epipolar`,
  /// `prefiltered` below are the first light's.
  std::vector<LightStats> lights;
  std::optional<EpipolarStats> epipolar;        ///< when the epipolar technique ran this frame
  std::optional<PrefilteredStats> prefiltered;  ///< when the prefiltered technique ran this frame
  std::optional<EpipolarCounts> epipolarCounts; ///< once an epipolar frame's counts were read back
  /// A CPU driver (lavapipe) ends a shader invocation's loops after 65,535 iterations; a light's
  /// texel walk can exceed that and come out wrong: a point light's over maps above 4096², a
  /// directional light's over cascades whose sides add up to 32,768 texels or more (four of 8192²);
  /// with translucent layers fewer (walkCanOverrunCpuLoopBudget: e.g. with 4 layers a spot light's
  /// maps above 2730², a point light's above 682², a directional light's four cascades above 1365²).
  bool walkOverCpuLoopLimit = false;
  /// Read back from the frame of `lastTimings`: a view ray of the Reference crossed a shadow-map texel
  /// with more translucent surfaces than ShadowMapDesc::translucentLayerCount (the overflow layer
  /// held one); the surfaces past the count were left out, so L_in there is too bright.
  bool translucentLayersOverflowed = false;
  bool debugViewDrawn = false;                  ///< false: debugOutput got the dimmed L_in alone
  std::string techniqueNote;                    ///< the above in one line for people; not for parsing
  std::vector<std::string> passesRecorded;      ///< the last `record`'s passes, in order
  /// How the last frame wrote the back buffer: a compute pass (the back buffer has STORAGE usage
  /// and a format compute can write) or a full-screen fragment pass; None when it was left alone.
  CompositePath composite = CompositePath::None;
  /// The resolution L_in was computed at in the last frame (the composite upsampled it below Full).
  ScatteringResolution scatteringResolution = ScatteringResolution::Full;
  ResolutionChange resolutionChange = ResolutionChange::None;  ///< why it is finer than asked
  /// The L_in target's format in the last frame: R16G16B16A16_SFLOAT when its first running light
  /// ran an approximate technique, R32G32B32A32_SFLOAT when that light ran the Reference or with
  /// ContextTuning::fullFloatTargets (docs/INTEGRATION.md "Device memory").
  VkFormat scatteringFormat = VK_FORMAT_UNDEFINED;
  std::uint32_t dispatches = 0;  ///< compute dispatches (direct and indirect) the last `record` recorded
  std::uint32_t barriers = 0;    ///< pipeline barriers the last `record` recorded
  FrameTimings lastTimings;                     ///< most recent frame whose timestamps were available
  bool timingsValid = false;                    ///< false until `lastTimings` holds one
  bool timestampsSupported = false;
  std::uint64_t deviceMemoryBytes = 0;  ///< held after the last `record` (targets, technique data)
  AutoEstimates autoEstimateMilliseconds;
};

}  // namespace tyndall
