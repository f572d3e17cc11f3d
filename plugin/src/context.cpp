// The context: what is created once, what is rebuilt on resize, and the per-frame recording.
#include <array>
#include <cstdio>
#include <cstring>
#include <string>
#include <new>
#include <optional>

#include "auto_profile.h"
#include "composite/composite_pass.h"
#include "composite/light_sum_pass.h"
#include "epipolar/epipolar_technique.h"
#include "frame_setup.h"
#include "gpu.h"
#include "prefiltered/prefiltered_technique.h"
#include "profiles.h"
#include "reference/reference_technique.h"
#include "retire_queue.h"
#include "technique_selection.h"
#include "timing.h"


namespace tyndall {

namespace {

// Layout in which a host depth image is sampled: kept when it already allows sampling,
// otherwise the read-only depth-stencil layout (valid for every depth format).
VkImageLayout sampledDepthLayout(VkImageLayout entry) {
  switch (entry) {
    case VK_IMAGE_LAYOUT_GENERAL:
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
      return entry;
    default:
      return VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  }
}

// Layout in which a host colour image is sampled: kept when it already allows sampling.
VkImageLayout sampledColorLayout(VkImageLayout entry) {
  return entry == VK_IMAGE_LAYOUT_GENERAL || entry == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
             ? entry
             : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

VkImageLayout keepGeneral(VkImageLayout entry, VkImageLayout wanted) {
  return entry == VK_IMAGE_LAYOUT_GENERAL ? entry : wanted;
}

// Whatever the host did before: every earlier write, any stage.
ImageUse hostBefore(const ImageRef& image) {
  return {image.layout, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT};
}
// Whatever the host does after: any access, any stage.
ImageUse hostAfter(const ImageRef& image) {
  return {image.layout, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
          VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT};
}

// The host's depth buffer is read by a technique's compute passes, by the composite's fragment
// shader (T) and by the T AOV's compute pass.
constexpr VkPipelineStageFlags kDepthReaders =
    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
// The L_in target is sampled by the composite, a fragment or a compute shader (whichever path the
// back buffer allows), then copied to the AOVs.
constexpr VkPipelineStageFlags kTargetSamplers =
    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags kTargetReaders = kTargetSamplers | VK_PIPELINE_STAGE_TRANSFER_BIT;
// Transfer destination: a frame without in-scattering clears L_in instead of running a technique.
constexpr VkImageUsageFlags kTargetUsage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                           VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
// The L_in target has the format of the technique that writes it (technique.h: half floats for
// the approximate ones, full floats for the Reference). The AOVs and the debug view are full
// floats: they are compared against double-precision references. A full-float, full-resolution
// L_in target holds T for the T AOV's copy once L_in has been composited and copied
// (Context::Impl::recordAovs); any other goes through the AOV image.
constexpr VkFormat kOutputFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
// Frames a retired L_in target is kept as a spare (about two seconds at 60 Hz).
constexpr std::uint32_t kSpareTargetFrames = 120;

// A 1×1 image bound in place of an input the frame lacks (every descriptor must be valid), cleared
// to `value` in the first frame that binds it: the clear now, the hand-over to compute reads in
// `acquire`.
void clearPlaceholderOnce(const Gpu& gpu, VkCommandBuffer cmd, const OwnedImage& image, const VkClearColorValue& value,
                          bool& cleared, BarrierBatch& acquire) {
  if (cleared) return;
  const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  const ImageUse transferWrite{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                               VK_ACCESS_TRANSFER_WRITE_BIT};
  imageBarrier(gpu, cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, {VK_IMAGE_LAYOUT_UNDEFINED, compute, 0}, transferWrite);
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  gpu.vk.vkCmdClearColorImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
  acquire.image(image.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, transferWrite,
                {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, compute, VK_ACCESS_SHADER_READ_BIT});
  cleared = true;
}

// How close to the view, in target pixels, a local light's image keeps L_in at full resolution:
// its 1/distance peak spreads over the upsample's taps, which reach one block from each pixel;
// a few blocks out the peak has fallen to what the bilateral blend interpolates.
constexpr double kLocalLightImageMarginBlocks = 4.0;

// Whether a spot or point light that scatters projects within kLocalLightImageMarginBlocks target
// pixels of the view at `resolution` (ResolutionChange::LocalLightInView).
bool localLightImageNearView(const FrameSetup& setup, VkExtent2D extent, ScatteringResolution resolution) {
  const double margin = kLocalLightImageMarginBlocks * static_cast<double>(resolution);
  for (const LightSetup& light : setup.lights) {
    if (light.skipped != LightSkipped::No || !light.imagePixel) continue;
    const glm::dvec2 p = *light.imagePixel;
    if (p.x >= -margin && p.y >= -margin && p.x <= extent.width + margin && p.y <= extent.height + margin) return true;
  }
  return false;
}

// One instance of each technique: a light's.
struct TechniqueSet {
  ReferenceTechnique reference;
  EpipolarTechnique epipolar;
  PrefilteredTechnique prefiltered;
  std::array<ScatteringTechnique*, 3> all() { return {&reference, &epipolar, &prefiltered}; }
  ScatteringTechnique* techniqueFor(Technique technique) {
    switch (technique) {
      case Technique::Reference: return &reference;
      case Technique::Epipolar: return &epipolar;
      case Technique::Prefiltered: return &prefiltered;
      case Technique::None: break;
    }
    return nullptr;
  }
};

}  // namespace

struct Context::Impl {
  ContextDesc desc;
  ContextTuning tuning;
  Gpu gpu;
  VkExtent2D extent{};
  VkSampler nearest = VK_NULL_HANDLE;
  VkSampler linear = VK_NULL_HANDLE;   // the light-colour texture's
  OwnedImage white;                    // 1×1 white: the light-colour texture of frames without one
  bool whiteCleared = false;
  OwnedImage noTranslucentLayers;      // 1×1, one layer of (1, 0): the layers of maps without any
  bool noTranslucentLayersCleared = false;
  std::vector<MappedBuffer> constants;  // one per frame slot
  GpuTimer timer;
  TechniqueSet first;  // FrameDesc::light's: compiles the pipelines every light's instance uses
  // The techniques of each additional light (FrameDesc::additionalLights[i] uses additional[i]):
  // created at the first frame with that light, recording with the first light's pipelines
  // (ScatteringTechnique::sharePipelinesOf), each with its own constants per frame slot.
  struct LightTechniques : TechniqueSet {
    std::vector<MappedBuffer> constants;  // one per frame slot
  };
  std::array<std::unique_ptr<LightTechniques>, kMaxLights - 1> additional;
  /// Light `index`'s instance of `technique` (0: FrameDesc::light's), null for Technique::None.
  ScatteringTechnique* instanceFor(std::size_t index, Technique technique) {
    return index == 0 ? first.techniqueFor(technique) : additional[index - 1]->techniqueFor(technique);
  }
  /// Light `index`'s FrameConstants buffer of frame slot `slot`.
  const MappedBuffer& constantsFor(std::size_t index, std::uint32_t slot) const {
    return index == 0 ? constants[slot] : additional[index - 1]->constants[slot];
  }
  /// Calls `f` with every technique instance there is: the first light's, then the additional ones'.
  template <class F>
  void forEachInstance(F&& f) {
    for (ScatteringTechnique* t : first.all()) f(*t);
    for (auto& light : additional) {
      if (!light) continue;
      for (ScatteringTechnique* t : light->all()) f(*t);
    }
  }
  LightSumPass lightSum;
  CompositePass composite;
  AutoProfile autoProfile;
  std::uint64_t lastTimedFrame = ~0ull;  // the latest frame whose time went to autoProfile
  // Size-dependent.
  /// The L_in target, at `resolution` (targetExtentFor). A frame of another resolution retires it
  /// (or destroys it, when no frame has used it yet); a retired target serves again as a spare for
  /// kSpareTargetFrames frames, so that a context switching between profiles of two resolutions
  /// (Auto) does not allocate at every switch, and holds one target once it has settled.
  OwnedImage scattering;
  ScatteringResolution resolution = ScatteringResolution::Full;
  // The profiles' techniques' (ContextTuning::fullFloatTargets), until a frame's lead technique
  // asks another.
  VkFormat scatteringFormat = kHalfScatteringFormat;
  bool scatteringUsed = false;
  RetireQueue<OwnedImage> retiredTargets;
  // Full resolution and full floats, for the AOVs of a target that is neither; at the first such frame.
  OwnedImage aovTarget;
  // An additional light's L_in before the light sum adds it to `scattering`, one per format: at the
  // first frame with an additional light of that format that runs, of the target's extent (one of
  // another extent is retired).
  std::array<OwnedImage, 2> lightTargets;
  OwnedImage& lightTargetFor(VkFormat format) { return lightTargets[format == kFullScatteringFormat ? 1 : 0]; }
  /// Whether the AOVs are copied from `aovTarget` rather than from the L_in target itself.
  bool aovsViaOwnImage() const { return resolution != ScatteringResolution::Full || scatteringFormat != kOutputFormat; }
  Outcome resizeFailure;  // why there are no size-dependent resources (until a resize succeeds)
  OwnedImage debugImage;  // created at the first frame that draws a debug view
  Stats stats;

