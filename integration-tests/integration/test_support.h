// Shared pieces of the integration tests: one validated device, scene loading, error metrics.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "analytic_reference.h"
#include "error_metrics.h"
#include "render_job.h"
#include "tyndall_host/renderer.h"
#include "tyndall_host/scene.h"

namespace tyndall::test {

/// The device every integration test uses: lavapipe (TYNDALL_DEVICE) with the Khronos validation
/// layer and synchronization validation. Created once per process.
host::Device& validatedDevice();

/// Fails the current test if the device reported any validation message since the last call.
void expectNoValidationMessages();

host::Scene loadTestScene(const std::string& name);  ///< samples/scenes/<name>.json

/// The project's error metrics (samples/render/error_metrics.h); these check the sizes first.
using samples::ErrorStats;
using samples::describe;
ErrorStats compareRgb(const host::ImageRgba32f& measured, const std::vector<double>& referenceRgb,
                      const std::vector<unsigned char>* mask = nullptr);
ErrorStats compareRgb(const host::ImageRgba32f& measured, const host::ImageRgba32f& reference,
                      const std::vector<unsigned char>* mask = nullptr);

/// The prefiltered issue's accuracy bar of a storage variant (relative RMSE of L_in against the
/// Reference): 5% for 6 moments, 8% for 4; Fourier has none (infinity: it is reported).
double prefilteredBar(PrefilteredBasis basis);

/// Turns the scene's camera so that the light (where its light comes from) appears at `ndc` (Vulkan
/// NDC, y down; beyond ±1 is off screen) of a `width`×`height` image, or, with `behind`, so that the
/// light is behind the camera and its mirrored epipole appears there. (The construction of
/// test_epipolar.cpp's placements, shared.)
host::Scene withEpipoleAt(host::Scene scene, glm::dvec2 ndc, bool behind, std::uint32_t width, std::uint32_t height);

/// Scene objects with the host's default albedo, for scenes built in a test.
host::Object planeObject(const glm::dvec3& point, const glm::dvec3& normal);
host::Object boxObject(const glm::dvec3& center, const glm::dvec3& halfExtents);

/// Renders `frames` frames with the options' profile and reads the AOVs back.
samples::RenderResult renderWithAovs(const host::Scene& scene, samples::RenderOptions options);

/// renderWithAovs through one Tyndall context per process and context description (output size,
/// frames in flight, back-buffer format, full-float targets), created by the first render that needs it, as an engine
/// keeps one context while its scenes and settings change. The context compiles each pipeline on
/// first use (seconds per pipeline on lavapipe with validation, against well under a second for a
/// 320×180 frame), so a test that renders many times with one technique compiles its pipelines
/// once. A test about what a fresh context renders uses renderWithAovs. `stats.frameIndex` counts every frame of the shared context.
samples::RenderResult renderWithSharedContext(const host::Scene& scene, samples::RenderOptions options);

/// Copies one of the frame's shadow maps to host memory from inside the post-process stack, where
/// Tyndall reads it (the host-stub tests check its contents; the extremes suite its clamps).
class ShadowMapCopy final : public host::PostProcessEffect {
 public:
  explicit ShadowMapCopy(host::Device& device, std::size_t mapIndex = 0) : device_(device), mapIndex_(mapIndex) {}
  ~ShadowMapCopy() override {
    if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device_.device(), buffer_, nullptr);
    if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_.device(), memory_, nullptr);
  }
  ShadowMapCopy(const ShadowMapCopy&) = delete;
  ShadowMapCopy& operator=(const ShadowMapCopy&) = delete;

  bool record(VkCommandBuffer cmd, const host::PostProcessInputs& inputs, std::string& error) override {
    if (mapIndex_ >= inputs.shadowMaps.size()) {
      error = "no shadow map " + std::to_string(mapIndex_);
      return false;
    }
    const host::HostShadowMap& map = inputs.shadowMaps[mapIndex_];
    size_ = map.depth.extent.width;
    worldToShadowClip_ = glm::dmat4(map.worldToShadowClip);
    if (buffer_ == VK_NULL_HANDLE && !createBuffer(VkDeviceSize{size_} * size_ * sizeof(float), error)) return false;

    VkImageMemoryBarrier2 toCopy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    toCopy.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    toCopy.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    toCopy.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toCopy.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
    toCopy.oldLayout = map.depth.layout;
    toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    toCopy.srcQueueFamilyIndex = toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toCopy.image = map.depth.image;
    toCopy.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &toCopy;
    vkCmdPipelineBarrier2(cmd, &dependency);

    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    region.imageExtent = {size_, size_, 1};
    vkCmdCopyImageToBuffer(cmd, map.depth.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_, 1, &region);

    VkImageMemoryBarrier2 back = toCopy;
    back.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    back.srcAccessMask = VK_ACCESS_2_NONE;
    back.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    back.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT;
    back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    back.newLayout = map.depth.layout;
    VkBufferMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    toHost.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.buffer = buffer_;
    toHost.size = VK_WHOLE_SIZE;
    dependency.pImageMemoryBarriers = &back;
    dependency.bufferMemoryBarrierCount = 1;
    dependency.pBufferMemoryBarriers = &toHost;
    vkCmdPipelineBarrier2(cmd, &dependency);
    return true;
  }
  bool resize(VkExtent2D, std::string&) override { return true; }

  std::uint32_t size() const { return size_; }
  const glm::dmat4& worldToShadowClip() const { return worldToShadowClip_; }
  /// The stored depth of texel (column, row); valid after the renderer waited for the frame.
  float texel(std::uint32_t column, std::uint32_t row) const {
    return static_cast<const float*>(mapped_)[std::size_t{row} * size_ + column];
  }
  bool copied() const { return mapped_ != nullptr; }
  /// Clip-space position of `p` and the stored depth of the texel it falls in (u → column, v → row).
  void lookup(const glm::dvec3& p, glm::dvec3& ndc, float& stored) const {
    const glm::dvec4 clip = worldToShadowClip_ * glm::dvec4(p, 1.0);
    ndc = glm::dvec3(clip) / clip.w;
    stored = texel(static_cast<std::uint32_t>((ndc.x + 1.0) * 0.5 * size_),
                   static_cast<std::uint32_t>((ndc.y + 1.0) * 0.5 * size_));
  }

 private:
  bool createBuffer(VkDeviceSize bytes, std::string& error) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (vkCreateBuffer(device_.device(), &info, nullptr, &buffer_) != VK_SUCCESS) {
      error = "vkCreateBuffer failed";
      return false;
    }
    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(device_.device(), buffer_, &requirements);
    VkPhysicalDeviceMemoryProperties properties{};
    vkGetPhysicalDeviceMemoryProperties(device_.physicalDevice(), &properties);
    const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (std::uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
      if ((requirements.memoryTypeBits & (1u << i)) == 0 ||
          (properties.memoryTypes[i].propertyFlags & wanted) != wanted) {
        continue;
      }
      VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
      allocation.allocationSize = requirements.size;
      allocation.memoryTypeIndex = i;
      if (vkAllocateMemory(device_.device(), &allocation, nullptr, &memory_) != VK_SUCCESS ||
          vkBindBufferMemory(device_.device(), buffer_, memory_, 0) != VK_SUCCESS ||
          vkMapMemory(device_.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_) != VK_SUCCESS) {
        error = "cannot allocate, bind or map the readback buffer";
        return false;
      }
      return true;
    }
    error = "no host-visible coherent memory type";
    return false;
  }

  host::Device& device_;
  std::size_t mapIndex_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
  std::uint32_t size_ = 0;
  glm::dmat4 worldToShadowClip_{1.0};
};

}  // namespace tyndall::test
