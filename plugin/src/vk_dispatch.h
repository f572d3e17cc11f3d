// The Vulkan entry points Tyndall uses, loaded through the host's vkGet*ProcAddr: the library
// links no Vulkan loader and works with whatever dispatch the host uses (layers included).
#pragma once

#include <vulkan/vulkan.h>

namespace tyndall {

#define TYNDALL_INSTANCE_FUNCTIONS(X)      \
  X(vkGetPhysicalDeviceProperties)         \
  X(vkGetPhysicalDeviceMemoryProperties)   \
  X(vkGetPhysicalDeviceFormatProperties)   \
  X(vkGetPhysicalDeviceQueueFamilyProperties)

#define TYNDALL_DEVICE_FUNCTIONS(X) \
  X(vkCreateImage)                  \
  X(vkDestroyImage)                 \
  X(vkGetImageMemoryRequirements)   \
  X(vkBindImageMemory)              \
  X(vkCreateImageView)              \
  X(vkDestroyImageView)             \
  X(vkCreateBuffer)                 \
  X(vkDestroyBuffer)                \
  X(vkGetBufferMemoryRequirements)  \
  X(vkBindBufferMemory)             \
  X(vkAllocateMemory)               \
  X(vkFreeMemory)                   \
  X(vkMapMemory)                    \
  X(vkUnmapMemory)                  \
  X(vkCreateSampler)                \
  X(vkDestroySampler)               \
  X(vkCreateDescriptorSetLayout)    \
  X(vkDestroyDescriptorSetLayout)   \
  X(vkCreatePipelineLayout)         \
  X(vkDestroyPipelineLayout)        \
  X(vkCreateShaderModule)           \
  X(vkDestroyShaderModule)          \
  X(vkCreateComputePipelines)       \
  X(vkCreateGraphicsPipelines)      \
  X(vkDestroyPipeline)              \
  X(vkCreateDescriptorPool)         \
  X(vkDestroyDescriptorPool)        \
  X(vkAllocateDescriptorSets)       \
  X(vkUpdateDescriptorSets)         \
  X(vkCreateQueryPool)              \
  X(vkDestroyQueryPool)             \
  X(vkGetQueryPoolResults)          \
  TYNDALL_COMMAND_FUNCTIONS(X)

// The commands Tyndall records (a fault-injection test counts them through this list).
#define TYNDALL_COMMAND_FUNCTIONS(X) \
  X(vkCmdResetQueryPool)             \
  X(vkCmdWriteTimestamp)             \
  X(vkCmdPipelineBarrier)            \
  X(vkCmdBindPipeline)               \
  X(vkCmdBindDescriptorSets)         \
  X(vkCmdPushConstants)              \
  X(vkCmdDispatch)                   \
  X(vkCmdDispatchIndirect)           \
  X(vkCmdFillBuffer)                 \
  X(vkCmdCopyBuffer)                 \
  X(vkCmdDraw)                       \
  X(vkCmdSetViewport)                \
  X(vkCmdSetScissor)                 \
  X(vkCmdBlitImage)                  \
  X(vkCmdClearColorImage)

struct Dispatch {
#define TYNDALL_DECLARE(name) PFN_##name name = nullptr;
  TYNDALL_INSTANCE_FUNCTIONS(TYNDALL_DECLARE)
  TYNDALL_DEVICE_FUNCTIONS(TYNDALL_DECLARE)
#undef TYNDALL_DECLARE
  // Core in Vulkan 1.3, or VK_KHR_dynamic_rendering: whichever the device exposes.
  PFN_vkCmdBeginRendering vkCmdBeginRendering = nullptr;
  PFN_vkCmdEndRendering vkCmdEndRendering = nullptr;

  /// Loads every entry point; returns the name of the first one missing, or nullptr.
  const char* load(VkInstance instance, VkDevice device, PFN_vkGetInstanceProcAddr getInstanceProcAddr,
                   PFN_vkGetDeviceProcAddr getDeviceProcAddr);
};

}  // namespace tyndall