  void report(Severity severity, const std::string& message) const {
    if (desc.messageCallback != nullptr) desc.messageCallback(severity, message.c_str(), desc.messageUserData);
  }
  Outcome fail(Outcome outcome) const {
    report(Severity::Error, std::string(to_string(outcome.status)) + ": " + outcome.message);
    return outcome;
  }

  Outcome createSizeIndependent();
  /// What every technique instance is created with (the first light's and each additional one's).
  TechniqueResources techniqueResources() const {
    TechniqueResources resources{nearest, linear, desc.maxFramesInFlight};
    resources.marchThreadsPerSample = tuning.marchThreadsPerSample;
    resources.scatteringFormat = tuning.fullFloatTargets ? kFullScatteringFormat : kHalfScatteringFormat;
    return resources;
  }
  /// The techniques and constants of additional light `index` (≥ 1), created the first time.
  Outcome ensureAdditionalLight(std::size_t index);
  Outcome warmUp();
  /// The pipelines `technique` needs for this frame's light, compiled now if they are not yet.
  Outcome ensurePipelines(Technique technique, const FrameDesc& frame);
  Outcome createSizeDependent();
  void destroySizeDependent();
  /// Makes `scattering` the target of `wanted`'s resolution in `format` (a spare or a new image; on
  /// failure the old one stays).
  Outcome useTarget(ScatteringResolution wanted, VkFormat format);
  void destroyAll();
  Outcome record(VkCommandBuffer cmd, const FrameDesc& frame);
  /// A light that runs its technique this frame: its index (0: FrameDesc::light), the frame as
  /// that light sees it, and its instance of the technique.
  struct LightRun {
    std::size_t index = 0;
    FrameDesc frame;
    ScatteringTechnique* technique = nullptr;
  };
  void recordScattering(VkCommandBuffer cmd, std::uint32_t slot, const FrameDesc& frame,
                        const std::vector<LightRun>& runs);
  // `release` receives the barriers that hand the inputs back to the host; `target` (the L_in
  // target or the light target) is left in GENERAL, written by compute shaders.
  void recordTechnique(VkCommandBuffer cmd, std::uint32_t slot, const LightRun& run, const OwnedImage& target,
                       VkImageLayout depthLayout, BarrierBatch& release);
  void recordAovs(VkCommandBuffer cmd, std::uint32_t slot, const FrameDesc& frame, bool fromTargets);
};

Outcome Context::Impl::createSizeIndependent() {
  if (Outcome o = createSampler(gpu, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, nearest); !o) return o;
  if (Outcome o = createSampler(gpu, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, linear); !o) return o;
  if (Outcome o = createImage(gpu, VK_FORMAT_R8G8B8A8_UNORM, {1, 1},
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, white);
      !o) {
    return o;
  }
  if (Outcome o = createImageArray(gpu, VK_FORMAT_R32G32_SFLOAT, {1, 1}, 1,
                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, noTranslucentLayers);
      !o) {
    return o;
  }

  constants.resize(desc.maxFramesInFlight);
  for (MappedBuffer& buffer : constants) {
    if (Outcome o = createMappedBuffer(gpu, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, buffer); !o) {
      return o;
    }
  }
  if (Outcome o = timer.create(gpu, desc.maxFramesInFlight, desc.queueFamilyIndex); !o) return o;
  stats.timestampsSupported = timer.supported();
  const TechniqueResources resources = techniqueResources();
  for (ScatteringTechnique* technique : first.all()) {
    if (Outcome o = technique->create(gpu, resources); !o) return o;
  }
  if (Outcome o = composite.create(gpu, nearest, desc.maxFramesInFlight); !o) return o;
  if (Outcome o = lightSum.create(gpu, desc.maxFramesInFlight * (kMaxLights - 1)); !o) return o;
  if (tuning.pipelineCreation == PipelineCreation::AtCreate) {
    if (Outcome o = warmUp(); !o) return o;
  }
  if (desc.backBufferFormat != VK_FORMAT_UNDEFINED) {
    if ((gpu.optimalFeatures(desc.backBufferFormat) & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT) == 0) {
      return failure(Status::UnsupportedFormat, "backBufferFormat has no COLOR_ATTACHMENT_BLEND support");
    }
    if (Outcome o = composite.ensurePipeline(gpu, desc.backBufferFormat); !o) return o;
    if (compositeFormatRunsInCompute(gpu, desc.backBufferFormat)) {
      if (Outcome o = composite.ensureComputePipeline(gpu, desc.backBufferFormat); !o) return o;
    }
  }
  return {};
}

Outcome Context::Impl::ensureAdditionalLight(std::size_t index) {
  std::unique_ptr<LightTechniques>& light = additional[index - 1];
  if (light) return {};
  auto created = std::make_unique<LightTechniques>();
  const TechniqueResources resources = techniqueResources();
  // Destroys what was created when a step fails: nothing half-built is kept.
  auto discard = [&](Outcome failed) {
    for (ScatteringTechnique* t : created->all()) t->destroy(gpu);
    for (MappedBuffer& buffer : created->constants) destroyBuffer(gpu, buffer);
    return failed;
  };
  for (ScatteringTechnique* t : created->all()) {
    if (Outcome o = t->create(gpu, resources); !o) return discard(o);
  }
  created->reference.sharePipelinesOf(first.reference);
  created->epipolar.sharePipelinesOf(first.epipolar);
  created->prefiltered.sharePipelinesOf(first.prefiltered);
  created->constants.resize(desc.maxFramesInFlight);
  for (MappedBuffer& buffer : created->constants) {
    if (Outcome o = createMappedBuffer(gpu, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, buffer); !o) {
      return discard(o);
    }
  }
  light = std::move(created);
  report(Severity::Info, "techniques for light " + std::to_string(index) + " created");
  return {};
}

Outcome Context::Impl::warmUp() {
  for (ScatteringTechnique* technique : first.all()) {
    if (Outcome o = technique->createPipelines(gpu); !o) return o;
  }
  return {};
}

Outcome Context::Impl::ensurePipelines(Technique technique, const FrameDesc& frame) {
  ScatteringTechnique* t = first.techniqueFor(technique);
  if (t == nullptr) return {};
  bool compiled = false;
  const Outcome outcome = t->ensurePipelines(gpu, frame, compiled);
  if (compiled) {
    report(Severity::Warning, std::string("pipelines of the ") + to_string(technique) +
                                  " technique compiled during record (PipelineCreation::OnFirstUse; call warmUp "
                                  "to compile them up front)");
  }
  return outcome;
}

Outcome Context::Impl::createSizeDependent() {
  scatteringUsed = false;
  return createImage(gpu, scatteringFormat, targetExtentFor(extent, resolution), kTargetUsage, scattering);
}

Outcome Context::Impl::useTarget(ScatteringResolution wanted, VkFormat format) {
  if (wanted == resolution && format == scatteringFormat) return {};
  const VkExtent2D size = targetExtentFor(extent, wanted);
  OwnedImage next;
  if (std::optional<OwnedImage> spare = retiredTargets.take([&](const OwnedImage& image) {
        return image.extent.width == size.width && image.extent.height == size.height && image.format == format;
      })) {
    next = *spare;
  } else if (Outcome o = createImage(gpu, format, size, kTargetUsage, next); !o) {
    return o;
  }
  if (scatteringUsed) {
    retiredTargets.retire(stats.frameIndex, scattering);
  } else {
    destroyImage(gpu, scattering);
  }
  scattering = next;
  scatteringUsed = false;
  resolution = wanted;
  scatteringFormat = format;
  return {};
}

void Context::Impl::destroySizeDependent() {
  forEachInstance([&](ScatteringTechnique& technique) { technique.destroySizeDependent(gpu); });
  for (OwnedImage& target : lightTargets) destroyImage(gpu, target);
  destroyImage(gpu, debugImage);
  destroyImage(gpu, aovTarget);
  retiredTargets.destroyAll([&](OwnedImage& image) { destroyImage(gpu, image); });
  destroyImage(gpu, scattering);
}

// Reverse order of creation.
void Context::Impl::destroyAll() {
  if (gpu.device == VK_NULL_HANDLE) return;
  destroySizeDependent();
  for (auto it = additional.rbegin(); it != additional.rend(); ++it) {
    if (!*it) continue;
    for (ScatteringTechnique* technique : (*it)->all()) technique->destroy(gpu);
    for (MappedBuffer& buffer : (*it)->constants) destroyBuffer(gpu, buffer);
    it->reset();
  }
  lightSum.destroy(gpu);
  composite.destroy(gpu);
  const std::array<ScatteringTechnique*, 3> techniques = first.all();
  for (auto it = techniques.rbegin(); it != techniques.rend(); ++it) (*it)->destroy(gpu);
  timer.destroy(gpu);
  for (MappedBuffer& buffer : constants) destroyBuffer(gpu, buffer);
  constants.clear();
  destroyImage(gpu, white);
  destroyImage(gpu, noTranslucentLayers);
  if (linear != VK_NULL_HANDLE) gpu.vk.vkDestroySampler(gpu.device, linear, gpu.allocator);
  linear = VK_NULL_HANDLE;
  if (nearest != VK_NULL_HANDLE) gpu.vk.vkDestroySampler(gpu.device, nearest, gpu.allocator);
  nearest = VK_NULL_HANDLE;
}

Result<std::unique_ptr<Context>> Context::create(const ContextDesc& desc) {
  try {
    return createContext(desc);
  } catch (const std::bad_alloc&) {
    Outcome outcome = vkFailed("create", VK_ERROR_OUT_OF_HOST_MEMORY);
    outcome.message = "create: out of host memory";
    return outcome;
  }
}

Result<std::unique_ptr<Context>> Context::createContext(const ContextDesc& desc) {
  auto impl = std::make_unique<Impl>();
  impl->desc = desc;
  if (desc.tuning != nullptr) impl->tuning = *desc.tuning;
  impl->scatteringFormat = impl->techniqueResources().scatteringFormat;
  impl->desc.tuning = nullptr;  // not kept: the host's struct may not outlive this call
  auto fail = [&](Status status, const std::string& message) {
    return impl->fail(failure(status, message));
  };
  if (desc.instance == VK_NULL_HANDLE || desc.physicalDevice == VK_NULL_HANDLE || desc.device == VK_NULL_HANDLE) {
    return fail(Status::InvalidArgument, "ContextDesc needs instance, physicalDevice and device");
  }
  if (desc.getInstanceProcAddr == nullptr || desc.getDeviceProcAddr == nullptr) {
    return fail(Status::InvalidArgument, "ContextDesc needs getInstanceProcAddr and getDeviceProcAddr");
  }
  if (desc.maxFramesInFlight < 1 || desc.maxFramesInFlight > 8) {
    return fail(Status::InvalidArgument, "maxFramesInFlight must be in 1..8");
  }
  if (const std::uint32_t t = impl->tuning.marchThreadsPerSample; t > 64 || (t & (t - 1)) != 0) {
    return fail(Status::InvalidArgument, "marchThreadsPerSample must be 0 (by device) or a power of two up to 64");
  }
  if (desc.outputExtent.width == 0 || desc.outputExtent.height == 0) {
    return fail(Status::InvalidArgument, "outputExtent must be at least 1x1");
  }

  Gpu& gpu = impl->gpu;
  if (const char* missing = gpu.vk.load(desc.instance, desc.device, desc.getInstanceProcAddr, desc.getDeviceProcAddr)) {
    return fail(Status::UnsupportedFeature, std::string("the device does not provide ") + missing);
  }
  gpu.physicalDevice = desc.physicalDevice;
  gpu.device = desc.device;
  gpu.pipelineCache = desc.pipelineCache;
  gpu.allocator = desc.allocator;
  gpu.vk.vkGetPhysicalDeviceProperties(desc.physicalDevice, &gpu.properties);
  gpu.vk.vkGetPhysicalDeviceMemoryProperties(desc.physicalDevice, &gpu.memory);

  std::uint32_t familyCount = 0;
  gpu.vk.vkGetPhysicalDeviceQueueFamilyProperties(desc.physicalDevice, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  gpu.vk.vkGetPhysicalDeviceQueueFamilyProperties(desc.physicalDevice, &familyCount, families.data());
  const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  if (desc.queueFamilyIndex >= familyCount || (families[desc.queueFamilyIndex].queueFlags & needed) != needed) {
    return fail(Status::InvalidArgument, "queueFamilyIndex must name a graphics and compute queue family");
  }
  if (VK_API_VERSION_MINOR(gpu.properties.apiVersion) < 2 && VK_API_VERSION_MAJOR(gpu.properties.apiVersion) == 1) {
    return fail(Status::UnsupportedFeature, "Tyndall needs a Vulkan 1.2 or later device");
  }

  impl->extent = desc.outputExtent;
  Outcome outcome = impl->createSizeIndependent();
  if (outcome) outcome = impl->createSizeDependent();
  if (!outcome) {
    impl->destroyAll();
    return impl->fail(outcome);
  }
  return std::unique_ptr<Context>(new Context(std::move(impl)));
}

Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Context::~Context() {
  if (impl_) impl_->destroyAll();
}

Outcome Context::resize(VkExtent2D outputExtent) {
  if (outputExtent.width == 0 || outputExtent.height == 0) {
    return impl_->fail(failure(Status::InvalidArgument, "resize: outputExtent must be at least 1x1"));
  }
  if (outputExtent.width == impl_->extent.width && outputExtent.height == impl_->extent.height) return {};
  impl_->destroySizeDependent();
  impl_->extent = outputExtent;
  if (Outcome o = impl_->createSizeDependent(); !o) {
    // Nothing half-built is kept, and no size counts as built: the next resize, to any size,
    // builds again, and frames fail until one does.
    impl_->destroySizeDependent();
    impl_->extent = {};
    impl_->resizeFailure = o;
    return impl_->fail(o);
  }
  impl_->resizeFailure = {};
  return {};
}

Outcome Context::record(VkCommandBuffer commandBuffer, const FrameDesc& frame) {
  if (commandBuffer == VK_NULL_HANDLE) {
    return impl_->fail(failure(Status::InvalidArgument, "record: commandBuffer is null"));
  }
  // No exception crosses the API; the only one the recording can raise is an allocation failure
  // of the host heap (stats strings and vectors).
  try {
    return impl_->record(commandBuffer, frame);
  } catch (const std::bad_alloc&) {
    Outcome outcome = vkFailed("record", VK_ERROR_OUT_OF_HOST_MEMORY);
    outcome.message = "record: out of host memory";
    return outcome;
  }
}

Outcome Context::Impl::record(VkCommandBuffer cmd, const FrameDesc& frame) {
  if (!resizeFailure.ok()) {
    Outcome o = resizeFailure;
    o.message = "record: no output target since the last resize failed (" + o.message + "); resize again";
    return fail(o);
  }
  FrameSetup setup;
  if (Outcome o = prepareFrame(gpu, extent, frame, setup); !o) return fail(o);
  const bool computeComposite = compositeRunsInCompute(gpu, frame.color);
  if (setup.attenuates && !(computeComposite ? composite.hasComputePipeline(frame.color.format)
                                             : composite.hasPipeline(frame.color.format))) {
    report(Severity::Warning, "composite pipeline for back-buffer format " +
                                  std::to_string(static_cast<int>(frame.color.format)) +
                                  " built during record; pass ContextDesc::backBufferFormat to build it up front");
    if (Outcome o = computeComposite ? composite.ensureComputePipeline(gpu, frame.color.format)
                                     : composite.ensurePipeline(gpu, frame.color.format);
        !o) {
      return fail(o);
    }
  }

  const std::uint32_t slot = static_cast<std::uint32_t>(stats.frameIndex % desc.maxFramesInFlight);
  // The slot's previous frame is read before anything is recorded: a lost device shows there.
  if (Outcome o = timer.readSlot(gpu, slot); !o) return fail(o);
  // Auto picks a profile from the times its earlier frames measured (auto_profile.h).
  const Profile profile = frame.profile == Profile::Auto
                              ? autoProfile.choose(stats.frameIndex, frame.autoBudgetMilliseconds)
                              : frame.profile;

  // Per light: the technique its kind's profile row (or the frame) asks for, and what runs. The
  // frame's first light that runs (FrameDesc::light unless it is skipped) is the one the stats'
  // frame-level fields, the note and the debug view describe.
  const std::size_t lightCount = setup.lights.size();
  std::vector<const ProfileChoice*> choices(lightCount);
  std::vector<Technique> requestedTechniques(lightCount);
  std::vector<TechniqueSelection> selections(lightCount);
  std::size_t lead = lightCount;
  for (std::size_t i = 0; i < lightCount; ++i) {
    const LightSetup& light = setup.lights[i];
    choices[i] = &profileChoice(profile, lightClassOf(light.light.type));
    requestedTechniques[i] = frame.technique != Technique::None ? frame.technique : choices[i]->technique;
    selections[i] = selectTechnique({requestedTechniques[i], light.light.type, !light.lightColor.empty(), extent,
                                     light.skipped == LightSkipped::No,
                                     hasCascades(light.light.type, light.shadowMaps.size()),
                                     !light.shadowMaps.empty() && light.shadowMaps[0].translucentLayerCount > 0});
    if (lead == lightCount && selections[i].technique != Technique::None) lead = i;
  }
  if (lead == lightCount) lead = 0;
  const ProfileChoice& choice = *choices[lead];
  const Technique requested = requestedTechniques[lead];
  const TechniqueSelection selection = selections[lead];
  const Technique technique = selection.technique;
  std::string note = frame.technique != Technique::None ? std::string("technique set by the frame: ") +
                                                              to_string(frame.technique)
                                                        : std::string(choice.note);
  if (frame.profile == Profile::Auto) {
    char line[160];
    const double estimate = autoProfile.estimateMs(profile);
    if (estimate >= 0.0) {
      std::snprintf(line, sizeof(line), "Auto within %.3g ms -> %s (measured %.3g ms); ",
                    double(frame.autoBudgetMilliseconds), to_string(profile), estimate);
    } else {
      std::snprintf(line, sizeof(line), "Auto within %.3g ms -> %s (not measured yet); ",
                    double(frame.autoBudgetMilliseconds), to_string(profile));
    }
    note = line + note;
  }
  if (selection.change == TechniqueChange::NothingScatters) {
    note = techniqueChangeNote(selection.change);
  } else if (selection.change != TechniqueChange::None) {
    note += std::string("; ") + techniqueChangeNote(selection.change);
  }
  // lavapipe ends every loop of a shader invocation once its loops together have run 65,535
  // iterations (docs/REFERENCE.md "Loop budget on lavapipe"): a point light's walk above 4096²
  // maps, a directional light's over four cascades of 8192², can run past it. Said, not hidden: the
  // result is wrong there.
  bool overLoopLimit = false;
  for (std::size_t i = 0; i < lightCount; ++i) {
    const LightSetup& light = setup.lights[i];
    overLoopLimit = overLoopLimit ||
                    (gpu.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU &&
                     (selections[i].technique == Technique::Reference || selections[i].technique == Technique::Epipolar) &&
                     !light.shadowMaps.empty() &&
                     walkCanOverrunCpuLoopBudget(light.light.type, light.shadowMaps.size(),
                                                 light.shadowMaps[0].depth.extent.width,
                                                 light.shadowMaps[0].translucentLayerCount));
  }
  if (overLoopLimit) {
    note += "; CPU driver: a light's texel walk over its maps (their size and count) can exceed lavapipe's 65,535 "
            "loop iterations per invocation and come out too dark";
  }

  // The lights that run, each with the frame as it sees it; the lead light draws the debug view.
  std::vector<LightRun> runs;
  for (std::size_t i = 0; i < lightCount; ++i) {
    if (selections[i].technique == Technique::None) continue;
    const LightSetup& light = setup.lights[i];
    LightRun run{i, frame, nullptr};
    run.frame.light = light.light;
    run.frame.shadowMaps = light.shadowMaps;
    run.frame.lightColor = light.lightColor;
    run.frame.additionalLights = {};
    if (i != lead) run.frame.debugView = DebugView::None;
    if (Outcome o = ensurePipelines(selections[i].technique, run.frame); !o) return fail(o);
    if (i > 0) {
      if (Outcome o = ensureAdditionalLight(i); !o) return fail(o);
    }
    run.technique = instanceFor(i, selections[i].technique);
    runs.push_back(run);
  }
  ScatteringTechnique* const leadTechnique = runs.empty() ? nullptr : runs.front().technique;
  const bool drawsDebugView =
      frame.debugView != DebugView::None && leadTechnique != nullptr && leadTechnique->drawsDebugViews();
  if (frame.debugView != DebugView::None && !drawsDebugView) note += "; debug view: drawn by the epipolar technique only";
  if (drawsDebugView && debugImage.image == VK_NULL_HANDLE) {
    if (Outcome o = createImage(gpu, kOutputFormat, extent, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                debugImage);
        !o) {
      return fail(o);
    }
    report(Severity::Info, "debug view image allocated");
  }
  // The L_in target at the lead technique's resolution, which every light's technique runs at, and
  // in its format; a frame without one keeps the current target.
  stats.resolutionChange = ResolutionChange::None;
  if (leadTechnique != nullptr) {
    const ResolutionRequest asked = leadTechnique->resolution(runs.front().frame, choice);
    ScatteringResolution wanted = resolutionForRows(asked.resolution, asked.minimumRows, extent.height);
    if (wanted != asked.resolution) stats.resolutionChange = ResolutionChange::BelowMinimumRows;
    if (wanted != ScatteringResolution::Full && localLightImageNearView(setup, extent, wanted)) {
      wanted = ScatteringResolution::Full;
      stats.resolutionChange = ResolutionChange::LocalLightInView;
    }
    if (Outcome o = useTarget(wanted, leadTechnique->scatteringFormat()); !o) return fail(o);
  }
  retiredTargets.release(stats.frameIndex, desc.maxFramesInFlight + kSpareTargetFrames,
                         [&](OwnedImage& image) { destroyImage(gpu, image); });
  forEachInstance([&](ScatteringTechnique& t) { t.releaseRetired(gpu, stats.frameIndex, desc.maxFramesInFlight); });
  const bool reduced = resolution != ScatteringResolution::Full;
  if (aovsViaOwnImage() && aovTarget.image == VK_NULL_HANDLE &&
      (!frame.scatteringOutput.empty() || !frame.transmittanceOutput.empty())) {
    if (Outcome o = createImage(gpu, kOutputFormat, extent, kTargetUsage, aovTarget); !o) return fail(o);
    report(Severity::Info,
           "full-resolution AOV image allocated (the L_in target is at reduced resolution or in half floats)");
  }
  for (std::size_t k = 1; k < runs.size(); ++k) {
    const VkFormat format = runs[k].technique->scatteringFormat();
    OwnedImage& lightTarget = lightTargetFor(format);
    if (lightTarget.extent.width == scattering.extent.width && lightTarget.extent.height == scattering.extent.height) {
      continue;
    }
    OwnedImage next;
    if (Outcome o = createImage(gpu, format, scattering.extent, kTargetUsage, next); !o) return fail(o);
    if (lightTarget.image != VK_NULL_HANDLE) retiredTargets.retire(stats.frameIndex, lightTarget);
    lightTarget = next;
    report(Severity::Info, "light target allocated (several lights run)");
  }
  // A half-float target holds L_in scaled to its range; a full-float one as it is (its AOVs are
  // copied from it).
  const float targetScale = scatteringFormat == kHalfScatteringFormat ? scatteringTargetScale(setup) : 1.0f;
  for (LightSetup& light : setup.lights) {
    light.constants.target_scale = targetScale;
    light.constants.target_unscale = 1.0f / targetScale;
    light.constants.target_extent = glm::uvec2(scattering.extent.width, scattering.extent.height);
    light.constants.target_stride = static_cast<std::uint32_t>(resolution);
    light.constants.target_offset = light.constants.target_stride / 2;
  }
  std::vector<TechniqueReport> reports(lightCount);
  for (const LightRun& run : runs) {
    const FrameInputs inputs{run.frame, *choices[run.index], extent, scattering.extent, slot, stats.frameIndex,
                             desc.maxFramesInFlight};
    if (Outcome o = run.technique->prepare(gpu, inputs, reports[run.index]); !o) return fail(o);
  }
  if (leadTechnique != nullptr) {
    note += reports[lead].note;
    if (reduced) note += std::string("; L_in at ") + to_string(resolution) + " resolution, upsampled by the composite";
    if (stats.resolutionChange == ResolutionChange::LocalLightInView) {
      note += "; L_in at full resolution: a spot or point light's image is in view (its peak would spread over the "
              "upsampling blocks)";
    }
    if (stats.resolutionChange == ResolutionChange::BelowMinimumRows) {
      note += std::string("; L_in at ") + to_string(resolution) +
              " resolution: the output is too small for the one asked (fewer target rows than minimumRows)";
    }
  }
  if (lightCount > 1) {
    std::string summary = "; " + std::to_string(lightCount) + " lights:";
    for (std::size_t i = 0; i < lightCount; ++i) {
      summary += std::string(i == 0 ? " " : ", ") +
                 (setup.lights[i].skipped != LightSkipped::No ? std::string("skipped (") + to_string(setup.lights[i].skipped) + ")"
                                                               : std::string(to_string(selections[i].technique)));
    }
    note += summary;
  }

  stats.requestedProfile = frame.profile;
  stats.profileUsed = profile;
  stats.requestedTechnique = requested;
  stats.techniqueSetByFrame = frame.technique != Technique::None;
  stats.techniqueChange = selection.change;
  stats.epipolar = reports[lead].epipolar;
  stats.prefiltered = reports[lead].prefiltered;
  stats.lights.resize(lightCount);
  for (std::size_t i = 0; i < lightCount; ++i) {
    LightStats& l = stats.lights[i];
    l.type = setup.lights[i].light.type;
    l.requestedTechnique = requestedTechniques[i];
    l.technique = selections[i].technique;
    l.techniqueChange = selections[i].change;
    l.skipped = setup.lights[i].skipped;
    l.epipolar = reports[i].epipolar;
    l.prefiltered = reports[i].prefiltered;
    l.translucentLayers = selections[i].technique == Technique::Reference && !setup.lights[i].shadowMaps.empty()
                              ? setup.lights[i].shadowMaps[0].translucentLayerCount
                              : 0;
  }
  stats.walkOverCpuLoopLimit = overLoopLimit;
  stats.debugViewDrawn = drawsDebugView;
  stats.scatteringResolution = resolution;
  stats.scatteringFormat = scatteringFormat;
  stats.passesRecorded.clear();
  gpu.dispatches = 0;
  gpu.barriers = 0;
  timer.beginFrame(gpu, cmd, slot, stats.frameIndex);
  // Counts the slot's previous frame left, whichever technique runs now (the first light's).
  for (ScatteringTechnique* t : first.all()) t->readBack(slot, stats);
  // Every light's Reference reports translucent layers that overflowed.
  stats.translucentLayersOverflowed = false;
  forEachInstance([&](ScatteringTechnique& t) { t.readBackFlags(slot, stats); });

  if (!setup.attenuates) {
    // σ_t = 0: out = in, L_in = 0, T = 1. Only requested AOVs are written.
    stats.technique = Technique::None;
    stats.techniqueChange = TechniqueChange::NoExtinction;
    stats.composite = CompositePath::None;
    stats.epipolar.reset();
    stats.prefiltered.reset();
    for (LightStats& l : stats.lights) {
      l.technique = Technique::None;
      l.techniqueChange = TechniqueChange::NoExtinction;
      l.epipolar.reset();
      l.prefiltered.reset();
    }
    stats.debugViewDrawn = false;
    stats.techniqueNote = techniqueChangeNote(TechniqueChange::NoExtinction);
    recordAovs(cmd, slot, frame, false);
  } else {
    stats.technique = technique;  // None when nothing scatters
    stats.composite = computeComposite ? CompositePath::Compute : CompositePath::Fragment;
    stats.techniqueNote = note;
    for (std::size_t i = 0; i < lightCount; ++i) {
      if (i == 0 || selections[i].technique != Technique::None) {
        std::memcpy(constantsFor(i, slot).mapped, &setup.lights[i].constants, sizeof(gpu::FrameConstants));
      }
    }
    recordScattering(cmd, slot, frame, runs);
    scatteringUsed = true;
    recordAovs(cmd, slot, frame, true);
    // The host's depth buffer, which recordScattering acquired: read by the technique, the
    // composite and the T AOV's pass.
    imageBarrier(gpu, cmd, frame.depth.image, barrierAspect(frame.depth.format), frame.depth.arrayLayer,
                 {sampledDepthLayout(frame.depth.layout), kDepthReaders, 0}, hostAfter(frame.depth));
  }

  if (const FrameTimings* latest = timer.latest()) {
    stats.lastTimings = *latest;
    stats.timingsValid = true;
    if (latest->frameIndex != lastTimedFrame) {
      autoProfile.measured(latest->frameIndex, latest->totalMilliseconds);
      lastTimedFrame = latest->frameIndex;
    }
  }
  auto estimate = [&](Profile p) -> std::optional<double> {
    const double ms = autoProfile.estimateMs(p);
    return ms >= 0.0 ? std::optional<double>(ms) : std::nullopt;
  };
  stats.autoEstimateMilliseconds = {estimate(Profile::High), estimate(Profile::Balanced), estimate(Profile::Performance)};
  stats.deviceMemoryBytes = gpu.allocatedBytes;
  stats.dispatches = gpu.dispatches;
  stats.barriers = gpu.barriers;
  ++stats.frameIndex;
  return {};
}

void Context::Impl::recordScattering(VkCommandBuffer cmd, std::uint32_t slot, const FrameDesc& frame,
                                     const std::vector<LightRun>& runs) {
  const VkImageLayout depthLayout = sampledDepthLayout(frame.depth.layout);
  // The techniques' releases and the back buffer's acquisition for the composite: one barrier.
  BarrierBatch release;
  // The depth buffer stays acquired until the T AOV (Impl::record releases it).
  imageBarrier(gpu, cmd, frame.depth.image, barrierAspect(frame.depth.format), frame.depth.arrayLayer,
               hostBefore(frame.depth), {depthLayout, kDepthReaders, VK_ACCESS_SHADER_READ_BIT});
  if (runs.empty()) {
    // Nothing scatters: L_in = 0 without a technique (the previous frame's reads finish first).
    const ImageUse transferWrite{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                 VK_ACCESS_TRANSFER_WRITE_BIT};
    timer.beginPass(gpu, cmd, "scattering_clear");
    imageBarrier(gpu, cmd, scattering.image, VK_IMAGE_ASPECT_COLOR_BIT, 0,
                 {VK_IMAGE_LAYOUT_UNDEFINED, kTargetReaders, 0}, transferWrite);
    const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    gpu.vk.vkCmdClearColorImage(cmd, scattering.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
    timer.endPass(gpu, cmd);
    stats.passesRecorded.emplace_back("scattering_clear");
    imageBarrier(gpu, cmd, scattering.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, transferWrite,
                 {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kTargetSamplers,
                  VK_ACCESS_SHADER_READ_BIT});
  } else {
    // The first light writes the L_in target; each later one its own target, then adds it.
    const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    // With several lights each light's passes are named "lightI/…" (I its index in the frame), so
    // that their timings say which light they belong to.
    const bool named = stats.lights.size() > 1;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const std::string prefix = named ? "light" + std::to_string(runs[k].index) + "/" : std::string();
      const std::size_t firstPass = stats.passesRecorded.size();
      timer.setPassPrefix(prefix);
      OwnedImage& lightTarget = lightTargetFor(runs[k].technique->scatteringFormat());
      recordTechnique(cmd, slot, runs[k], k == 0 ? scattering : lightTarget, depthLayout, release);
      for (std::size_t p = firstPass; p < stats.passesRecorded.size(); ++p) {
        stats.passesRecorded[p].insert(0, prefix);
      }
      if (k == 0) {
        timer.setPassPrefix({});
        continue;
      }
      BarrierBatch toSum;
      toSum.image(lightTarget.image, VK_IMAGE_ASPECT_COLOR_BIT, 0,
                  {VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_SHADER_WRITE_BIT},
                  {VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_SHADER_READ_BIT});
      toSum.image(scattering.image, VK_IMAGE_ASPECT_COLOR_BIT, 0,
                  {VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_SHADER_WRITE_BIT},
                  {VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT});
      timer.beginPass(gpu, cmd, "light_sum");
      toSum.record(gpu, cmd);
      lightSum.record(gpu, cmd, slot * (kMaxLights - 1) + static_cast<std::uint32_t>(k - 1), scattering,
                      lightTarget);
      timer.endPass(gpu, cmd);
      timer.setPassPrefix({});
      stats.passesRecorded.push_back(prefix + "light_sum");
    }
    release.image(scattering.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, {VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_SHADER_WRITE_BIT},
                  {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kTargetSamplers, VK_ACCESS_SHADER_READ_BIT});
  }

  // Composite into the back buffer: in place by compute where it is a storage image, else blended.
  timer.beginPass(gpu, cmd, "composite");
  if (stats.composite == CompositePath::Compute) {
    const ImageUse readWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                             VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    release.image(frame.color.image, VK_IMAGE_ASPECT_COLOR_BIT, frame.color.arrayLayer, hostBefore(frame.color),
                  readWrite);
    release.record(gpu, cmd);
    composite.recordCompute(gpu, cmd, slot, constants[slot].buffer, frame.depth, depthLayout, scattering.view,
                            frame.color);
    timer.endPass(gpu, cmd);
    stats.passesRecorded.emplace_back("composite");
    imageBarrier(gpu, cmd, frame.color.image, VK_IMAGE_ASPECT_COLOR_BIT, frame.color.arrayLayer,
                 {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                 hostAfter(frame.color));
    return;
  }
  const VkImageLayout attachment = keepGeneral(frame.color.layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  const VkPipelineStageFlags output = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkAccessFlags blend = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  release.image(frame.color.image, VK_IMAGE_ASPECT_COLOR_BIT, frame.color.arrayLayer, hostBefore(frame.color),
                {attachment, output, blend});
  release.record(gpu, cmd);
  composite.record(gpu, cmd, slot, constants[slot].buffer, frame.depth, depthLayout, scattering.view,
                   frame.color, attachment);
  timer.endPass(gpu, cmd);
  stats.passesRecorded.emplace_back("composite");
  imageBarrier(gpu, cmd, frame.color.image, VK_IMAGE_ASPECT_COLOR_BIT, frame.color.arrayLayer,
               {attachment, output, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT}, hostAfter(frame.color));
}

// One light's technique's passes into `target`, left in GENERAL for the caller to hand on.
// The depth buffer is acquired (recordScattering), in `depthLayout`.
void Context::Impl::recordTechnique(VkCommandBuffer cmd, std::uint32_t slot, const LightRun& run,
                                    const OwnedImage& target, VkImageLayout depthLayout, BarrierBatch& release) {
  const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  const FrameDesc& frame = run.frame;
  ScatteringTechnique& technique = *run.technique;

  // Each pass's timestamps are written before its barriers: a CPU driver (lavapipe) takes a
  // timestamp when it next flushes, and a barrier flushes, so the stamps then bracket the work.
  const char* singlePass = technique.singlePassName();
  if (singlePass != nullptr) timer.beginPass(gpu, cmd, singlePass);
  // The technique's inputs and target in one barrier. Tyndall's target: the previous frame's reads
  // must finish before it is overwritten; the old contents are discarded.
  BarrierBatch acquire;
  acquire.image(target.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, {VK_IMAGE_LAYOUT_UNDEFINED, kTargetReaders, 0},
                {VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_SHADER_WRITE_BIT});

  // Host inputs: depth buffer and shadow maps, sampled by the compute pass.
  ScatteringBindings bindings;
  bindings.constants = constantsFor(run.index, slot).buffer;
  bindings.depth = frame.depth.view;
  bindings.depthLayout = depthLayout;
  bindings.light = frame.light.type;
  bindings.scattering = target.view;
  // The light-colour texture, or the white texel (cleared once, in the first frame that needs it).
  if (!frame.lightColor.empty()) {
    bindings.lightColor = frame.lightColor.view;
    bindings.lightColorLayout = sampledColorLayout(frame.lightColor.layout);
    bindings.hasLightColor = true;
    acquire.image(frame.lightColor.image, VK_IMAGE_ASPECT_COLOR_BIT, frame.lightColor.arrayLayer,
                  hostBefore(frame.lightColor), {bindings.lightColorLayout, compute, VK_ACCESS_SHADER_READ_BIT});
  } else {
    clearPlaceholderOnce(gpu, cmd, white, {{1.0f, 1.0f, 1.0f, 1.0f}}, whiteCleared, acquire);
    bindings.lightColor = white.view;
    bindings.lightColorLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  }
  for (std::size_t i = 0; i < frame.shadowMaps.size(); ++i) {
    const ImageRef& map = frame.shadowMaps[i].depth;
    bindings.shadowMaps[i] = map.view;
    bindings.shadowLayouts[i] = sampledDepthLayout(map.layout);
    acquire.image(map.image, barrierAspect(map.format), map.arrayLayer, hostBefore(map),
                  {bindings.shadowLayouts[i], compute, VK_ACCESS_SHADER_READ_BIT});
    // The translucent layers and the overflow layer after them.
    const ImageRef& layers = frame.shadowMaps[i].translucentLayers;
    if (!layers.empty()) {
      bindings.translucentLayers[i] = layers.view;
      bindings.translucentLayouts[i] = sampledColorLayout(layers.layout);
      acquire.image(layers.image, VK_IMAGE_ASPECT_COLOR_BIT, layers.arrayLayer, hostBefore(layers),
                    {bindings.translucentLayouts[i], compute, VK_ACCESS_SHADER_READ_BIT},
                    frame.shadowMaps[i].translucentLayerCount + 1);
    }
  }
  clearPlaceholderOnce(gpu, cmd, noTranslucentLayers, {{1.0f, 0.0f, 0.0f, 0.0f}}, noTranslucentLayersCleared, acquire);
  bindings.noTranslucentLayers = noTranslucentLayers.view;

  if (frame.debugView != DebugView::None && technique.drawsDebugViews()) {
    bindings.debug = debugImage.view;
    bindings.debugView = frame.debugView;
    acquire.image(debugImage.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_TRANSFER_BIT, 0},
                  {VK_IMAGE_LAYOUT_GENERAL, compute, VK_ACCESS_SHADER_WRITE_BIT});
  }
  acquire.record(gpu, cmd);
  technique.record(gpu, cmd, RecordTarget{slot, bindings, target.extent, timer, stats.passesRecorded});
  if (singlePass != nullptr) {
    timer.endPass(gpu, cmd);
    stats.passesRecorded.emplace_back(singlePass);
  }
  // The inputs go back to the host with the caller's barriers.
  if (!frame.lightColor.empty()) {
    release.image(frame.lightColor.image, VK_IMAGE_ASPECT_COLOR_BIT, frame.lightColor.arrayLayer,
                  {bindings.lightColorLayout, compute, 0}, hostAfter(frame.lightColor));
  }
  for (std::size_t i = 0; i < frame.shadowMaps.size(); ++i) {
    const ImageRef& map = frame.shadowMaps[i].depth;
    release.image(map.image, barrierAspect(map.format), map.arrayLayer, {bindings.shadowLayouts[i], compute, 0},
                  hostAfter(map));
    const ImageRef& layers = frame.shadowMaps[i].translucentLayers;
    if (!layers.empty()) {
      release.image(layers.image, VK_IMAGE_ASPECT_COLOR_BIT, layers.arrayLayer, {bindings.translucentLayouts[i], compute, 0},
                    hostAfter(layers), frame.shadowMaps[i].translucentLayerCount + 1);
    }
  }
}


// Copies L_in and T to the host's AOV images (blit: converts to their format), or, when
// nothing was computed, clears them to L_in = 0 and T = 1. T has no target of its own: once L_in
// is composited and copied, the full-float image L_in was copied from receives T from the
// composite's own formula, then is copied.
void Context::Impl::recordAovs(VkCommandBuffer cmd, std::uint32_t slot, const FrameDesc& frame, bool fromTargets) {
  if (frame.scatteringOutput.empty() && frame.transmittanceOutput.empty() && frame.debugOutput.empty()) return;

  const char* pass = fromTargets ? "aov_output" : "aov_clear";
  timer.beginPass(gpu, cmd, pass);
  // One host output: acquired for the transfer, filled by `fill` (a blit or a clear), released.
  auto write = [&](const ImageRef& output, auto&& fill) {
    const VkImageLayout layout = keepGeneral(output.layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    const ImageUse transferWrite{layout, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT};
    imageBarrier(gpu, cmd, output.image, VK_IMAGE_ASPECT_COLOR_BIT, output.arrayLayer, hostBefore(output),
                 transferWrite);
    fill(layout);
    imageBarrier(gpu, cmd, output.image, VK_IMAGE_ASPECT_COLOR_BIT, output.arrayLayer, transferWrite,
                 hostAfter(output));
  };
  // `from`: the part of `source` that covers the output (a debug view at reduced resolution is
  // scaled up, each of its texels to its block).
  auto blit = [&](VkImage source, VkExtent2D from, const ImageRef& output, VkImageLayout layout) {
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {static_cast<std::int32_t>(from.width), static_cast<std::int32_t>(from.height), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, output.arrayLayer, 1};
    region.dstOffsets[1] = {static_cast<std::int32_t>(extent.width), static_cast<std::int32_t>(extent.height), 1};
    gpu.vk.vkCmdBlitImage(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, output.image, layout, 1, &region,
                          VK_FILTER_NEAREST);
  };
  auto clear = [&](const ImageRef& output, VkImageLayout layout, float value, float alpha) {
    const VkClearColorValue color{{value, value, value, alpha}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, output.arrayLayer, 1};
    gpu.vk.vkCmdClearColorImage(cmd, output.image, layout, &color, 1, &range);
  };

  // The full-resolution, full-float image the AOVs are copied from: the L_in target itself where it
  // is both, else the AOV image, which first receives L_in (upsampled) as the composite added it.
  // `target`: how the composite (or the previous frame) left it; then as each step below leaves it.
  const bool viaOwnImage = aovsViaOwnImage();
  const OwnedImage& full = viaOwnImage ? aovTarget : scattering;
  ImageUse target = viaOwnImage ? ImageUse{VK_IMAGE_LAYOUT_UNDEFINED, kTargetReaders, 0}
                                : ImageUse{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kTargetSamplers, 0};
  const ImageUse computeWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT};
  const VkImageLayout depthLayout = sampledDepthLayout(frame.depth.layout);
  for (const ImageRef* output : {&frame.scatteringOutput, &frame.transmittanceOutput}) {
    if (output->empty()) continue;
    const bool isTransmittance = output == &frame.transmittanceOutput;
    write(*output, [&](VkImageLayout layout) {
      // L_in's alpha is 0, as every technique writes it.
      if (!fromTargets) {
        return isTransmittance ? clear(*output, layout, 1.0f, 1.0f) : clear(*output, layout, 0.0f, 0.0f);
      }
      // A frame in which nothing scatters cleared L_in: its AOV is that zero, without a copy.
      if (!isTransmittance && stats.technique == Technique::None) return clear(*output, layout, 0.0f, 0.0f);
      if (isTransmittance || viaOwnImage) {
        // L_in's reads (the composite's, its copy's) finish before the image is overwritten.
        imageBarrier(gpu, cmd, full.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, {VK_IMAGE_LAYOUT_UNDEFINED, target.stage, 0},
                     computeWrite);
        if (isTransmittance) {
          composite.recordTransmittance(gpu, cmd, slot, constants[slot].buffer, frame.depth, depthLayout, full.view,
                                        extent);
        } else {
          composite.recordScatteringAov(gpu, cmd, slot, constants[slot].buffer, frame.depth, depthLayout,
                                        scattering.view, full.view, extent);
        }
        target = computeWrite;
      }
      // The blit reads the image in the layout transfers prefer.
      const ImageUse transferRead{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                  VK_ACCESS_TRANSFER_READ_BIT};
      imageBarrier(gpu, cmd, full.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, target, transferRead);
      target = transferRead;
      blit(full.image, extent, *output, layout);
    });
  }
  if (!frame.debugOutput.empty()) {
    // The debug view, when one was drawn (GENERAL, written by compute); otherwise black.
    const bool drawn = fromTargets && stats.debugViewDrawn;
    write(frame.debugOutput, [&](VkImageLayout layout) {
      if (!drawn) return clear(frame.debugOutput, layout, 0.0f, 1.0f);
      imageBarrier(gpu, cmd, debugImage.image, VK_IMAGE_ASPECT_COLOR_BIT, 0,
                   {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                   {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT});
      blit(debugImage.image, scattering.extent, frame.debugOutput, layout);
    });
  }
  timer.endPass(gpu, cmd);
  stats.passesRecorded.emplace_back(pass);
}

Outcome Context::warmUp() {
  if (Outcome o = impl_->warmUp(); !o) return impl_->fail(o);
  return {};
}

void Context::collectTimings() {
  impl_->timer.harvestAll(impl_->gpu);
  if (const FrameTimings* latest = impl_->timer.latest()) {
    impl_->stats.lastTimings = *latest;
    impl_->stats.timingsValid = true;
  }
}

std::vector<FrameTimings> Context::takeCompletedTimings() { return impl_->timer.takeCompleted(); }

const Stats& Context::stats() const noexcept { return impl_->stats; }

}  // namespace tyndall
