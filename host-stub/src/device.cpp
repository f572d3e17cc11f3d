// Headless Vulkan 1.3 device of the stub host, optionally under the Khronos validation layer with
// synchronization validation (the tests run every frame under it and expect zero messages).
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>

#include "tyndall_host/renderer.h"
#include "vk_util.h"

namespace tyndall::host {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool envFlag(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && std::strcmp(value, "1") == 0;
}

bool hasInstanceExtension(const char* layer, const char* extension) {
  std::uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
  std::vector<VkExtensionProperties> properties(count);
  vkEnumerateInstanceExtensionProperties(layer, &count, properties.data());
  for (const VkExtensionProperties& p : properties) {
    if (std::strcmp(p.extensionName, extension) == 0) return true;
  }
  return false;
}

bool hasLayer(const char* layer) {
  std::uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> properties(count);
  vkEnumerateInstanceLayerProperties(&count, properties.data());
  for (const VkLayerProperties& p : properties) {
    if (std::strcmp(p.layerName, layer) == 0) return true;
  }
  return false;
}

std::string oneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

}  // namespace

struct Device::Impl {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  std::string name;

  bool printValidation = false;
  // The layer may call back from whichever thread makes a Vulkan call.
  std::mutex messagesMutex;
  mutable std::mutex queueMutex;
  std::vector<std::string> messages;

  ~Impl() {
    if (device != VK_NULL_HANDLE) {
      vkDeviceWaitIdle(device);
      vkDestroyDevice(device, nullptr);
    }
    if (messenger != VK_NULL_HANDLE) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroy != nullptr) destroy(instance, messenger, nullptr);
    }
    if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
  }

  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                  void* userData) {
    auto* self = static_cast<Impl*>(userData);
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 ? "ERROR" : "WARNING";
    std::string line = std::string("[") + level + "] " +
                       (data->pMessageIdName != nullptr ? data->pMessageIdName : "") + ": " +
                       (data->pMessage != nullptr ? data->pMessage : "");
    line = oneLine(std::move(line));
    if (self->printValidation) std::cerr << line << '\n';
    std::lock_guard<std::mutex> lock(self->messagesMutex);
    self->messages.push_back(std::move(line));
    return VK_FALSE;  // never abort the call that triggered the message
  }

  bool createInstance(const DeviceOptions& options, std::string& error);
  bool pickPhysicalDevice(const DeviceOptions& options, std::string& error);
  bool createDevice(std::string& error);
};

bool Device::Impl::createInstance(const DeviceOptions& options, std::string& error) {
  std::uint32_t loaderVersion = 0;
  if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS || loaderVersion < VK_API_VERSION_1_3) {
    error = "the Vulkan loader does not support Vulkan 1.3";
    return false;
  }

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  if (options.validation) {
    if (!hasLayer(kValidationLayer)) {
      error = std::string("validation requested but ") + kValidationLayer +
              " is not installed (Debian: apt install vulkan-validationlayers)";
      return false;
    }
    if (!hasInstanceExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
      error = "validation requested but " VK_EXT_DEBUG_UTILS_EXTENSION_NAME " is not available";
      return false;
    }
    if (!hasInstanceExtension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
      error = std::string(kValidationLayer) + " lacks " VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME
              " (needed to turn on synchronization validation)";
      return false;
    }
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "tyndall-host-stub";
  app.pEngineName = "tyndall-host-stub";
  app.apiVersion = VK_API_VERSION_1_3;

  // Chained into the instance create info too, so messages from vkCreateInstance and
  // vkDestroyInstance are recorded as well.
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messengerInfo.pfnUserCallback = &Impl::onMessage;
  messengerInfo.pUserData = this;

  const VkValidationFeatureEnableEXT enabledFeatures[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT validationFeatures{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  validationFeatures.enabledValidationFeatureCount = 1;
  validationFeatures.pEnabledValidationFeatures = enabledFeatures;
  validationFeatures.pNext = &messengerInfo;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  if (options.validation) info.pNext = &validationFeatures;
  if (!vk::check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance", error)) return false;

  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create == nullptr) {
      error = "vkCreateDebugUtilsMessengerEXT is not available";
      return false;
    }
    if (!vk::check(create(instance, &messengerInfo, nullptr, &messenger),
                   "vkCreateDebugUtilsMessengerEXT", error)) {
      return false;
    }
  }
  return true;
}

bool Device::Impl::pickPhysicalDevice(const DeviceOptions& options, std::string& error) {
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  if (count == 0 || vkEnumeratePhysicalDevices(instance, &count, devices.data()) < 0) {
    error = "no Vulkan physical device found (is mesa-vulkan-drivers installed for lavapipe?)";
    return false;
  }

  const char* requested = std::getenv("TYNDALL_DEVICE");
  std::string available;
  VkPhysicalDevice chosen = VK_NULL_HANDLE;
  for (VkPhysicalDevice candidate : devices) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(candidate, &properties);
    available += std::string(available.empty() ? "" : ", ") + "\"" + properties.deviceName + "\"";
    if (requested != nullptr && requested[0] != '\0') {
      if (chosen == VK_NULL_HANDLE && std::strstr(properties.deviceName, requested) != nullptr)
        chosen = candidate;
    } else if (options.preferDiscreteGpu && chosen == VK_NULL_HANDLE &&
               properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) {
      chosen = candidate;
    }
  }
  if (requested != nullptr && requested[0] != '\0' && chosen == VK_NULL_HANDLE) {
    error = std::string("TYNDALL_DEVICE=\"") + requested + "\" matches no device; available: " + available;
    return false;
  }
  if (chosen == VK_NULL_HANDLE) chosen = devices.front();
  physicalDevice = chosen;

  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(physicalDevice, &properties);
  name = properties.deviceName;
  if (properties.apiVersion < VK_API_VERSION_1_3) {
    error = "device \"" + name + "\" does not support Vulkan 1.3";
    return false;
  }

  std::uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &familyCount, families.data());
  const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (std::uint32_t i = 0; i < familyCount; ++i) {
    if ((families[i].queueFlags & needed) == needed) {
      queueFamily = i;
      return true;
    }
  }
  error = "device \"" + name + "\" has no queue family with graphics and compute";
  return false;
}

