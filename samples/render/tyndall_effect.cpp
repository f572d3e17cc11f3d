#include "tyndall_effect.h"

#include <cmath>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

namespace tyndall::samples {

namespace {

static_assert(host::kMaxSceneCascades == kMaxCascades);

Mat4 toMat4(const glm::mat4& m) {
  Mat4 out{};
  std::memcpy(out.data(), glm::value_ptr(m), sizeof(out));
  return out;
}

Float3 toFloat3(const glm::dvec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

ImageRef toImageRef(const host::HostImage& image) {
  ImageRef ref;
  ref.image = image.image;
  ref.view = image.view;
  ref.format = image.format;
  ref.extent = image.extent;
  ref.layout = image.layout;
  ref.usage = image.usage;  // 0 where the host does not report it; the back buffer's STORAGE bit picks the composite
  return ref;
}

float radians(double degrees) { return static_cast<float>(degrees * M_PI / 180.0); }

PhaseFunction toPhase(host::PhaseType type) {
  switch (type) {
    case host::PhaseType::Rayleigh: return PhaseFunction::Rayleigh;
    case host::PhaseType::HenyeyGreenstein: return PhaseFunction::HenyeyGreenstein;
    case host::PhaseType::CornetteShanks: return PhaseFunction::CornetteShanks;
    case host::PhaseType::Isotropic: break;
  }
  return PhaseFunction::Isotropic;
}

}  // namespace

LightDesc toLightDesc(const host::Light& light) {
  LightDesc desc;
  switch (light.type) {
    case host::LightType::Directional: desc.type = LightType::Directional; break;
    case host::LightType::Spot: desc.type = LightType::Spot; break;
    case host::LightType::Point: desc.type = LightType::Point; break;
  }
  desc.direction = toFloat3(light.direction);
  desc.position = toFloat3(light.position);
  desc.color = toFloat3(light.color);
  desc.intensity = static_cast<float>(light.intensity);
  desc.innerConeRadians = radians(light.innerConeDegrees);
  desc.outerConeRadians = radians(light.outerConeDegrees);
  return desc;
}

std::vector<MediumComponent> toMedium(const std::vector<host::MediumComponent>& medium) {
  std::vector<MediumComponent> out;
  for (const host::MediumComponent& c : medium) {
    MediumComponent component;
    component.scattering = toFloat3(c.scattering);
    component.absorption = toFloat3(c.absorption);
    component.phase = toPhase(c.phase);
    component.g = static_cast<float>(c.g);
    out.push_back(component);
  }
  return out;
}

ContextDesc contextDescFor(host::Device& device, const host::RenderSettings& settings) {
  ContextDesc desc;
  desc.instance = device.instance();
  desc.physicalDevice = device.physicalDevice();
  desc.device = device.device();
  desc.getInstanceProcAddr = device.getInstanceProcAddr();
  desc.getDeviceProcAddr = device.getDeviceProcAddr();
  desc.queueFamilyIndex = device.queueFamily();
  desc.maxFramesInFlight = settings.framesInFlight;
  desc.outputExtent = {settings.width, settings.height};
  desc.backBufferFormat = settings.backBufferFormat;
  return desc;
}

std::unique_ptr<TyndallEffect> TyndallEffect::create(host::Device& device, const host::RenderSettings& settings,
                                                     Profile profile, std::string& error,
                                                     PipelineCreation pipelineCreation,
                                                     std::uint32_t marchThreadsPerSample, bool fullFloatTargets) {
  auto effect = std::unique_ptr<TyndallEffect>(new TyndallEffect());
  effect->profile_ = profile;
  ContextDesc desc = contextDescFor(device, settings);
  const ContextTuning tuning{pipelineCreation, marchThreadsPerSample, fullFloatTargets};
  desc.tuning = &tuning;
  desc.messageCallback = &TyndallEffect::onMessage;
  desc.messageUserData = effect.get();
  Result<std::unique_ptr<Context>> context = Context::create(desc);
  if (!context) {
    error = "tyndall: " + context.outcome().message;
    return nullptr;
  }
  effect->context_ = std::move(context).value();
  return effect;
}

void TyndallEffect::onMessage(Severity severity, const char* message, void* user) {
  auto* self = static_cast<TyndallEffect*>(user);
  const char* prefix = severity == Severity::Error ? "error: " : severity == Severity::Warning ? "warning: " : "";
  self->messages_.push_back(std::string(prefix) + message);
}

FrameDesc makeFrameDesc(const host::PostProcessInputs& inputs, Profile profile, FrameStorage& storage) {
  const host::Scene& scene = *inputs.scene;
  storage.medium = toMedium(scene.medium);
  const auto toShadowMaps = [](const std::vector<host::HostShadowMap>& maps) {
    std::vector<ShadowMapDesc> out;
    for (const host::HostShadowMap& map : maps) {
      ShadowMapDesc& desc =
          out.emplace_back(ShadowMapDesc{toImageRef(map.depth), toMat4(map.worldToShadowClip), map.viewDepthNear,
                                         map.viewDepthFar});
      if (map.translucentLayerCount > 0) {
        desc.translucentLayers = toImageRef(map.translucentLayers);
        desc.translucentLayerCount = map.translucentLayerCount;
      }
    }
    return out;
  };
  storage.shadowMaps = toShadowMaps(inputs.shadowMaps);
  // Every light's maps first: additionalLights' spans point into them, so they must not move after.
  storage.additionalShadowMaps.clear();
  for (const host::LightInputs& light : inputs.additionalLights) {
    storage.additionalShadowMaps.push_back(toShadowMaps(light.shadowMaps));
  }
  storage.additionalLights.clear();
  for (std::size_t i = 0; i < inputs.additionalLights.size(); ++i) {
    const host::LightInputs& light = inputs.additionalLights[i];
    storage.additionalLights.push_back(
        {toLightDesc(*light.light), storage.additionalShadowMaps[i], toImageRef(light.lightColor)});
  }

  FrameDesc frame;
  frame.camera.view = toMat4(inputs.view);
  frame.camera.projection = toMat4(inputs.projection);
  frame.camera.infiniteFarSkyDistance = static_cast<float>(scene.camera.farPlane);
  frame.light = toLightDesc(scene.light);
  frame.medium = storage.medium;
  frame.shadowMaps = storage.shadowMaps;
  frame.depth = toImageRef(inputs.depth);
  frame.color = toImageRef(inputs.color);
  frame.scatteringOutput = toImageRef(inputs.aovScattering);
  frame.transmittanceOutput = toImageRef(inputs.aovTransmittance);
  frame.lightColor = toImageRef(inputs.lightColor);
  frame.additionalLights = storage.additionalLights;
  frame.profile = profile;
  return frame;
}

bool TyndallEffect::record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string& error) {
  FrameStorage storage;
  FrameDesc frame = makeFrameDesc(inputs, profile_, storage);
  frame.autoBudgetMilliseconds = autoBudget_;
  frame.technique = technique_;
  if (epipolar_) frame.epipolar = &*epipolar_;
  frame.resolution = resolution_;
  if (!aovOutputs_) {
    frame.scatteringOutput = {};
    frame.transmittanceOutput = {};
  } else if (debugView_ != DebugView::None) {
    frame.debugView = debugView_;
    frame.debugOutput = toImageRef(inputs.aovDebug);
  }
  if (prefiltered_) frame.prefiltered = &*prefiltered_;
  if (Outcome outcome = context_->record(cmd, frame); !outcome) {
    error = std::string("tyndall: ") + to_string(outcome.status) + ": " + outcome.message;
    return false;
  }
  return true;
}

bool TyndallEffect::resize(VkExtent2D extent, std::string& error) {
  if (Outcome outcome = context_->resize(extent); !outcome) {
    error = "tyndall: " + outcome.message;
    return false;
  }
  return true;
}

}  // namespace tyndall::samples
