// What each technique decided for a frame (Stats::epipolar, Stats::prefiltered,
// Stats::epipolarCounts): data for tools, tests and engines that tune; tyndall.h includes it.
#pragma once

#include <cstdint>

namespace tyndall {

/// How the epipolar technique marched its samples.
enum class EpipolarMarch : std::uint32_t {
  MinMaxTree,          ///< along each slice's 1D min/max tree (yusov2013)
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

}  // namespace tyndall
