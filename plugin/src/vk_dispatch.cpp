#include "vk_dispatch.h"

namespace tyndall {

const char* Dispatch::load(VkInstance instance, VkDevice device,
                           PFN_vkGetInstanceProcAddr getInstanceProcAddr,
                           PFN_vkGetDeviceProcAddr getDeviceProcAddr) {
#define TYNDALL_LOAD_INSTANCE(name)                                                   \
  name = reinterpret_cast<PFN_##name>(getInstanceProcAddr(instance, #name));          \
  if (name == nullptr) return #name;
#define TYNDALL_LOAD_DEVICE(name)                                                     \
  name = reinterpret_cast<PFN_##name>(getDeviceProcAddr(device, #name));              \
  if (name == nullptr) return #name;
  TYNDALL_INSTANCE_FUNCTIONS(TYNDALL_LOAD_INSTANCE)
  TYNDALL_DEVICE_FUNCTIONS(TYNDALL_LOAD_DEVICE)
#undef TYNDALL_LOAD_INSTANCE
#undef TYNDALL_LOAD_DEVICE

  vkCmdBeginRendering =
      reinterpret_cast<PFN_vkCmdBeginRendering>(getDeviceProcAddr(device, "vkCmdBeginRendering"));
  vkCmdEndRendering =
      reinterpret_cast<PFN_vkCmdEndRendering>(getDeviceProcAddr(device, "vkCmdEndRendering"));
  if (vkCmdBeginRendering == nullptr || vkCmdEndRendering == nullptr) {
    vkCmdBeginRendering = reinterpret_cast<PFN_vkCmdBeginRendering>(
        getDeviceProcAddr(device, "vkCmdBeginRenderingKHR"));
    vkCmdEndRendering = reinterpret_cast<PFN_vkCmdEndRendering>(
        getDeviceProcAddr(device, "vkCmdEndRenderingKHR"));
  }
  if (vkCmdBeginRendering == nullptr) return "vkCmdBeginRendering";
  if (vkCmdEndRendering == nullptr) return "vkCmdEndRendering";
  return nullptr;
}

}  // namespace tyndall
