// Tyndall's technique tuning: the parameters each technique runs with, for tools, tests and
// engines that tune beyond the quality profiles. An integrator who picks a Profile needs none of
// this (tyndall.h); the profile table (plugin/src/profiles.cpp) fills these for each profile.
#pragma once

#include <cstdint>

#include "tyndall/tyndall.h"

namespace tyndall {

/// Parameters of the epipolar technique. Every field is validated per frame.
struct EpipolarSettings {
  std::uint32_t slices = 512;            ///< epipolar slices (lines from the epipole to the border), 8..4096
  std::uint32_t samplesPerSlice = 256;   ///< samples along each slice, 2..4096
  bool improvedSamplePlacement = true;   ///< a short slice uses only ≈ one sample per pixel (yusov2013)
  /// Every n-th sample along a slice is ray-marched (and the last one), 1..4096, default 16.
  std::uint32_t initialSampleStep = 16;
  /// Relative difference of view-ray length between neighbouring samples that makes both of them
  /// ray-marched samples (a depth break), (0, 1], default 0.03.
  float refinementThreshold = 0.03f;
  /// Second round of refinement: where the L_in of neighbouring ray-marched samples differs by
  /// more than this fraction of the larger, the interval between them gets 3 more ray-marching
  /// samples (shadow and cone edges crossing a slice, fast falloff). (0, 1], default 0.2;
  /// 1 turns the second round off (its passes are then not recorded).
  float intensityRefinementThreshold = 0.2f;
  /// Last / first sample spacing along a slice, [1, 1000] (1: uniform), or 0 (default): by the
  /// light, 1 for a directional light, 16 for a spot or point light, whose occluders next to it cut
  /// L_in within a pixel there (docs/EPIPOLAR.md "Spot lights: where the error is").
  float epipoleDensity = 0.0f;
  /// March along each slice's 1D min/max binary tree (yusov2013): same result as without, fewer
  /// steps. Directional and spot lights with shadow maps up to 4096²; point lights and larger maps
  /// march without it (the stats' techniqueNote says so). Default true.
  bool minMaxTree = true;
  /// Longest section (in 1D samples, about one shadow-map texel each) the tree march takes in one
  /// step: limits the tree's depth (yusov2013's maximum step). A power of two in 2..4096, default 1024.
  std::uint32_t maxTreeStep = 1024;
  /// Relative difference of view-ray length up to which an epipolar sample is interpolated into
  /// a pixel (the bilateral filter of the unwarp), (0, 1], default 0.05.
  float bilateralDepthThreshold = 0.05f;
  /// A pixel whose bilateral weights sum to less than this is ray-marched by the fix-up pass,
  /// (0, 1], default 0.05.
  float fixupWeightThreshold = 0.05f;
  /// A pixel whose two slices' interpolated L_in differ (in any channel) by more than this fraction
  /// of the larger, or whose two samples along one slice do, is ray-marched by the fix-up pass: a
  /// shaft or colour edge runs between the slices, narrower than their spacing (fine coloured
  /// shafts), or an occluder next to a local light cuts L_in between two samples a pixel apart.
  /// (0, 1], default 1 (off): the pixels near every shaft edge are fixed up, which costs more where
  /// shafts are many.
  float sliceContrastThreshold = 1.0f;
  /// Pixels within this many pixels of the projected light (on screen or just off it) are
  /// ray-marched by the fix-up pass (klehm2014's epipole block): next to the epipole the slices
  /// converge faster than interpolation across them can follow. [0, 256], default 8. The block's
  /// radius is the larger of this and `epipoleFixupHeightFraction` of the output's height.
  float epipoleFixupRadius = 8.0f;
  /// The epipole block's radius grows with the output to this fraction of its height, [0, 0.25],
  /// default 1/45 (8 px at 360 lines, 24 px at 1080). The peak of L_in around the light (the phase
  /// function's forward lobe, a local light's fall-off) spans a fixed angle, so a fixed number of
  /// pixels covers less of it as the output grows (docs/EPIPOLAR.md, "Unwarp and fix-up").
  float epipoleFixupHeightFraction = 1.0f / 45.0f;
  /// Steps along a fixed-up pixel's ray. 0 (default): the Reference's walk, texel by texel through
  /// the shadow map, exact. N in 1..256: yusov2013's fix-up "using fewer steps": the ray's stretch
  /// in each map is cut into N equal steps, and each step is lit or shadowed by the texel under its
  /// middle (its lit part against that texel's depth found exactly, then integrated in closed form or
  /// by the Reference's quadrature). A fixed-up pixel then reads N texels instead of one per texel
  /// its ray crosses (about the map's side); an occluder narrower than a step can be missed.
  std::uint32_t fixupSteps = 0;
  /// With a light-colour texture (FrameDesc::lightColor), directional and spot lights: the march
  /// integrates each lit section in chunks of at most this many 1D samples (about one shadow-map
  /// texel each), each chunk uncoloured times the light's mean colour over it (prefix sums of the
  /// colour along each slice, a pass of its own), and shorter where a chunk would span more than
  /// 0.1 of optical depth. Exact for the colour; a longer chunk ignores more of how the colour and
  /// the fog's attenuation (a spot light's fall-off) vary together inside it, a shorter one costs
  /// more steps. A power of two in 1..4096, default 32 (docs/EPIPOLAR.md, "Coloured shafts").
  std::uint32_t coloredStep = 32;
  /// The resolution of the L_in target (slices and samples are unchanged; the unwarp and the
  /// fix-up run per target pixel), upsampled by the composite. Default Full.
  ScatteringResolution resolution = ScatteringResolution::Full;
  /// A reduced `resolution` runs only while its L_in target keeps at least this many rows; for a
  /// smaller output the next finer one does (Stats::resolutionChange). The upsample's error grows
  /// as a block covers more of the scene, so a resolution measured at one output size is not
  /// accurate enough below it: the profile table sets the rows of the size its row was chosen at.
  /// 0 (default): no floor.
  std::uint32_t minimumRows = 0;
};

/// How a prefiltered shadow map represents the visibility along a light ray (docs/PREFILTERED.md
/// has the memory and accuracy of each). Moments are those of the signed rectified depth, with
/// peters2017's quantization and worst-case bias per variant.
enum class PrefilteredBasis : std::uint32_t {
  Moments4_64,   ///< 4 moments, RGBA16_UNORM with the sparse quantization Θ4* (peters2017 §2.4)
  Moments4_128,  ///< 4 moments, RGBA32F
  Moments6_64,   ///< 6 moments, two A2B10G10R10_UNORM textures with Θ6* (peters2017 §5.4.3)
  Moments6_96,   ///< 6 moments, RGBA16_UNORM + RG16_UNORM with Θ6*
  Moments6_192,  ///< 6 moments, RGBA32F + RG32F
  Fourier32,     ///< klehm2014's 32 Fourier coefficients, an 8-layer RGBA8 array (the baseline)
};

/// Which rectified shadow map rows are built in.
enum class PrefilteredRectification : std::uint32_t {
  /// Projective where klehm2014's matrix keeps every texel within twice the non-linear one's
  /// angle (the epipole well off screen), non-linear otherwise; the stats' note says which ran.
  Automatic,
  NonLinear,   ///< peters2017 §5.1.1: (r, φ, θ), valid for every view
  /// klehm2014 §4.2, one matrix; a frame whose frustum contains the light axis (either way)
  /// cannot use it and runs NonLinear, and the note says so.
  Projective,
};

/// The world distance per texel Δ(v) the transmittance weights of a row assume: that of one
/// reference ray of the slice. A pixel's ray crosses the row's texels at its own pace; with
/// `PrefilteredSettings::rayWeightTaps` = 1 it takes the reference's weights as they are.
enum class PrefilteredSpacing : std::uint32_t {
  MeanTheta,     ///< peters2017 §5.1.1: the inclination halfway through the slice's range
  ReferenceRay,  ///< klehm2014 §3.2: the bisectrix of the slice's smallest and largest Δ
  /// The slice's fastest ray (klehm2014's ω_min, the smallest Δ), from which every ray of the
  /// slice is re-weighted with non-negative coefficients: needed by rayWeightTaps > 1.
  FastestRay,
};

/// How the prefix sums along each row are computed (same result, different cost).
enum class PrefixSumScheme : std::uint32_t {
  RowParallel,    ///< peters2017 Appendix C: 8 threads per row, each writes every 8th texel (coalesced)
  ThreadPerRow,   ///< klehm2014 §3.3: one thread walks a row
  WorkgroupScan,  ///< a workgroup per row: each thread blends a run of texels, a scan joins the runs
                  ///< (equal to the others up to rounding; docs/PREFILTERED.md "Prefix-sum schemes")
};

/// Parameters of the prefiltered technique. Every field is validated per frame; the message of an
/// invalid one names it.
struct PrefilteredSettings {
  PrefilteredBasis basis = PrefilteredBasis::Moments6_64;  ///< default: peters2017 §5.5.3's recommendation
  PrefilteredRectification rectification = PrefilteredRectification::Automatic;
  /// Rectified map rows (epipolar slices), 16..4096, default 512.
  std::uint32_t rows = 512;
  /// Rectified map columns (texels along every view ray of a slice), 16..4096, default 2048: with
  /// the segmented reconstruction the error near the epipole falls with the columns and hardly with
  /// the rows, so the default 1M texels are 512 × 2048 (docs/PREFILTERED.md "Segmented reconstruction").
  std::uint32_t columns = 2048;
  /// Resample a moment shadow map built from the host's with bilinear filtering and peters2017's
  /// Algorithm 2 (two depths per texel) instead of one nearest texel: shafts from straight
  /// silhouettes do not alias. Default true.
  bool filteredResampling = true;
  PrefilteredSpacing spacing = PrefilteredSpacing::FastestRay;
  /// Prefix-sum lookups per pixel and prefix-sum set, 1..8, default 4. 1: the papers' single
  /// lookup with the reference ray's weights. K > 1: K lookups along the pixel's row re-weight the
  /// prefix sums to the pixel's own ray (its transmittance falls faster than the reference's when
  /// it runs closer to the light direction; docs/PREFILTERED.md); needs spacing = FastestRay.
  std::uint32_t rayWeightTaps = 4;
  /// With rayWeightTaps = K > 1: reconstruct the visibility of each of the K segments between the
  /// lookups on its own (the difference of two lookups: that segment's occluders alone) and average
  /// the K results, instead of reconstructing once from their combination. The same linear average,
  /// but each reconstruction sees a quarter of the ray's occluders, so the moment bounds leave less
  /// doubt (docs/PREFILTERED.md "Segmented reconstruction"); K reconstructions per pixel instead of
  /// one. No effect with one lookup. Default true.
  bool segmentedReconstruction = true;
  /// Default WorkgroupScan: its chain of dependent blends per row is 2·columns/128 + 7 long instead of
  /// `columns` (docs/PREFILTERED.md "Prefix-sum schemes").
  PrefixSumScheme prefixSums = PrefixSumScheme::WorkgroupScan;
  /// Moment bases: where the shadow intensity is taken between the sharp lower bound (β = 1,
  /// scattering overestimated) and upper bound (β = 0). true: peters2017 §5.3.1's adaptive
  /// β = (1 + ω_l·ω_p)/2, 0 looking into the light, 1 looking away from it. false: the constant
  /// `overestimation`. Default false: the constant ½ measured lower errors (docs/PREFILTERED.md).
  bool adaptiveOverestimation = false;
  /// β when not adaptive, [0, 1], default 0.5 (the smallest worst-case error, peters2017 §5.3.1).
  float overestimation = 0.5f;
  /// Side in pixels of the block around an on-screen epipole (the projected light, or where the
  /// shafts converge when it is behind the camera) that is ray-marched per pixel with the
  /// Reference's walk instead (klehm2014 Fig. 8). 0..256, default 16; 0 turns the block off.
  std::uint32_t epipoleBlockPixels = 16;
  /// Short rays: a view ray that ends within the first `shortRayColumns` columns of its rectified
  /// row crosses too few texels for any reconstruction (next to the epipole, where a ray runs
  /// almost along the light, and in front of a surface close to the camera) and is ray-marched
  /// with the Reference's walk instead; its stretch across the host's map is as short, so the walk
  /// is too. A criterion in texels, not pixels, so it holds at every output size
  /// (docs/PREFILTERED.md "Short rays"). 0..columns, default 16; 0 turns it off.
  std::uint32_t shortRayColumns = 16;
  /// Row depth bounds: the running min and max of the occluder depths along each rectified row
  /// (RG16_UNORM, 4 bytes per texel, two maps), so that a view ray whose row holds only occluders
  /// in front of it (or none) gets visibility 0 (or 1) exactly instead of the reconstruction, whose
  /// bounds leave doubt there (a closed room's roof over every ray; docs/PREFILTERED.md). Default true.
  bool depthBounds = true;
  /// Trimmed segments (with depthBounds and the segmented reconstruction): each row's min/max tree
  /// beside its texels (about as many texels again) finds the runs at both ends of a segment that
  /// lie wholly in front of the ray or behind it; they count exactly (with the ray's own weights)
  /// and only the columns between them are reconstructed (a ray leaving a roof's shadow into a
  /// window's beam; docs/PREFILTERED.md "Trimmed segments"). Default true.
  bool trimmedSegments = true;
  /// Texel walk (with the trimmed segments): the columns between a trimmed segment's two runs are
  /// walked from their start for up to `texelWalkSteps` steps, each a run the row decides (0 or 1)
  /// or one undecided texel, whose two depths (the filtered resampling's, kept in one more
  /// RGBA16_UNORM map of 8 bytes per texel) give its visibility exactly; only what the walk does
  /// not reach is reconstructed (the edges of a window's beam; docs/PREFILTERED.md "Texel walk").
  /// 0..64, default 8; 0 turns it off.
  std::uint32_t texelWalkSteps = 8;
  /// The resolution of the L_in target (the evaluation runs per target pixel), upsampled by the
  /// composite. Default Full.
  ScatteringResolution resolution = ScatteringResolution::Full;
  /// As EpipolarSettings::minimumRows: the fewest L_in rows a reduced `resolution` runs with.
  std::uint32_t minimumRows = 0;
};

const char* to_string(PrefilteredBasis basis) noexcept;

/// When the techniques' compute pipelines are compiled.
enum class PipelineCreation : std::uint32_t {
  /// Every technique's pipelines in `Context::create` (default): no frame ever compiles one, so
  /// switching profiles or techniques never hitches.
  AtCreate,
  /// A technique's pipelines in the first frame that runs it (a Warning through the message
  /// callback says so), or all of them in `Context::warmUp`: a faster start where only some
  /// techniques run (tools, tests).
  OnFirstUse,
};

/// Context-wide tuning (ContextDesc::tuning); the defaults suit every device.
struct ContextTuning {
  PipelineCreation pipelineCreation = PipelineCreation::AtCreate;  ///< default AtCreate
  /// Threads that share one epipolar sample's ray march: 0 (default) chooses by device, 1 on a CPU
  /// driver (the same work, serially) and 8 on a GPU (a few tens of thousands of marched samples
  /// do not fill one, docs/EPIPOLAR.md); else a power of two up to 64. With 1 the fix-up walks a
  /// directional light's pixels one per thread too; otherwise each pixel's walk is split over 64.
  std::uint32_t marchThreadsPerSample = 0;
  /// L_in targets in R32G32B32A32_SFLOAT for every technique: for comparisons against the Reference
  /// finer than half-float rounding (2⁻¹¹ relative). Default: the epipolar and prefiltered
  /// techniques write R16G16B16A16_SFLOAT (half the memory; docs/INTEGRATION.md "Device memory").
  bool fullFloatTargets = false;
};

}  // namespace tyndall
