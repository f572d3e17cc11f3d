#include "fault_injection.h"

#include <cstring>
#include <tuple>
#include <type_traits>

#include "vk_dispatch.h"

namespace tyndall::test {

namespace {

PFN_vkGetDeviceProcAddr realGetDeviceProcAddr = nullptr;

template <class Handle>
std::uint64_t handleValue(Handle handle) {
  if constexpr (std::is_pointer_v<Handle>) {
    return reinterpret_cast<std::uintptr_t>(handle);
  } else {
    return static_cast<std::uint64_t>(handle);
  }
}

// The device's own entry point behind each wrapper, one per function type.
template <class Tag>
struct Real {
  static inline typename Tag::Pfn fn = nullptr;
};

template <class Tag, class Pfn = typename Tag::Pfn>
struct Wrap;

// vkCmd*: counted and forwarded.
template <class Tag, class... A>
struct Wrap<Tag, void(VKAPI_PTR*)(A...)> {
  static VKAPI_ATTR void VKAPI_CALL call(A... a) {
    FaultInjector::get().commandRecorded();
    Real<Tag>::fn(a...);
  }
};

// vkCreate*, vkAllocateMemory, binds, maps: fallible; what they create (their last parameter,
// when Tag::object names its type) is counted until destroyed.
template <class Tag, class... A>
struct Wrap<Tag, VkResult(VKAPI_PTR*)(A...)> {
  static VKAPI_ATTR VkResult VKAPI_CALL call(A... a) {
    FaultInjector& injector = FaultInjector::get();
    VkResult result = VK_SUCCESS;
    if (injector.shouldFail(Tag::kind, Tag::name, result)) return result;
    result = Real<Tag>::fn(a...);
    if constexpr (Tag::object != nullptr) {
      if (result == VK_SUCCESS) injector.created(Tag::object, handleValue(*std::get<sizeof...(A) - 1>(std::tie(a...))));
    }
    return result;
  }
};

// vkDestroy*, vkFreeMemory: (device, handle, allocator).
template <class Tag, class Pfn = typename Tag::Pfn>
struct Destroy;
template <class Tag, class Handle>
struct Destroy<Tag, void(VKAPI_PTR*)(VkDevice, Handle, const VkAllocationCallbacks*)> {
  static VKAPI_ATTR void VKAPI_CALL call(VkDevice device, Handle handle, const VkAllocationCallbacks* allocator) {
    if (handle != VK_NULL_HANDLE) FaultInjector::get().destroyed(Tag::object, handleValue(handle));
    Real<Tag>::fn(device, handle, allocator);
  }
};

// vkCreate{Compute,Graphics}Pipelines: a failure leaves every element null, as the spec says.
template <class Tag, class Info>
VkResult createPipelines(VkDevice device, VkPipelineCache cache, std::uint32_t count, const Info* infos,
                         const VkAllocationCallbacks* allocator, VkPipeline* pipelines) {
  FaultInjector& injector = FaultInjector::get();
  VkResult result = VK_SUCCESS;
  if (injector.shouldFail(FaultKind::Pipeline, Tag::name, result)) {
    for (std::uint32_t i = 0; i < count; ++i) pipelines[i] = VK_NULL_HANDLE;
    return result;
  }
  result = Real<Tag>::fn(device, cache, count, infos, allocator, pipelines);
  for (std::uint32_t i = 0; i < count; ++i) {
    if (pipelines[i] != VK_NULL_HANDLE) injector.created("pipeline", handleValue(pipelines[i]));
  }
  return result;
}
struct ComputePipelinesTag {
  using Pfn = PFN_vkCreateComputePipelines;
  static constexpr const char* name = "vkCreateComputePipelines";
};
struct GraphicsPipelinesTag {
  using Pfn = PFN_vkCreateGraphicsPipelines;
  static constexpr const char* name = "vkCreateGraphicsPipelines";
};
VKAPI_ATTR VkResult VKAPI_CALL createComputePipelines(VkDevice d, VkPipelineCache c, std::uint32_t n,
                                                      const VkComputePipelineCreateInfo* i,
                                                      const VkAllocationCallbacks* a, VkPipeline* p) {
  return createPipelines<ComputePipelinesTag>(d, c, n, i, a, p);
}
VKAPI_ATTR VkResult VKAPI_CALL createGraphicsPipelines(VkDevice d, VkPipelineCache c, std::uint32_t n,
                                                       const VkGraphicsPipelineCreateInfo* i,
                                                       const VkAllocationCallbacks* a, VkPipeline* p) {
  return createPipelines<GraphicsPipelinesTag>(d, c, n, i, a, p);
}

// A lost device reports itself where a driver can: the query results the timer reads.
struct QueryResultsTag {
  using Pfn = PFN_vkGetQueryPoolResults;
};
VKAPI_ATTR VkResult VKAPI_CALL getQueryPoolResults(VkDevice d, VkQueryPool pool, std::uint32_t first,
                                                   std::uint32_t count, std::size_t size, void* data,
                                                   VkDeviceSize stride, VkQueryResultFlags flags) {
  if (FaultInjector::get().deviceLost()) return VK_ERROR_DEVICE_LOST;
  return Real<QueryResultsTag>::fn(d, pool, first, count, size, data, stride, flags);
}

#define TYNDALL_FALLIBLE(fn, objectType)                      \
  struct fn##Tag {                                            \
    using Pfn = PFN_##fn;                                     \
    static constexpr const char* name = #fn;                  \
    static constexpr const char* object = objectType;         \
    static constexpr FaultKind kind = FaultKind::Allocation;  \
  };
#define TYNDALL_DESTROY(fn, objectType)               \
  struct fn##Tag {                                    \
    using Pfn = PFN_##fn;                             \
    static constexpr const char* object = objectType; \
  };
