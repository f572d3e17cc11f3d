// Tyndall: light shafts in homogeneous single-scattering media, as a Vulkan post-process.
//
// The host owns the instance, the device, the queues and the submission. Tyndall records its
// passes into the host's command buffer and leaves the back buffer holding
//     out = in · transmittance + in-scattering            (per RGB channel)
// See docs/INTEGRATION.md for a walk-through.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

namespace tyndall {

// ---------------------------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------------------------

/// What went wrong. Tyndall never throws across its API and never aborts on bad input.
enum class Status : std::int32_t {
  Success = 0,
  InvalidArgument,     ///< a value out of range, NaN/Inf, null handle, mismatched sizes…
  UnsupportedFormat,   ///< an image format Tyndall cannot read or write for that input
  UnsupportedFeature,  ///< the device or the frame asks for something not available
  VulkanError,         ///< a Vulkan call failed; `Outcome::vkResult` holds its result
};

/// Human-readable name of a status ("InvalidArgument", …).
const char* to_string(Status status) noexcept;

/// The result of a call: a status, the Vulkan result where one is involved, and one readable line.
struct Outcome {
  Status status = Status::Success;
  VkResult vkResult = VK_SUCCESS;
  std::string message;

  [[nodiscard]] bool ok() const noexcept { return status == Status::Success; }
  explicit operator bool() const noexcept { return ok(); }
};

enum class Severity : std::uint32_t { Info, Warning, Error };

/// Called for every error Tyndall reports and for warnings (e.g. a pipeline created lazily in a
/// frame). May be called from `create`, `resize` and `record`, on the calling thread.
using MessageCallback = void (*)(Severity severity, const char* message, void* userData);

// ---------------------------------------------------------------------------------------------
// Profiles
// ---------------------------------------------------------------------------------------------

/// Quality profiles. A profile maps to a technique and its parameters through the profile table
/// (plugin/src/profiles.cpp, justified in docs/TRADEOFFS.md). Switching needs no new context.
enum class Profile : std::uint32_t {
  Reference,    ///< brute force per pixel, texel by texel through the shadow map (validation)
  High,
  Balanced,
  Performance,
  /// The most accurate of High, Balanced and Performance whose GPU time, measured by this
  /// context's timestamps, fits `FrameDesc::autoBudgetMilliseconds`: it starts at Balanced, steps
  /// down when the current profile's time exceeds the budget, and up when the better one measured
  /// at most 80% of the budget (or, unmeasured or measured over 300 frames ago, when the current
  /// one uses at most half); it holds each choice 8 frames. `Stats::profileUsed` says which ran.
  Auto,
};

/// A technique: what a profile maps to, and what ran for a frame.
enum class Technique : std::uint32_t {
  None,       ///< nothing recorded (nothing to compute), or: no override
  Reference,  ///< brute force per pixel
  Epipolar,   ///< epipolar sampling (engelhardt2010, yusov2013): samples along epipolar lines, unwarped
  /// Prefiltered single scattering (klehm2014, peters2017): one lookup per pixel in transmittance-
  /// weighted prefix sums over a rectified shadow map. Directional lights only: a frame with a spot
  /// or point light runs Epipolar instead, and Stats::techniqueNote says so.
  Prefiltered,
};

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
  float epipoleDensity = 1.0f;           ///< last / first sample spacing along a slice, [1, 1000]; 1 = uniform
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
  /// of the larger is ray-marched by the fix-up pass: a shaft or colour edge runs between the slices,
  /// narrower than their spacing (fine coloured shafts). (0, 1], default 1 (off): the pixels near
  /// every shaft edge are fixed up, which costs more where shafts are many.
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
};

/// A picture of how the technique sampled the frame, for people tuning it (tyndall-render
/// --debug-view). Drawn over a dimmed grey L_in (luminance / (1 + luminance), times 0.4).
enum class DebugView : std::uint32_t {
  None,
  /// The ray-marched epipolar samples at the pixel each lies in: yellow, or blue where the shadow
  /// test found the whole ray in shadow and set it to zero without marching.
  EpipolarSamples,
  FixedUpPixels,    ///< the pixels the epipolar fix-up pass ray-marched, red
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
};

const char* to_string(Profile profile) noexcept;
const char* to_string(Technique technique) noexcept;
const char* to_string(PrefilteredBasis basis) noexcept;

// ---------------------------------------------------------------------------------------------
// Context creation
// ---------------------------------------------------------------------------------------------

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

