// Internal Vulkan helpers of the stub host: error strings, RAII owners for the handful of object
// kinds the host creates, memory allocation and synchronization2 barriers.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

namespace tyndall::host::vk {

/// "VK_ERROR_OUT_OF_DEVICE_MEMORY", … ("VkResult(-42)" for values this helper does not know).
std::string resultName(VkResult result);

/// Returns true on VK_SUCCESS; otherwise sets `error` to "<what> failed: <result>".
bool check(VkResult result, const char* what, std::string& error);

/// Owns one handle destroyed with `vkDestroyX(device, handle, nullptr)`.
template <typename Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
class Unique {
 public:
  Unique() = default;
  Unique(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
  ~Unique() { reset(); }
  Unique(const Unique&) = delete;
  Unique& operator=(const Unique&) = delete;
  Unique(Unique&& other) noexcept
      : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  Unique& operator=(Unique&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  Handle get() const { return handle_; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

using UniquePipeline = Unique<VkPipeline, vkDestroyPipeline>;
using UniquePipelineLayout = Unique<VkPipelineLayout, vkDestroyPipelineLayout>;
using UniqueDescriptorSetLayout = Unique<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = Unique<VkDescriptorPool, vkDestroyDescriptorPool>;
using UniqueSampler = Unique<VkSampler, vkDestroySampler>;
using UniqueShaderModule = Unique<VkShaderModule, vkDestroyShaderModule>;
using UniqueCommandPool = Unique<VkCommandPool, vkDestroyCommandPool>;
using UniqueFence = Unique<VkFence, vkDestroyFence>;

/// What the helpers need to know about the device.
struct GpuContext {
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::mutex* queueMutex = nullptr;  ///< held around every submission to `queue` (Device::queueMutex)
  std::uint32_t queueFamily = 0;
  VkPhysicalDeviceMemoryProperties memory{};
};

/// Allocates memory for `requirements` with at least `properties`.
bool allocateMemory(const GpuContext& gpu, const VkMemoryRequirements& requirements,
                    VkMemoryPropertyFlags properties, VkDeviceMemory& memory, std::string& error);

/// A 2D image (one mip, one layer) with its own memory and a view of mip 0 / layer 0.
class Image {
 public:
  struct Desc {
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    VkImageUsageFlags usage = 0;
    const char* name = "image";  // for error messages
    std::uint32_t layers = 1;    // > 1: an array; view() shows all layers (2D_ARRAY), layerView(k) one
  };

  Image() = default;
  ~Image() { reset(); }
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
  Image(Image&& other) noexcept { *this = std::move(other); }
  Image& operator=(Image&& other) noexcept;

  bool create(const GpuContext& gpu, const Desc& desc, std::string& error);
  void reset();

  VkImage image() const { return image_; }
  VkImageView view() const { return view_; }
  VkImageView layerView(std::uint32_t layer) const { return layerViews_.empty() ? view_ : layerViews_[layer]; }
  std::uint32_t layers() const { return layers_; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  VkImageAspectFlags aspect() const { return aspect_; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> layerViews_;  // arrays only
  std::uint32_t layers_ = 1;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  VkImageAspectFlags aspect_ = 0;
};

/// A buffer with its own memory; host-visible buffers stay mapped for their whole life.
class Buffer {
 public:
  Buffer() = default;
  ~Buffer() { reset(); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& other) noexcept { *this = std::move(other); }
  Buffer& operator=(Buffer&& other) noexcept;

  bool create(const GpuContext& gpu, VkDeviceSize size, VkBufferUsageFlags usage,
              VkMemoryPropertyFlags properties, std::string& error);
  void reset();

  VkBuffer buffer() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

bool isDepthFormat(VkFormat format);

/// Collects image barriers and records them with one vkCmdPipelineBarrier2.
class Barriers {
 public:
  struct Scope {
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
  };
  /// Array layers [layer, layer + layerCount) of mip 0.
  Barriers& image(VkImage image, VkImageAspectFlags aspect, VkImageLayout oldLayout,
                  VkImageLayout newLayout, Scope src, Scope dst, std::uint32_t layer = 0,
                  std::uint32_t layerCount = 1);
  Barriers& buffer(VkBuffer buffer, Scope src, Scope dst);
  void record(VkCommandBuffer cmd);

 private:
  std::vector<VkImageMemoryBarrier2> images_;
  std::vector<VkBufferMemoryBarrier2> buffers_;
};

/// A sampler's description with `filter` for magnification and minification, nearest mips and
/// every address clamped to the edge (the passes' samplers start from it).
VkSamplerCreateInfo clampedSamplerInfo(VkFilter filter);

/// Records `body` into a fresh command buffer from `pool`, submits it and waits for it.
bool submitAndWait(const GpuContext& gpu, VkCommandPool pool,
                   const std::function<void(VkCommandBuffer)>& body, std::string& error);

bool createShaderModule(VkDevice device, std::span<const std::uint32_t> words,
                        UniqueShaderModule& out, std::string& error);

/// The few pipeline states the host's passes differ in; everything else is fixed (triangle lists,
/// dynamic viewport, scissor, cull mode and front face; dynamic rendering).
struct GraphicsPipelineDesc {
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::span<const std::uint32_t> vertexShader;
  std::span<const std::uint32_t> fragmentShader;  // empty: depth-only
  std::vector<VkVertexInputBindingDescription> bindings;
  std::vector<VkVertexInputAttributeDescription> attributes;
  std::vector<VkFormat> colorFormats;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
  bool depthClamp = false;
  bool additiveBlend = false;  // colour attachments: rgb += fragment rgb, alpha kept
  bool alphaBlend = false;     // colour attachments: rgb = src rgb · src a + dst rgb · (1 − src a), alpha kept
  bool depthWrite = true;      // with a depthFormat: write depth (else test only)
};

bool createGraphicsPipeline(VkDevice device, const GraphicsPipelineDesc& desc, UniquePipeline& out,
                            std::string& error);

/// Viewport and scissor covering `extent`. Positive height: framebuffer row = (y_ndc + 1) / 2 · H.
void setViewport(VkCommandBuffer cmd, VkExtent2D extent);

}  // namespace tyndall::host::vk