#define TYNDALL_COMMAND(fn) \
  struct fn##Tag {          \
    using Pfn = PFN_##fn;   \
  };

#define TYNDALL_FALLIBLE_CALLS(X)                        \
  X(vkAllocateMemory, "memory")                          \
  X(vkCreateImage, "image")                              \
  X(vkCreateImageView, "image view")                     \
  X(vkCreateBuffer, "buffer")                            \
  X(vkCreateSampler, "sampler")                          \
  X(vkCreateDescriptorSetLayout, "descriptor set layout") \
  X(vkCreatePipelineLayout, "pipeline layout")           \
  X(vkCreateShaderModule, "shader module")               \
  X(vkCreateDescriptorPool, "descriptor pool")           \
  X(vkCreateQueryPool, "query pool")                     \
  X(vkAllocateDescriptorSets, nullptr)                   \
  X(vkBindImageMemory, nullptr)                          \
  X(vkBindBufferMemory, nullptr)                         \
  X(vkMapMemory, nullptr)
#define TYNDALL_DESTROY_CALLS(X)                          \
  X(vkFreeMemory, "memory")                               \
  X(vkDestroyImage, "image")                              \
  X(vkDestroyImageView, "image view")                     \
  X(vkDestroyBuffer, "buffer")                            \
  X(vkDestroySampler, "sampler")                          \
  X(vkDestroyDescriptorSetLayout, "descriptor set layout") \
  X(vkDestroyPipelineLayout, "pipeline layout")           \
  X(vkDestroyShaderModule, "shader module")               \
  X(vkDestroyDescriptorPool, "descriptor pool")           \
  X(vkDestroyQueryPool, "query pool")                     \
  X(vkDestroyPipeline, "pipeline")
// Every command the plugin's dispatch table loads, and dynamic rendering's pair (loaded beside it).
#define TYNDALL_COMMAND_CALLS(X) \
  TYNDALL_COMMAND_FUNCTIONS(X)   \
  X(vkCmdBeginRendering)         \
  X(vkCmdEndRendering)

TYNDALL_FALLIBLE_CALLS(TYNDALL_FALLIBLE)
TYNDALL_DESTROY_CALLS(TYNDALL_DESTROY)
TYNDALL_COMMAND_CALLS(TYNDALL_COMMAND)