/// Everything Tyndall needs from the host, once.
///
/// IMPORTANT: the device must be Vulkan 1.3 (or 1.2 with VK_KHR_dynamic_rendering) and created
/// with the features `dynamicRendering` and `dualSrcBlend` enabled; Tyndall cannot query which
/// features the host enabled, so a device without them fails validation, not `create`.
struct ContextDesc {
  VkInstance instance = VK_NULL_HANDLE;                       ///< required
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;           ///< required
  VkDevice device = VK_NULL_HANDLE;                           ///< required
  PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;    ///< required (physical-device queries)
  PFN_vkGetDeviceProcAddr getDeviceProcAddr = nullptr;        ///< required (all device calls)
  std::uint32_t queueFamilyIndex = 0;  ///< family of the queue the host submits Tyndall's work on; needs compute + graphics
  std::uint32_t maxFramesInFlight = 2; ///< 1..8; number of frames the host records ahead of the GPU
  VkExtent2D outputExtent{};           ///< size of the depth and back buffers, ≥ 1×1; change it with `resize`
  VkFormat backBufferFormat = VK_FORMAT_UNDEFINED; ///< optional: composite pipeline built up front for it
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;             ///< optional
  const VkAllocationCallbacks* allocator = nullptr;           ///< optional
  MessageCallback messageCallback = nullptr;                  ///< optional
  PipelineCreation pipelineCreation = PipelineCreation::AtCreate;  ///< default AtCreate
  /// Threads that share one epipolar sample's ray march: 0 (default) chooses by device, 1 on a CPU
  /// driver (the same work, serially) and 8 on a GPU (a few tens of thousands of marched samples
  /// do not fill one, docs/EPIPOLAR.md); else a power of two up to 64. With 1 the fix-up walks a
  /// directional light's pixels one per thread too; otherwise each pixel's walk is split over 64.
  std::uint32_t marchThreadsPerSample = 0;
  void* messageUserData = nullptr;                            ///< passed back to `messageCallback`
};

// ---------------------------------------------------------------------------------------------
// Per-frame description
// ---------------------------------------------------------------------------------------------

/// Column-major 4×4 matrix (the memory layout of GLM and GLSL), transforming column vectors.
using Mat4 = std::array<float, 16>;
using Float3 = std::array<float, 3>;

/// An image the host owns. Tyndall transitions it from `layout` to what it needs and back to
/// `layout` before `record` returns: the layout on entry is the layout on exit.
/// IMPORTANT: Tyndall makes every earlier write to the image (any stage) visible before it reads,
/// and makes its own writes available to every later stage; the host needs no extra barrier.
struct ImageRef {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;   ///< 2D view of mip 0, layer `arrayLayer` (depth: DEPTH aspect only)
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t arrayLayer = 0;        ///< the layer of `image` that `view` shows
  VkExtent2D extent{};
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  ///< current layout; never UNDEFINED for inputs

  [[nodiscard]] bool empty() const noexcept { return image == VK_NULL_HANDLE; }
};

/// The camera that produced the depth buffer.
struct CameraDesc {
  /// World → view. Right-handed view space, camera looking down −Z (GLM's lookAt).
  Mat4 view{};
  /// View → clip with clip depth in [0, 1] (Vulkan). Standard or reverse-Z, finite or infinite far:
  /// all four are detected from the matrix. Perspective only. Any y orientation: Tyndall inverts
  /// exactly this matrix, so it must be the one the depth buffer was rendered with.
  Mat4 projection{};
  /// Distance in scene units to which sky pixels (depth at the far value) integrate when the
  /// projection's far plane is at infinity. Range (0, ∞), default 1000.
  float infiniteFarSkyDistance = 1000.0f;
};

enum class LightType : std::uint32_t {
  Directional,  ///< uses `direction`; shadowMaps[0] is an orthographic light view
  Spot,         ///< uses `position`, `direction`, cone angles; shadowMaps[0] a perspective frustum
  Point,        ///< uses `position`; shadowMaps[0..5] are six 90° perspective frusta (klehm2014 §3.2)
};

struct LightDesc {
  LightType type = LightType::Directional;
  Float3 direction{0.0f, -1.0f, 0.0f};  ///< unit-length not required; the direction light travels (light → scene)
  Float3 position{0.0f, 0.0f, 0.0f};    ///< scene units (spot, point)
  Float3 color{1.0f, 1.0f, 1.0f};       ///< linear RGB, each ≥ 0
  /// Directional: irradiance E (colour · intensity, per scene unit²); spot/point: radiant
  /// intensity I, attenuated as I / d² · exp(−σ_t d). ≥ 0, default 1.
  float intensity = 1.0f;
  float innerConeRadians = 0.5f;  ///< spot: half-angle of full intensity, 0 ≤ inner ≤ outer
  float outerConeRadians = 0.6f;  ///< spot: half-angle where intensity reaches 0, < π/2
};

