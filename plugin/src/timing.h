// Per-pass GPU timings from timestamp queries. Each frame slot has its own range of queries; a
// slot's results are read when the slot comes round again (the host has waited for that frame
// by then), so reading never stalls.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "gpu.h"

namespace tyndall {

class GpuTimer {
 public:
  /// Up to this many timed passes per frame; later passes run untimed (and unlisted in the timings).
  static constexpr std::uint32_t kMaxPasses = 160;  // kMaxLights lights of a dozen passes each, and the shared ones

  Outcome create(const Gpu& gpu, std::uint32_t slots, std::uint32_t queueFamilyIndex);
  void destroy(const Gpu& gpu);
  [[nodiscard]] bool supported() const { return pool_ != VK_NULL_HANDLE; }

  /// Reads the slot's previous frame (if any), then resets its queries for a new frame.
  void beginFrame(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, std::uint64_t frameIndex);
  void beginPass(const Gpu& gpu, VkCommandBuffer cmd, const char* name);
  /// Names the passes begun from now on `prefix` + name (a frame of several lights: "light2/").
  void setPassPrefix(std::string prefix) { prefix_ = std::move(prefix); }
  void endPass(const Gpu& gpu, VkCommandBuffer cmd);

  /// Reads every slot whose results are available, without waiting.
  void harvestAll(const Gpu& gpu);
  /// Reads the slot's previous frame if it is available (beginFrame would); fails once the results
  /// came back VK_ERROR_DEVICE_LOST, and from then on.
  Outcome readSlot(const Gpu& gpu, std::uint32_t slot);
  std::vector<FrameTimings> takeCompleted();
  [[nodiscard]] const FrameTimings* latest() const { return haveLatest_ ? &latest_ : nullptr; }

 private:
  struct Slot {
    bool pending = false;
    std::uint64_t frameIndex = 0;
    std::vector<std::string> passes;
  };
  bool harvest(const Gpu& gpu, std::uint32_t slot);

  VkQueryPool pool_ = VK_NULL_HANDLE;
  double nanosecondsPerTick_ = 1.0;
  std::uint64_t validMask_ = ~0ull;
  std::vector<Slot> slots_;
  std::uint32_t current_ = 0;
  std::string prefix_;
  bool passOpen_ = false;  // beginPass wrote the pass's first stamp; endPass writes its second
  std::vector<FrameTimings> completed_;
  FrameTimings latest_;
  bool haveLatest_ = false;
  Outcome deviceLost_;
};

}  // namespace tyndall
