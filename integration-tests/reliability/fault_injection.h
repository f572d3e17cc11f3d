// A layer of the test's own between Tyndall and the device, installed through the
// PFN_vkGetDeviceProcAddr a host hands the plugin: it counts the Vulkan objects the plugin holds
// and the commands it records, and fails the Nth fallible call on request (allocation or pipeline
// creation), or reports the device lost.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include <vulkan/vulkan.h>

namespace tyndall::test {

enum class FaultKind {
  Allocation,  ///< vkAllocateMemory, vkCreate{Image,Buffer,ImageView,Sampler,…}, descriptor sets, binds, maps
  Pipeline,    ///< vkCreateComputePipelines, vkCreateGraphicsPipelines
};

/// One per process: Vulkan function pointers carry no user data, so the wrappers reach it as a
/// global. Not thread-safe; the concurrency test does not use it.
class FaultInjector {
 public:
  static FaultInjector& get();

  /// The procedure to hand the plugin (ContextDesc::getDeviceProcAddr) in place of `real`.
  PFN_vkGetDeviceProcAddr install(PFN_vkGetDeviceProcAddr real);

  /// Counting from now, the `n`th call (1-based) of `kind` returns `result` and creates nothing.
  void failAt(std::uint64_t n, FaultKind kind);
  /// From now on every call that can report a lost device does (vkGetQueryPoolResults, the
  /// fallible calls): what a driver returns once the device is lost.
  void loseDevice();
  /// No failure armed, the device back; counts of calls restart from 0.
  void reset();

  /// Fallible calls of `kind` made since the last reset or failAt.
  std::uint64_t calls(FaultKind kind) const { return calls_.at(kind); }
  /// The call that was made to fail ("vkAllocateMemory"), or empty.
  const std::string& failedCall() const { return failedCall_; }
  /// Commands recorded (vkCmd*) since the last call of this.
  std::uint64_t takeCommandCount();
  /// Objects created through the plugin and not destroyed, by type ("image", "pipeline", …); only
  /// non-zero counts are listed.
  std::map<std::string, std::int64_t> liveObjects() const;
  std::string describeLiveObjects() const;

  // The wrappers' side.
  bool shouldFail(FaultKind kind, const char* call, VkResult& result);
  void created(const char* type, std::uint64_t handle);
  void destroyed(const char* type, std::uint64_t handle);
  void commandRecorded() { ++commands_; }
  bool deviceLost() const { return deviceLost_; }

 private:
  std::map<FaultKind, std::uint64_t> calls_{{FaultKind::Allocation, 0}, {FaultKind::Pipeline, 0}};
  std::uint64_t failAt_ = 0;
  FaultKind failKind_ = FaultKind::Allocation;
  bool deviceLost_ = false;
  std::string failedCall_;
  std::uint64_t commands_ = 0;
  std::map<std::string, std::map<std::uint64_t, int>> live_;
};

}  // namespace tyndall::test