enum class PhaseFunction : std::uint32_t { Isotropic, Rayleigh, HenyeyGreenstein, CornetteShanks };

/// One component of the homogeneous medium. Coefficients per scene unit, linear RGB, each ≥ 0.
struct MediumComponent {
  Float3 scattering{0.0f, 0.0f, 0.0f};  ///< σ_s
  Float3 absorption{0.0f, 0.0f, 0.0f};  ///< σ_a
  PhaseFunction phase = PhaseFunction::Isotropic;
  float g = 0.0f;  ///< asymmetry for Henyey–Greenstein and Cornette–Shanks, (−1, 1); > 0 scatters forward
};

/// Maximum number of medium components per frame.
inline constexpr std::uint32_t kMaxMediumComponents = 4;
/// Maximum number of shadow maps (a point light's six frusta).
inline constexpr std::uint32_t kMaxShadowMaps = 6;

/// A shadow map rendered by the host from the light.
struct ShadowMapDesc {
  /// Depth image, square, formats D16_UNORM, D32_SFLOAT, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT or
  /// D32_SFLOAT_S8_UINT, usage SAMPLED. Depth 0 is nearest the light, 1 the far plane (cleared
  /// texels at 1 are lit). Points outside a directional map's square are lit; outside a spot's
  /// frustum they receive no light (keep the frustum around the outer cone).
  ImageRef depth;
  /// World → shadow clip space, clip depth in [0, 1], x/y in [−1, 1] over the map; texel (i, j)
  /// covers u = (x + 1) / 2 ∈ [i / N, (i + 1) / N], v likewise with row j.
  Mat4 worldToShadowClip{};
};

struct FrameDesc {
  CameraDesc camera;
  LightDesc light;
  /// 1..kMaxMediumComponents components; they share the path, so σ_t is their sum.
  std::span<const MediumComponent> medium;
  /// 1 shadow map for directional and spot lights, 6 for point lights.
  std::span<const ShadowMapDesc> shadowMaps;
  /// Host depth buffer, outputExtent, same formats as shadow maps, usage SAMPLED.
  ImageRef depth;
  /// Host back buffer (scene-linear HDR or an sRGB format), outputExtent, usage COLOR_ATTACHMENT,
  /// format with COLOR_ATTACHMENT_BLEND support (e.g. R16G16B16A16_SFLOAT, B8G8R8A8_SRGB).
  ImageRef color;
  /// Optional AOV: receives L_in alone. outputExtent, usage TRANSFER_DST, a float colour format
  /// with BLIT_DST support (R32G32B32A32_SFLOAT keeps full precision). `view` is not used.
  ImageRef scatteringOutput;
  /// Optional AOV: receives the view-ray transmittance exp(−σ_t s). Same requirements.
  ImageRef transmittanceOutput;
  /// Optional debug view (DebugView): written to `debugOutput`, which has the AOVs' requirements.
  /// Only the epipolar technique draws one; otherwise the image receives the dimmed L_in alone and
  /// `Stats::techniqueNote` says so. The debug image is allocated at its first use.
  DebugView debugView = DebugView::None;
  ImageRef debugOutput;
  /// Optional light-colour texture (stained glass, yusov2013 "Colored Light Shafts"): a colour
  /// filter laid over shadowMaps[0]'s UV square (the same u, v as the depth texels); the light
  /// reaching a point is multiplied by its linear RGB there (bilinear, clamped to the edge; outside
  /// the square the light is unfiltered). Directional and spot lights (a point light fails with
  /// UnsupportedFeature). Any colour format with SAMPLED_IMAGE_FILTER_LINEAR (an _SRGB format is
  /// decoded to linear), usage SAMPLED, any size. The techniques walk lit sections in short steps
  /// where it is set (one shadow-map texel for a directional light, one colour texel for a spot
  /// light), so it costs more.
  ImageRef lightColor;

  Profile profile = Profile::Balanced;
  /// GPU-time budget for Profile::Auto in milliseconds (Tyndall's passes, as in
  /// `FrameTimings::totalMilliseconds`), > 0, default 4.
  float autoBudgetMilliseconds = 4.0f;
  /// Optional: runs this technique instead of the profile's (validation, benchmarks). None: the
  /// profile decides.
  Technique technique = Technique::None;
  /// Optional: parameters of the epipolar technique instead of the profile's. Read during
  /// `record` only.
  const EpipolarSettings* epipolar = nullptr;
  /// Optional: parameters of the prefiltered technique instead of the profile's. Read during
  /// `record` only.
  const PrefilteredSettings* prefiltered = nullptr;
};

