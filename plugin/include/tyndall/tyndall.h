// Tyndall: light shafts in homogeneous single-scattering media, as a Vulkan post-process.
//
// The host owns the instance, the device, the queues and the submission. Tyndall records its
// passes into the host's command buffer and leaves the back buffer holding
//     out = in · transmittance + in-scattering            (per RGB channel)
// docs/INTEGRATION.md walks through an integration. Technique tuning lives in tyndall/tuning.h.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "tyndall/technique_stats.h"

namespace tyndall {

struct EpipolarSettings;     // tyndall/tuning.h
struct PrefilteredSettings;  // tyndall/tuning.h
struct ContextTuning;        // tyndall/tuning.h

// ----------------------------------------------------------------------------------------------
// Errors: no exception crosses the API, no bad input aborts.
// ----------------------------------------------------------------------------------------------

enum class Status : std::int32_t {
  Success = 0,
  InvalidArgument,     ///< a value out of range, NaN/Inf, null handle, mismatched sizes…
  UnsupportedFormat,   ///< an image format Tyndall cannot read or write for that input
  UnsupportedFeature,  ///< the device or the frame asks for something not available
  VulkanError,         ///< a Vulkan call failed; `Outcome::vkResult` holds its result
};
const char* to_string(Status status) noexcept;  ///< "InvalidArgument", …

/// A status, the Vulkan result where one is involved, and one readable line.
struct Outcome {
  Status status = Status::Success;
  VkResult vkResult = VK_SUCCESS;
  std::string message;

  [[nodiscard]] bool ok() const noexcept { return status == Status::Success; }
  explicit operator bool() const noexcept { return ok(); }
};

/// A value, or the Outcome that says why there is none (vk-bootstrap's Result).
template <class T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}                 // NOLINT: implicit by design
  Result(Outcome failure) : outcome_(std::move(failure)) {}     // NOLINT: implicit by design
  [[nodiscard]] bool ok() const noexcept { return value_.has_value(); }
  explicit operator bool() const noexcept { return ok(); }
  [[nodiscard]] const Outcome& outcome() const noexcept { return outcome_; }
  T& value() & { return *value_; }
  T&& value() && { return std::move(*value_); }

 private:
  std::optional<T> value_;
  Outcome outcome_;
};

enum class Severity : std::uint32_t { Info, Warning, Error };
/// Called for every error and warning (e.g. a pipeline compiled during a frame), on the thread
/// that called `create`, `resize` or `record`.
using MessageCallback = void (*)(Severity severity, const char* message, void* userData);

// ----------------------------------------------------------------------------------------------
// Profiles and techniques
// ----------------------------------------------------------------------------------------------

/// A profile maps to a technique and its parameters through the profile table
/// (plugin/src/profiles.cpp, justified in docs/TRADEOFFS.md). Switching needs no new context.
enum class Profile : std::uint32_t {
  Reference,  ///< brute force per pixel, texel by texel through the shadow map (validation)
  High,
  Balanced,
  Performance,
  /// The most accurate of High, Balanced and Performance whose GPU time, measured by this
  /// context's timestamps, fits `FrameDesc::autoBudgetMilliseconds` (docs/INTEGRATION.md
  /// "Profiles"). `Stats::profileUsed` says which ran.
  Auto,
};

enum class Technique : std::uint32_t {
  None,         ///< nothing recorded (nothing to compute), or: no override
  Reference,    ///< brute force per pixel
  Epipolar,     ///< epipolar sampling with 1D min/max trees (engelhardt2010, yusov2013)
  Prefiltered,  ///< prefiltered moment shadow maps (klehm2014, peters2017); directional lights only
};
const char* to_string(Profile profile) noexcept;
const char* to_string(Technique technique) noexcept;

/// The resolution a technique computes L_in at (FrameDesc::resolution, else the technique's
/// settings: EpipolarSettings/PrefilteredSettings::resolution, the profile table's). Below full, the composite upsamples it with a joint bilateral filter on the
/// depth buffer (docs/INTEGRATION.md "Reduced resolution"); the Reference always runs at full.
enum class ScatteringResolution : std::uint32_t {
  Full = 1,     ///< one L_in per pixel
  Half = 2,     ///< one per 2×2 pixels: a quarter of the per-pixel work and target memory
  Quarter = 4,  ///< one per 4×4 pixels
};
const char* to_string(ScatteringResolution resolution) noexcept;  ///< "full", "half", "quarter"

