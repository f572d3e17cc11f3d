#include "timing.h"

#include <algorithm>

namespace tyndall {

Outcome GpuTimer::create(const Gpu& gpu, std::uint32_t slots, std::uint32_t queueFamilyIndex) {
  std::uint32_t familyCount = 0;
  gpu.vk.vkGetPhysicalDeviceQueueFamilyProperties(gpu.physicalDevice, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  gpu.vk.vkGetPhysicalDeviceQueueFamilyProperties(gpu.physicalDevice, &familyCount, families.data());
  const std::uint32_t validBits = queueFamilyIndex < familyCount ? families[queueFamilyIndex].timestampValidBits : 0;
  if (validBits == 0 || gpu.properties.limits.timestampPeriod <= 0.0f) return {};  // stats say unsupported

  validMask_ = validBits >= 64 ? ~0ull : ((1ull << validBits) - 1ull);
  nanosecondsPerTick_ = gpu.properties.limits.timestampPeriod;
  slots_.assign(slots, Slot{});
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = slots * kMaxPasses * 2;
  VkResult result = gpu.vk.vkCreateQueryPool(gpu.device, &info, gpu.allocator, &pool_);
  return result == VK_SUCCESS ? Outcome{} : vkFailed("vkCreateQueryPool", result);
}

void GpuTimer::destroy(const Gpu& gpu) {
  if (pool_ != VK_NULL_HANDLE) gpu.vk.vkDestroyQueryPool(gpu.device, pool_, gpu.allocator);
  pool_ = VK_NULL_HANDLE;
}

void GpuTimer::beginFrame(const Gpu& gpu, VkCommandBuffer cmd, std::uint32_t slot, std::uint64_t frameIndex) {
  if (!supported()) return;
  harvest(gpu, slot);
  current_ = slot;
  Slot& s = slots_[slot];
  // A frame recorded but never submitted never completes; it is dropped here.
  s = Slot{true, frameIndex, {}};
  gpu.vk.vkCmdResetQueryPool(cmd, pool_, slot * kMaxPasses * 2, kMaxPasses * 2);
}

void GpuTimer::beginPass(const Gpu& gpu, VkCommandBuffer cmd, const char* name) {
  if (!supported()) return;
  Slot& s = slots_[current_];
  passOpen_ = s.passes.size() < kMaxPasses;
  if (!passOpen_) return;
  const std::uint32_t query = current_ * kMaxPasses * 2 + static_cast<std::uint32_t>(s.passes.size()) * 2;
  s.passes.push_back(prefix_ + name);
  // BOTTOM_OF_PIPE: the stamp is taken once all earlier work has finished.
  gpu.vk.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, query);
}

void GpuTimer::endPass(const Gpu& gpu, VkCommandBuffer cmd) {
  if (!supported()) return;
  if (!passOpen_) return;
  passOpen_ = false;
  Slot& s = slots_[current_];
  const std::uint32_t query = current_ * kMaxPasses * 2 + static_cast<std::uint32_t>(s.passes.size()) * 2 - 1;
  gpu.vk.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, query);
}

bool GpuTimer::harvest(const Gpu& gpu, std::uint32_t slot) {
  Slot& s = slots_[slot];
  if (!s.pending || s.passes.empty()) return false;
  const std::uint32_t count = static_cast<std::uint32_t>(s.passes.size()) * 2;
  // Each query: value, availability.
  std::vector<std::uint64_t> data(count * 2, 0);
  VkResult result = gpu.vk.vkGetQueryPoolResults(
      gpu.device, pool_, slot * kMaxPasses * 2, count, data.size() * sizeof(std::uint64_t), data.data(),
      2 * sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
  if (result == VK_ERROR_DEVICE_LOST && deviceLost_.ok()) {
    deviceLost_ = vkFailed("vkGetQueryPoolResults", result);
    deviceLost_.message += ": the device was lost; destroy the context with it";
  }
  if (result != VK_SUCCESS && result != VK_NOT_READY) return false;
  for (std::uint32_t q = 0; q < count; ++q) {
    if (data[q * 2 + 1] == 0) return false;  // not finished yet
  }
  FrameTimings timings;
  timings.frameIndex = s.frameIndex;
  auto ticks = [&](std::uint32_t q) { return data[q * 2] & validMask_; };
  auto ms = [&](std::uint64_t begin, std::uint64_t end) {
    return end >= begin ? static_cast<double>(end - begin) * nanosecondsPerTick_ * 1e-6 : 0.0;
  };
  for (std::uint32_t p = 0; p < s.passes.size(); ++p) {
    timings.passes.push_back({s.passes[p], ms(ticks(p * 2), ticks(p * 2 + 1))});
  }
  timings.totalMilliseconds = ms(ticks(0), ticks(count - 1));
  s.pending = false;
  latest_ = timings;
  haveLatest_ = true;
  completed_.push_back(std::move(timings));
  return true;
}

void GpuTimer::harvestAll(const Gpu& gpu) {
  if (!supported()) return;
  // Oldest frame first, so `latest` ends on the newest.
  std::vector<std::uint32_t> order;
  for (std::uint32_t i = 0; i < slots_.size(); ++i) {
    if (slots_[i].pending) order.push_back(i);
  }
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return slots_[a].frameIndex < slots_[b].frameIndex; });
  for (std::uint32_t slot : order) harvest(gpu, slot);
}

Outcome GpuTimer::readSlot(const Gpu& gpu, std::uint32_t slot) {
  if (supported()) harvest(gpu, slot);
  return deviceLost_;
}

std::vector<FrameTimings> GpuTimer::takeCompleted() {
  std::vector<FrameTimings> out;
  out.swap(completed_);
  return out;
}

}  // namespace tyndall