// ---------------------------------------------------------------------------------------------
// Statistics
// ---------------------------------------------------------------------------------------------

struct PassTiming {
  std::string name;
  double milliseconds = 0.0;
};

/// GPU timings of one earlier frame, read from timestamp queries without waiting.
struct FrameTimings {
  std::uint64_t frameIndex = 0;       ///< the value of `Stats::frameIndex` when it was recorded
  std::vector<PassTiming> passes;     ///< in recording order
  double totalMilliseconds = 0.0;     ///< first pass start to last pass end
};

struct Stats {
  std::uint64_t frameIndex = 0;       ///< frames recorded so far by this context
  Profile requestedProfile = Profile::Balanced;
  /// The profile whose settings ran: the requested one, or the one Auto chose within its budget.
  Profile profileUsed = Profile::Balanced;
  /// The technique that ran. None when the frame needed none: a medium without extinction (the
  /// back buffer is left as it is) or one where nothing scatters (σ_s = 0 or the light off: L_in
  /// is cleared, pass "scattering_clear", and the back buffer attenuated).
  Technique technique = Technique::None;
  /// Why that technique ran (e.g. "profile table: Balanced -> epipolar, 512 slices x 256 samples");
  /// empty when nothing was recorded.
  std::string techniqueNote;
  /// Names of the passes recorded in the last `record` call, in order.
  std::vector<std::string> passesRecorded;
  /// Most recent frame whose timestamps were available; `valid` false until one is.
  FrameTimings lastTimings;
  bool timingsValid = false;
  bool timestampsSupported = false;
  /// Epipolar technique: samples ray-marched (initial step plus depth breaks), from the same
  /// earlier frame as `fixedUpPixelFraction`; 0 until one is known.
  std::uint64_t marchedSamples = 0;
  /// Epipolar technique: samples the refinement would have ray-marched but found in shadow along
  /// their whole view ray from the slice's min/max tree, so set to zero without marching (all of
  /// them, and `marchedSamples` 0, when the light reaches no visible point); same frame.
  std::uint64_t shadowedSamples = 0;
  /// Epipolar technique: fraction of the pixels the fix-up pass ray-marched, from the same
  /// earlier frame as `lastTimings`; negative until one is known.
  double fixedUpPixelFraction = -1.0;
  /// Device memory the context holds after the last `record` (targets, technique textures and
  /// buffers, spare sets kept for profile switches), in bytes.
  std::uint64_t deviceMemoryBytes = 0;
  /// Profile::Auto's view of the profiles it chooses between, High, Balanced and Performance in that
  /// order: the median of each one's last measured frames under Auto in milliseconds, negative
  /// while unmeasured. It is what Auto compares with the budget (the context's own timestamps).
  std::array<double, 3> autoEstimateMilliseconds{-1.0, -1.0, -1.0};
};

// ---------------------------------------------------------------------------------------------
// The context
// ---------------------------------------------------------------------------------------------

class Context {
 public:
  /// Creates pipelines and size-independent resources, then the size-dependent ones for
  /// `desc.outputExtent`. On failure `out` stays empty and the outcome says why.
  static Outcome create(const ContextDesc& desc, std::unique_ptr<Context>& out);

  /// IMPORTANT: the host guarantees the GPU no longer uses anything recorded by this context.
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Rebuilds only the size-dependent resources. The host guarantees the GPU no longer uses
  /// anything recorded by this context (as for destruction).
  Outcome resize(VkExtent2D outputExtent);

  /// Compiles every pipeline not compiled yet (see PipelineCreation); nothing to do after an
  /// AtCreate context's creation. Call it outside frames, e.g. behind a loading screen.
  Outcome warmUp();

  /// Records this frame's passes into `commandBuffer` (outside any render pass, compute and
  /// graphics capable queue). Frames use `maxFramesInFlight` slots in turn.
  /// IMPORTANT: when record is called for frame n, the GPU has finished frame n − maxFramesInFlight
  /// (the host waited on that frame's fence), as in any frames-in-flight loop.
  /// An invalid frame records nothing and returns the reason.
  Outcome record(VkCommandBuffer commandBuffer, const FrameDesc& frame);

  /// Reads the timestamps of frames that have completed since they were recorded, without
  /// waiting. Call it after the host waited on its fences to pick up the last frames' timings.
  void collectTimings();

  /// Timings read so far and not yet taken, oldest first; clears the list.
  std::vector<FrameTimings> takeCompletedTimings();

  [[nodiscard]] const Stats& stats() const noexcept;

  struct Impl;

 private:
  explicit Context(std::unique_ptr<Impl> impl);
  static Outcome createContext(const ContextDesc& desc, std::unique_ptr<Context>& out);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tyndall
