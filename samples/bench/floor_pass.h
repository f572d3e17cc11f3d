// The full-screen floor of tyndall-bench: the cheapest post-process that reads depth and colour and
// writes colour (shaders/floor.frag), inserted into the stub host's stack like Tyndall and timed
// with its own timestamps. A technique's time over this pass's time says how far it is from what
// any post-process costs at that size on that device.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "tyndall_host/renderer.h"

namespace tyndall::samples::bench {

class FloorPass final : public host::PostProcessEffect {
 public:
  static std::unique_ptr<FloorPass> create(host::Device& device, std::string& error);
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