template <class Tag, class Wrapper>
PFN_vkVoidFunction wrap(PFN_vkVoidFunction real) {
  Real<Tag>::fn = reinterpret_cast<typename Tag::Pfn>(real);
  return reinterpret_cast<PFN_vkVoidFunction>(&Wrapper::call);
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL getDeviceProcAddr(VkDevice device, const char* name) {
  const PFN_vkVoidFunction real = realGetDeviceProcAddr(device, name);
  if (real == nullptr) return nullptr;
#define TYNDALL_MATCH_FALLIBLE(fn, objectType) \
  if (std::strcmp(name, #fn) == 0) return wrap<fn##Tag, Wrap<fn##Tag>>(real);
#define TYNDALL_MATCH_DESTROY(fn, objectType) \
  if (std::strcmp(name, #fn) == 0) return wrap<fn##Tag, Destroy<fn##Tag>>(real);
#define TYNDALL_MATCH_COMMAND(fn) \
  if (std::strcmp(name, #fn) == 0 || std::strcmp(name, #fn "KHR") == 0) return wrap<fn##Tag, Wrap<fn##Tag>>(real);
  TYNDALL_FALLIBLE_CALLS(TYNDALL_MATCH_FALLIBLE)
  TYNDALL_DESTROY_CALLS(TYNDALL_MATCH_DESTROY)
  TYNDALL_COMMAND_CALLS(TYNDALL_MATCH_COMMAND)
#undef TYNDALL_MATCH_FALLIBLE
#undef TYNDALL_MATCH_DESTROY
#undef TYNDALL_MATCH_COMMAND
  if (std::strcmp(name, "vkCreateComputePipelines") == 0) {
    Real<ComputePipelinesTag>::fn = reinterpret_cast<PFN_vkCreateComputePipelines>(real);
    return reinterpret_cast<PFN_vkVoidFunction>(&createComputePipelines);
  }
  if (std::strcmp(name, "vkCreateGraphicsPipelines") == 0) {
    Real<GraphicsPipelinesTag>::fn = reinterpret_cast<PFN_vkCreateGraphicsPipelines>(real);
    return reinterpret_cast<PFN_vkVoidFunction>(&createGraphicsPipelines);
  }
  if (std::strcmp(name, "vkGetQueryPoolResults") == 0) {
    Real<QueryResultsTag>::fn = reinterpret_cast<PFN_vkGetQueryPoolResults>(real);
    return reinterpret_cast<PFN_vkVoidFunction>(&getQueryPoolResults);
  }
  return real;
}

}  // namespace

FaultInjector& FaultInjector::get() {
  static FaultInjector injector;
  return injector;
}

PFN_vkGetDeviceProcAddr FaultInjector::install(PFN_vkGetDeviceProcAddr real) {
  realGetDeviceProcAddr = real;
  return &getDeviceProcAddr;
}

void FaultInjector::failAt(std::uint64_t n, FaultKind kind) {
  reset();
  failAt_ = n;
  failKind_ = kind;
}

void FaultInjector::loseDevice() { deviceLost_ = true; }

void FaultInjector::reset() {
  for (auto& [kind, count] : calls_) count = 0;
  failAt_ = 0;
  deviceLost_ = false;
  failedCall_.clear();
}

bool FaultInjector::shouldFail(FaultKind kind, const char* call, VkResult& result) {
  const std::uint64_t n = ++calls_[kind];
  if (failAt_ == 0 || kind != failKind_ || n != failAt_) return false;
  failedCall_ = call;
  if (std::strcmp(call, "vkAllocateMemory") == 0) {
    result = VK_ERROR_OUT_OF_DEVICE_MEMORY;
  } else if (std::strcmp(call, "vkMapMemory") == 0) {
    result = VK_ERROR_MEMORY_MAP_FAILED;
  } else {
    result = VK_ERROR_OUT_OF_HOST_MEMORY;
  }
  return true;
}

void FaultInjector::created(const char* type, std::uint64_t handle) { ++live_[type][handle]; }

void FaultInjector::destroyed(const char* type, std::uint64_t handle) {
  auto& handles = live_[type];
  if (--handles[handle] == 0) handles.erase(handle);
}

std::uint64_t FaultInjector::takeCommandCount() {
  const std::uint64_t count = commands_;
  commands_ = 0;
  return count;
}

std::map<std::string, std::int64_t> FaultInjector::liveObjects() const {
  std::map<std::string, std::int64_t> counts;
  for (const auto& [type, handles] : live_) {
    std::int64_t count = 0;
    for (const auto& [handle, references] : handles) count += references;
    if (count != 0) counts[type] = count;
  }
  return counts;
}

std::string FaultInjector::describeLiveObjects() const {
  std::string text;
  for (const auto& [type, count] : liveObjects()) {
    text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + type;
  }
  return text.empty() ? "none" : text;
}

}  // namespace tyndall::test