/// A picture of how the technique sampled the frame (FrameDesc::debugView), drawn over a dimmed
/// grey L_in. Only the epipolar technique draws one.
enum class DebugView : std::uint32_t {
  None,
  EpipolarSamples,  ///< ray-marched samples yellow; blue where the whole ray was found in shadow
  FixedUpPixels,    ///< the pixels the fix-up pass ray-marched, red
};

// ----------------------------------------------------------------------------------------------
// Context creation
// ----------------------------------------------------------------------------------------------

/// IMPORTANT: the device must be Vulkan 1.3 (or 1.2 with VK_KHR_dynamic_rendering) and created
/// with `dynamicRendering` and `dualSrcBlend` enabled; Tyndall cannot query which features the
/// host enabled, so a device without them fails validation, not `create`.
struct ContextDesc {
  VkInstance instance = VK_NULL_HANDLE;                     ///< required
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;         ///< required
  VkDevice device = VK_NULL_HANDLE;                         ///< required
  PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;  ///< required (physical-device queries)
  PFN_vkGetDeviceProcAddr getDeviceProcAddr = nullptr;      ///< required (all device calls)
  std::uint32_t queueFamilyIndex = 0;   ///< the family Tyndall's work is submitted on; compute + graphics
  std::uint32_t maxFramesInFlight = 2;  ///< 1..8: frames the host records ahead of the GPU
  VkExtent2D outputExtent{};            ///< depth and back buffer size, ≥ 1×1; change it with `resize`
  VkFormat backBufferFormat = VK_FORMAT_UNDEFINED;  ///< optional: builds the composite for it up front
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;   ///< optional
  const VkAllocationCallbacks* allocator = nullptr; ///< optional
  MessageCallback messageCallback = nullptr;        ///< optional
  void* messageUserData = nullptr;                  ///< passed back to `messageCallback`
  const ContextTuning* tuning = nullptr;            ///< optional (tyndall/tuning.h); read in `create` only
};

// ----------------------------------------------------------------------------------------------
// Per-frame description
// ----------------------------------------------------------------------------------------------

using Mat4 = std::array<float, 16>;  ///< column-major (GLM's and GLSL's layout), column vectors
using Float3 = std::array<float, 3>;

/// An image the host owns. Tyndall transitions it from `layout` and back before `record` returns.
/// IMPORTANT: Tyndall makes every earlier write to the image (any stage) visible before it reads,
/// and makes its own writes available to every later stage; the host needs no extra barrier.
struct ImageRef {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;  ///< 2D view of mip 0, layer `arrayLayer` (depth: DEPTH aspect only)
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t arrayLayer = 0;       ///< the layer of `image` that `view` shows
  VkExtent2D extent{};
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  ///< current layout; never UNDEFINED for inputs
  /// The usage the image was created with, where the host knows it (0: only each input's
  /// documented minimum is assumed). A back buffer with STORAGE lets the composite run in compute.
  VkImageUsageFlags usage = 0;

  [[nodiscard]] bool empty() const noexcept { return image == VK_NULL_HANDLE; }
};

struct CameraDesc {
  Mat4 view{};  ///< world → view; right-handed, looking down −Z (GLM's lookAt)
  /// View → clip, clip depth in [0, 1]. Standard or reverse-Z, finite or infinite far: detected
  /// from the matrix. Perspective only; exactly the matrix the depth buffer was rendered with.
  Mat4 projection{};
  float infiniteFarSkyDistance = 1000.0f;  ///< scene units sky pixels integrate to with an infinite far, > 0
};

enum class LightType : std::uint32_t {
  Directional,  ///< `direction`; shadowMaps[0] an orthographic light view
  Spot,         ///< `position`, `direction`, cone angles; shadowMaps[0] a perspective frustum
  Point,        ///< `position`; shadowMaps[0..5] six 90° perspective frusta (klehm2014 §3.2)
};