bool Device::Impl::createDevice(std::string& error) {
  VkPhysicalDeviceVulkan13Features supported13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  supported12.pNext = &supported13;
  VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  supported.pNext = &supported12;
  vkGetPhysicalDeviceFeatures2(physicalDevice, &supported);

  struct Required {
    VkBool32 supported;
    const char* name;
  };
  std::string missing;
  for (const Required& feature : {Required{supported13.dynamicRendering, "dynamicRendering"},
                                  Required{supported13.synchronization2, "synchronization2"},
                                  Required{supported.features.dualSrcBlend, "dualSrcBlend"},
                                  Required{supported.features.depthClamp, "depthClamp"}}) {
    if (feature.supported == VK_FALSE) missing += std::string(missing.empty() ? "" : ", ") + feature.name;
  }
  if (!missing.empty()) {
    error = "device \"" + name + "\" lacks required features: " + missing;
    return false;
  }
  VkPhysicalDeviceVulkan13Features enabled13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  enabled13.dynamicRendering = VK_TRUE;
  enabled13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features enabled12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  enabled12.pNext = &enabled13;
  VkPhysicalDeviceFeatures2 enabled{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  enabled.pNext = &enabled12;
  enabled.features.dualSrcBlend = VK_TRUE;  // the plugin composites with dual-source blending
  enabled.features.depthClamp = VK_TRUE;    // the shadow pass keeps casters outside the depth range
  // Optional features a post-process commonly relies on, enabled where the device has them
  // (an engine enables what it can); nothing in the host depends on them.
  enabled12.hostQueryReset = supported12.hostQueryReset;
  enabled12.scalarBlockLayout = supported12.scalarBlockLayout;
  enabled.features.fragmentStoresAndAtomics = supported.features.fragmentStoresAndAtomics;
  enabled.features.shaderStorageImageWriteWithoutFormat =
      supported.features.shaderStorageImageWriteWithoutFormat;
  enabled.features.independentBlend = supported.features.independentBlend;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &enabled;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  if (!vk::check(vkCreateDevice(physicalDevice, &info, nullptr, &device), "vkCreateDevice", error))
    return false;
  vkGetDeviceQueue(device, queueFamily, 0, &queue);
  return true;
}

std::unique_ptr<Device> Device::create(const DeviceOptions& options, std::string& error) {
  auto impl = std::make_unique<Impl>();
  impl->printValidation = envFlag("TYNDALL_PRINT_VALIDATION");
  if (!impl->createInstance(options, error) || !impl->pickPhysicalDevice(options, error) ||
      !impl->createDevice(error)) {
    return nullptr;
  }
  return std::unique_ptr<Device>(new Device(std::move(impl)));
}

Device::Device(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Device::~Device() = default;

VkInstance Device::instance() const { return impl_->instance; }
VkPhysicalDevice Device::physicalDevice() const { return impl_->physicalDevice; }
VkDevice Device::device() const { return impl_->device; }
VkQueue Device::queue() const { return impl_->queue; }
std::uint32_t Device::queueFamily() const { return impl_->queueFamily; }
std::string Device::name() const { return impl_->name; }
PFN_vkGetInstanceProcAddr Device::getInstanceProcAddr() const { return &vkGetInstanceProcAddr; }
PFN_vkGetDeviceProcAddr Device::getDeviceProcAddr() const { return &vkGetDeviceProcAddr; }

std::mutex& Device::queueMutex() const { return impl_->queueMutex; }

const std::vector<std::string>& Device::validationMessages() const { return impl_->messages; }

void Device::clearValidationMessages() {
  std::lock_guard<std::mutex> lock(impl_->messagesMutex);
  impl_->messages.clear();
}

}  // namespace tyndall::host
