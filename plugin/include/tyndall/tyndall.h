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

namespace tyndall {

struct EpipolarSettings;     // tyndall/tuning.h
struct PrefilteredSettings;  // tyndall/tuning.h
struct ContextTuning;        // tyndall/tuning.h
struct Stats;                // tyndall/stats.h, included at the end
struct FrameTimings;         // tyndall/stats.h

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
/// (plugin/src/profiles.cpp, justified in docs/TRADEOFFS-H200.md). Switching needs no new context.
enum class Profile : std::uint32_t {
  Reference,  ///< brute force per pixel, texel by texel through the shadow map (validation)
  High,
  Balanced,
  Performance,
  /// The most accurate of High, Balanced and Performance whose measured GPU time fits
  /// `FrameDesc::autoBudgetMilliseconds` (docs/INTEGRATION.md "Profiles"); see Stats::profileUsed.
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

/// The resolution L_in is computed at (FrameDesc::resolution, else the profile's). Below full the
/// composite upsamples it with a joint bilateral filter on depth (docs/INTEGRATION.md "Reduced
/// resolution"); the Reference always runs at full.
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

/// IMPORTANT: the device must be Vulkan 1.3 (or 1.2 with VK_KHR_dynamic_rendering) with
/// `dynamicRendering` and `dualSrcBlend` enabled; Tyndall cannot query them (validation fails).
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
  /// Its usage flags where the host knows them (0: each input's documented minimum is assumed).
  VkImageUsageFlags usage = 0;  ///< a back buffer with STORAGE lets the composite run in compute

  [[nodiscard]] bool empty() const noexcept { return image == VK_NULL_HANDLE; }
};

struct CameraDesc {
  Mat4 view{};  ///< world → view; right-handed, looking down −Z (GLM's lookAt)
  /// View → clip, depth in [0, 1], perspective; reverse-Z and infinite far are detected. Exactly
  /// the matrix the depth buffer was rendered with.
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
  /// ≥ 0. Directional: irradiance; spot/point: radiant intensity I, reaching d as I / d² · exp(−σ_t d).
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
inline constexpr std::uint32_t kMaxCascades = 4;    ///< a directional light's cascaded shadow maps
inline constexpr std::uint32_t kMaxLights = 8;      ///< FrameDesc::light and up to 7 additional lights
inline constexpr std::uint32_t kMaxTranslucentLayers = 8;  ///< ShadowMapDesc::translucentLayerCount

struct ShadowMapDesc {
  /// Square depth image: D16_UNORM, D32_SFLOAT, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT or
  /// D32_SFLOAT_S8_UINT, usage SAMPLED. Depth 0 nearest the light; texels cleared to 1 are lit.
  /// Outside a directional map's square points are lit; outside a spot's frustum they are dark.
  ImageRef depth;
  /// World → shadow clip, depth in [0, 1], x/y in [−1, 1]; texel (i, j) covers u = (x + 1) / 2 in
  /// [i / N, (i + 1) / N], v likewise with row j.
  Mat4 worldToShadowClip{};
  /// A directional light's cascade (2..kMaxCascades maps, finest first): the view depths
  /// [viewDepthNear, viewDepthFar) it serves, scene units along the camera's −Z. Each cascade
  /// starts where the one before ends; the first also serves what is nearer, the last what is
  /// farther. Ignored with one map and for spot and point lights (docs/INTEGRATION.md "Cascades").
  float viewDepthNear = 0.0f;
  float viewDepthFar = 0.0f;
  /// Optional translucent occluders (opacity α < 1), exact, for the Reference technique
  /// (docs/INTEGRATION.md "Translucent occluders"): the surfaces in front of `depth`, depth-peeled
  /// nearest the light first, one per array layer of an R32G32_SFLOAT image of the map's size holding
  /// (depth, α) per texel, (1, 0) where the texel has no more. `view` is a 2D_ARRAY view of the
  /// translucentLayerCount layers from `arrayLayer` and one more after them, the overflow layer: the
  /// next peel, whose depth is below 1 where a texel has more surfaces than the count. The light
  /// crossing a surface keeps 1 − α of itself. Usage SAMPLED. Every map of a light has them or none.
  ImageRef translucentLayers;
  std::uint32_t translucentLayerCount = 0;  ///< 1..kMaxTranslucentLayers with translucentLayers, else 0
};

/// A light after the frame's first (FrameDesc::additionalLights): the same three inputs the first
/// light takes in FrameDesc, with the same requirements.
struct LightInput {
  LightDesc light;
  std::span<const ShadowMapDesc> shadowMaps;  ///< 1 (directional, spot) or 6 (point)
  ImageRef lightColor;                        ///< optional, as FrameDesc::lightColor
};

struct FrameDesc {
  CameraDesc camera;
  LightDesc light;
  std::span<const MediumComponent> medium;    ///< 1..kMaxMediumComponents; σ_t is their sum
  std::span<const ShadowMapDesc> shadowMaps;  ///< 1..kMaxCascades (directional), 1 (spot), 6 (point)
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
  /// shadowMaps[0]'s UV square (bilinear, clamped; unfiltered outside). Directional lights with
  /// one map and spot lights; cascades or a point light fail with UnsupportedFeature. Any format with SAMPLED_IMAGE_FILTER_LINEAR
  /// (_SRGB is decoded), usage SAMPLED, any size. Costs more: lit sections are walked in short steps.
  ImageRef lightColor;
  /// Optional: more lights, up to kMaxLights − 1. L_in is the sum over `light` and these; each runs
  /// the technique its kind's profile row picks, the view ray's transmittance and the composite
  /// are shared (docs/INTEGRATION.md "Several lights").
  std::span<const LightInput> additionalLights;

  Profile profile = Profile::Balanced;
  float autoBudgetMilliseconds = 4.0f;  ///< Profile::Auto's GPU-time budget (FrameTimings' total), > 0
  std::optional<ScatteringResolution> resolution;  ///< optional: instead of the profile's
  /// Optional overrides for tools and validation (tyndall/tuning.h), read during `record` only:
  /// the technique instead of the profile's (None: the profile's), and its parameters.
  Technique technique = Technique::None;
  const EpipolarSettings* epipolar = nullptr;
  const PrefilteredSettings* prefiltered = nullptr;
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

  /// Rebuilds only the size-dependent resources. IMPORTANT: as for destruction, the GPU no longer
  /// uses this context's work. A failed resize keeps neither size: `record` fails until one succeeds.
  Outcome resize(VkExtent2D outputExtent);

  /// Compiles the pipelines not compiled yet (ContextTuning::pipelineCreation; none by default),
  /// e.g. behind a loading screen.
  Outcome warmUp();

  /// Records this frame's passes into `commandBuffer` (outside a render pass, on a compute and
  /// graphics queue). An invalid frame records nothing and returns the reason.
  /// IMPORTANT: when record is called for frame n, the GPU has finished frame n − maxFramesInFlight
  /// (the host waited on its fence). After a lost device every record fails with
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

#include "tyndall/stats.h"  // what each frame did: Context::stats()