struct LightDesc {
  LightType type = LightType::Directional;
  Float3 direction{0.0f, -1.0f, 0.0f};  ///< the direction light travels (light → scene); any length
  Float3 position{0.0f, 0.0f, 0.0f};    ///< scene units (spot, point)
  Float3 color{1.0f, 1.0f, 1.0f};       ///< linear RGB, each ≥ 0
  /// Directional: irradiance (per scene unit²); spot/point: radiant intensity I, attenuated as
  /// I / d² · exp(−σ_t d). ≥ 0, default 1.
  float intensity = 1.0f;
  float innerConeRadians = 0.5f;  ///< spot: half-angle of full intensity, 0 ≤ inner ≤ outer
  float outerConeRadians = 0.6f;  ///< spot: half-angle where intensity reaches 0, < π/2
};

enum class PhaseFunction : std::uint32_t { Isotropic, Rayleigh, HenyeyGreenstein, CornetteShanks };

/// One component of the homogeneous medium; coefficients per scene unit, linear RGB, each ≥ 0.
struct MediumComponent {
  Float3 scattering{0.0f, 0.0f, 0.0f};  ///< σ_s
  Float3 absorption{0.0f, 0.0f, 0.0f};  ///< σ_a
  PhaseFunction phase = PhaseFunction::Isotropic;
  float g = 0.0f;  ///< Henyey–Greenstein and Cornette–Shanks asymmetry, (−1, 1); > 0 scatters forward
};

inline constexpr std::uint32_t kMaxMediumComponents = 4;
inline constexpr std::uint32_t kMaxShadowMaps = 6;  ///< a point light's six frusta

struct ShadowMapDesc {
  /// Square depth image: D16_UNORM, D32_SFLOAT, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT or
  /// D32_SFLOAT_S8_UINT, usage SAMPLED. Depth 0 nearest the light; texels cleared to 1 are lit.
  /// Outside a directional map's square points are lit; outside a spot's frustum they are dark.
  ImageRef depth;
  /// World → shadow clip, depth in [0, 1], x/y in [−1, 1]; texel (i, j) covers u = (x + 1) / 2 in
  /// [i / N, (i + 1) / N], v likewise with row j.
  Mat4 worldToShadowClip{};
};

struct FrameDesc {
  CameraDesc camera;
  LightDesc light;
  std::span<const MediumComponent> medium;    ///< 1..kMaxMediumComponents; σ_t is their sum
  std::span<const ShadowMapDesc> shadowMaps;  ///< 1 (directional, spot) or 6 (point)
  ImageRef depth;  ///< host depth buffer: outputExtent, a shadow-map depth format, usage SAMPLED
  /// Host back buffer (scene-linear HDR or _SRGB), outputExtent, usage COLOR_ATTACHMENT, a format
  /// with COLOR_ATTACHMENT_BLEND (e.g. R16G16B16A16_SFLOAT, B8G8R8A8_SRGB).
  ImageRef color;
  /// Optional AOVs: L_in alone, and the view ray's transmittance exp(−σ_t s). outputExtent, usage
  /// TRANSFER_DST, a float colour format with BLIT_DST (R32G32B32A32_SFLOAT keeps full precision).
  ImageRef scatteringOutput;
  ImageRef transmittanceOutput;
  DebugView debugView = DebugView::None;  ///< optional, written to `debugOutput` (the AOVs' requirements)
  ImageRef debugOutput;
  /// Optional light-colour texture (stained glass, yusov2013): a linear-RGB filter over
  /// shadowMaps[0]'s UV square (bilinear, clamped; unfiltered outside). Directional and spot lights;
  /// a point light fails with UnsupportedFeature. Any format with SAMPLED_IMAGE_FILTER_LINEAR
  /// (_SRGB is decoded), usage SAMPLED, any size. Costs more: lit sections are walked in short steps.
  ImageRef lightColor;

  Profile profile = Profile::Balanced;
  float autoBudgetMilliseconds = 4.0f;  ///< Profile::Auto's GPU-time budget (FrameTimings' total), > 0
  /// Optional: the resolution of L_in instead of the profile's (or the settings'); the Reference
  /// always runs at full resolution.
  std::optional<ScatteringResolution> resolution;
  /// Optional overrides for tools and validation (tyndall/tuning.h), read during `record` only:
  /// the technique instead of the profile's (None: the profile's), and its parameters.
  Technique technique = Technique::None;
  const EpipolarSettings* epipolar = nullptr;
  const PrefilteredSettings* prefiltered = nullptr;
};

