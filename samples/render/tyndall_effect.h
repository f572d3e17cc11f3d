// Tyndall inserted into the stub host's post-process stack, as an engine would insert it:
// the host's per-frame data becomes a tyndall::FrameDesc.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tyndall/tuning.h"
#include "tyndall_host/renderer.h"

namespace tyndall::samples {

class TyndallEffect final : public host::PostProcessEffect {
 public:
  /// Creates the Tyndall context on the host's device.
  static std::unique_ptr<TyndallEffect> create(host::Device& device, const host::RenderSettings& settings,
                                               Profile profile, std::string& error,
                                               PipelineCreation pipelineCreation = PipelineCreation::AtCreate,
                                               std::uint32_t marchThreadsPerSample = 0,
                                               bool fullFloatTargets = false);

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string& error) override;
  bool resize(VkExtent2D extent, std::string& error) override;

  void setProfile(Profile profile) { profile_ = profile; }
  /// Profile::Auto's GPU-time budget in milliseconds.
  void setAutoBudget(float milliseconds) { autoBudget_ = milliseconds; }
  /// Technique::None lets the profile decide.
  void setTechnique(Technique technique) { technique_ = technique; }
  /// Parameters of the epipolar technique instead of the profile's (empty: the profile's).
  void setEpipolarSettings(const std::optional<EpipolarSettings>& settings) { epipolar_ = settings; }
  /// The resolution of L_in instead of the profile's or the settings' (empty: theirs).
  void setResolution(std::optional<ScatteringResolution> resolution) { resolution_ = resolution; }
  /// A debug view into the host's debug AOV (needs RenderSettings::aovImages).
  void setDebugView(DebugView view) { debugView_ = view; }
  /// Parameters of the prefiltered technique instead of the profile's (empty: the profile's).
  void setPrefilteredSettings(const std::optional<PrefilteredSettings>& settings) { prefiltered_ = settings; }
  /// Whether the frames recorded next copy L_in, T and the debug view into the host's AOV images
  /// (default true). Timed frames leave them off: an engine does not read AOVs every frame, and the
  /// copy (aov_output) is a blit, slow where the graphics units are few.
  void setAovOutputs(bool on) { aovOutputs_ = on; }
  Context& context() { return *context_; }
  /// Messages the context reported through its callback.
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  static void onMessage(Severity severity, const char* message, void* user);

  std::unique_ptr<Context> context_;
  Profile profile_ = Profile::Balanced;
  float autoBudget_ = 4.0f;
  Technique technique_ = Technique::None;
  std::optional<EpipolarSettings> epipolar_;
  std::optional<ScatteringResolution> resolution_;
  DebugView debugView_ = DebugView::None;
  std::optional<PrefilteredSettings> prefiltered_;
  bool aovOutputs_ = true;
  std::vector<std::string> messages_;
};

/// The ContextDesc for the host's device and render settings (what an engine fills in once).
ContextDesc contextDescFor(host::Device& device, const host::RenderSettings& settings);

/// Converts the host's scene description into Tyndall's (radians, float, spans).
LightDesc toLightDesc(const host::Light& light);
std::vector<MediumComponent> toMedium(const std::vector<host::MediumComponent>& medium);

/// What a FrameDesc's spans point into; must outlive the FrameDesc.
struct FrameStorage {
  std::vector<MediumComponent> medium;
  std::vector<ShadowMapDesc> shadowMaps;
  std::vector<std::vector<ShadowMapDesc>> additionalShadowMaps;  ///< per additional light
  std::vector<LightInput> additionalLights;
};
/// The FrameDesc an engine would build from its per-frame data.
FrameDesc makeFrameDesc(const host::PostProcessInputs& inputs, Profile profile, FrameStorage& storage);

}  // namespace tyndall::samples
