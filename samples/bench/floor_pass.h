// The full-screen floors of tyndall-bench: the cheapest post-process that reads depth and colour and
// writes colour, as a fragment pass blending into the back buffer (shaders/floor.frag) or as a compute
// pass writing it in place (shaders/floor.comp), inserted into the stub host's stack like Tyndall and
// timed with its own timestamps. A technique's time over the floor of its composite's kind says how
// far it is from what any post-process of that kind costs at that size on that device.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "tyndall_host/renderer.h"

namespace tyndall::samples::bench {

/// How the floor writes the back buffer, as Tyndall's composite does (Stats::composite).
enum class FloorKind { Fragment, Compute };

/// Why the compute floor cannot run on `device` with back buffers of `settings`; empty when it can.
/// It needs a back buffer with STORAGE usage (RenderSettings::storageBackBuffer and a format with
/// storage-image support) and shaderStorageImageWriteWithoutFormat.
std::string computeFloorUnavailable(const host::Device& device, const host::RenderSettings& settings);

class FloorPass final : public host::PostProcessEffect {
 public:
  /// The compute kind fails in `record` for a back buffer without STORAGE usage
  /// (computeFloorUnavailable says beforehand).
  static std::unique_ptr<FloorPass> create(host::Device& device, FloorKind kind, std::string& error);
  ~FloorPass() override;
  FloorPass(const FloorPass&) = delete;
  FloorPass& operator=(const FloorPass&) = delete;

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string& error) override;
  bool resize(VkExtent2D extent, std::string& error) override;

  /// GPU milliseconds of the pass in the frame recorded last; call once that frame is complete
  /// (after Renderer::waitIdle). Empty before the first frame.
  std::optional<double> lastMilliseconds();

  struct Impl;

 private:
  explicit FloorPass(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tyndall::samples::bench