// ----------------------------------------------------------------------------------------------
// Statistics: what ran and why, as data; `techniqueNote` summarises it for people.
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
  EpipolarNeeds2x2,                  ///< epipolar asked for an output under 2×2: the Reference ran
};
const char* to_string(TechniqueChange change) noexcept;

/// Profile::Auto's estimate of each profile's time: the median of its last measured frames under
/// Auto, in milliseconds; empty while unmeasured.
struct AutoEstimates {
  std::optional<double> high, balanced, performance;
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
  std::optional<EpipolarStats> epipolar;        ///< when the epipolar technique ran this frame
  std::optional<PrefilteredStats> prefiltered;  ///< when the prefiltered technique ran this frame
  std::optional<EpipolarCounts> epipolarCounts; ///< once an epipolar frame's counts were read back
  /// A CPU driver (lavapipe) ends a shader invocation's loops after 65,535 iterations; a point
  /// light's texel walk over maps above 4096² can exceed that and come out too dark.
  bool pointLightWalkOverCpuLoopLimit = false;
  bool debugViewDrawn = false;                  ///< false: debugOutput got the dimmed L_in alone
  std::string techniqueNote;                    ///< the above in one line for people; not for parsing
  std::vector<std::string> passesRecorded;      ///< the last `record`'s passes, in order
  /// How the last frame wrote the back buffer: a compute pass (the back buffer has STORAGE usage
  /// and a format compute can write) or a full-screen fragment pass; None when it was left alone.
  CompositePath composite = CompositePath::None;
  /// The resolution L_in was computed at in the last frame (the composite upsampled it below Full).
  ScatteringResolution scatteringResolution = ScatteringResolution::Full;
  std::uint32_t dispatches = 0;  ///< compute dispatches (direct and indirect) the last `record` recorded
  std::uint32_t barriers = 0;    ///< pipeline barriers the last `record` recorded
  FrameTimings lastTimings;                     ///< most recent frame whose timestamps were available
  bool timingsValid = false;                    ///< false until `lastTimings` holds one
  bool timestampsSupported = false;
  std::uint64_t deviceMemoryBytes = 0;  ///< held after the last `record` (targets, technique data)
  AutoEstimates autoEstimateMilliseconds;
};

// ----------------------------------------------------------------------------------------------
// The context
// ----------------------------------------------------------------------------------------------

class Context {
 public:
  /// Creates pipelines and size-independent resources, then the size-dependent ones.
  static Result<std::unique_ptr<Context>> create(const ContextDesc& desc);

  /// IMPORTANT: the host guarantees the GPU no longer uses anything recorded by this context.
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Rebuilds only the size-dependent resources. IMPORTANT: as for destruction, the GPU no
  /// longer uses anything recorded by this context. A failed resize keeps neither size: `record`
  /// fails until a later `resize` succeeds.
  Outcome resize(VkExtent2D outputExtent);

  /// Compiles every pipeline not compiled yet (ContextTuning::pipelineCreation); nothing to do
  /// by default. Call it outside frames, e.g. behind a loading screen.
  Outcome warmUp();

  /// Records this frame's passes into `commandBuffer` (outside a render pass, on a compute and
  /// graphics queue). An invalid frame records nothing and returns the reason.
  /// IMPORTANT: when record is called for frame n, the GPU has finished frame n − maxFramesInFlight
  /// (the host waited on that frame's fence), as in any frames-in-flight loop.
  /// A lost device shows in the timestamps record reads: from then on every record fails with
  /// VK_ERROR_DEVICE_LOST and records nothing (destroy the context with the device).
  Outcome record(VkCommandBuffer commandBuffer, const FrameDesc& frame);

  /// Reads the timestamps of frames completed since they were recorded, without waiting.
  void collectTimings();
  /// Timings read so far and not yet taken, oldest first; clears the list.
  std::vector<FrameTimings> takeCompletedTimings();

  [[nodiscard]] const Stats& stats() const noexcept;

  struct Impl;

 private:
  explicit Context(std::unique_ptr<Impl> impl);
  static Result<std::unique_ptr<Context>> createContext(const ContextDesc& desc);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tyndall
