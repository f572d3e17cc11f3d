// The smallest complete Tyndall integration: what an engine creates once, what it passes each
// frame, and how it submits. Headless: the "engine" here clears its depth buffer, back buffer and
// shadow map instead of rendering a scene, then lets Tyndall add fog-lit sky to the back buffer.
// Walk-through: docs/INTEGRATION.md. Exit status 0 when the result is what radiometry predicts.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <vulkan/vulkan.h>

#include "tyndall/tyndall.h"

namespace {

#define CHECK(call)                                                         \
  do {                                                                      \
    VkResult r_ = (call);                                                   \
    if (r_ != VK_SUCCESS) {                                                 \
      std::fprintf(stderr, "%s failed: %d\n", #call, static_cast<int>(r_)); \
      std::exit(1);                                                         \
    }                                                                       \
  } while (0)

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
};

std::uint32_t memoryType(VkPhysicalDevice gpu, std::uint32_t bits, VkMemoryPropertyFlags flags) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(gpu, &props);
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  }
  std::fprintf(stderr, "no suitable memory type\n");
  std::exit(1);
}

Image makeImage(VkPhysicalDevice gpu, VkDevice device, VkFormat format, VkExtent2D extent,
                VkImageUsageFlags usage, VkImageAspectFlags aspect) {
  Image out;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {extent.width, extent.height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  CHECK(vkCreateImage(device, &info, nullptr, &out.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, out.image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = memoryType(gpu, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  CHECK(vkAllocateMemory(device, &alloc, nullptr, &out.memory));
  CHECK(vkBindImageMemory(device, out.image, out.memory, 0));
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = out.image;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {aspect, 0, 1, 0, 1};
  CHECK(vkCreateImageView(device, &view, nullptr, &out.view));
  return out;
}

void destroyImage(VkDevice device, Image& image) {
  vkDestroyImageView(device, image.view, nullptr);
  vkDestroyImage(device, image.image, nullptr);
  vkFreeMemory(device, image.memory, nullptr);
}

void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                VkImageLayout to) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &b);
}

}  // namespace

int main() {
  // --- Engine start-up: instance, device with the features Tyndall needs. --------------------
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  VkInstance instance;
  CHECK(vkCreateInstance(&instanceInfo, nullptr, &instance));
  std::uint32_t count = 1;
  VkPhysicalDevice gpu;
  VkResult enumerated = vkEnumeratePhysicalDevices(instance, &count, &gpu);
  if ((enumerated != VK_SUCCESS && enumerated != VK_INCOMPLETE) || count == 0) {
    std::fprintf(stderr, "no Vulkan device\n");
    return 1;
  }
  std::uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(gpu, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(gpu, &familyCount, families.data());
  std::uint32_t family = 0;
  while (family < familyCount &&
         (families[family].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) !=
             (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
    ++family;
  }
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = family;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  features13.dynamicRendering = VK_TRUE;  // Tyndall requires it
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &features13;
  features.features.dualSrcBlend = VK_TRUE;  // Tyndall requires it (one-pass composite)
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &features;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  VkDevice device;
  CHECK(vkCreateDevice(gpu, &deviceInfo, nullptr, &device));
  VkQueue queue;
  vkGetDeviceQueue(device, family, 0, &queue);

  // --- Engine render targets (normally rendered; here cleared). -------------------------------
  const VkExtent2D extent{32, 16};
  const std::uint32_t shadowSize = 64;
  const VkFormat colorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  Image depth = makeImage(gpu, device, VK_FORMAT_D32_SFLOAT, extent,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                              VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                          VK_IMAGE_ASPECT_DEPTH_BIT);
  Image shadow = makeImage(gpu, device, VK_FORMAT_D32_SFLOAT, {shadowSize, shadowSize},
                           VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                               VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                           VK_IMAGE_ASPECT_DEPTH_BIT);
  Image color = makeImage(gpu, device, colorFormat, extent,
                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                          VK_IMAGE_ASPECT_COLOR_BIT);
  // The L_in AOV is written by transfer; SAMPLED only because makeImage gives every image a view.
  Image aov = makeImage(gpu, device, VK_FORMAT_R32G32B32A32_SFLOAT, extent,
                        VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                        VK_IMAGE_ASPECT_COLOR_BIT);

  // --- Create the Tyndall context once. --------------------------------------------------------
  tyndall::ContextDesc desc;
  desc.instance = instance;
  desc.physicalDevice = gpu;
  desc.device = device;
  desc.getInstanceProcAddr = vkGetInstanceProcAddr;
  desc.getDeviceProcAddr = vkGetDeviceProcAddr;
  desc.queueFamilyIndex = family;
  desc.maxFramesInFlight = 1;
  desc.outputExtent = extent;
  desc.backBufferFormat = colorFormat;
  desc.messageCallback = [](tyndall::Severity, const char* message, void*) {
    std::fprintf(stderr, "tyndall: %s\n", message);
  };
  tyndall::Result<std::unique_ptr<tyndall::Context>> created = tyndall::Context::create(desc);
  if (!created) return 1;
  std::unique_ptr<tyndall::Context> context = std::move(created).value();

  // --- One frame. ------------------------------------------------------------------------------
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.queueFamilyIndex = family;
  VkCommandPool pool;
  CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  VkCommandBufferAllocateInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cmdInfo.commandPool = pool;
  cmdInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cmdInfo.commandBufferCount = 1;
  VkCommandBuffer cmd;
  CHECK(vkAllocateCommandBuffers(device, &cmdInfo, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  CHECK(vkBeginCommandBuffer(cmd, &begin));

  // The "scene": empty sky (depth at the far value 1), black back buffer, no occluder.
  const VkImageAspectFlags depthAspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  transition(cmd, depth.image, depthAspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  transition(cmd, shadow.image, depthAspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  transition(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  transition(cmd, aov.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  const VkClearDepthStencilValue far{1.0f, 0};
  const VkImageSubresourceRange depthRange{depthAspect, 0, 1, 0, 1};
  vkCmdClearDepthStencilImage(cmd, depth.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &far, 1, &depthRange);
  vkCmdClearDepthStencilImage(cmd, shadow.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &far, 1, &depthRange);
  const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
  const VkImageSubresourceRange colorRange{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &colorRange);
  transition(cmd, depth.image, depthAspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
  transition(cmd, shadow.image, depthAspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  transition(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

  // Camera at the origin looking down −Z, 90° vertical field of view, near 0.1, far 100
  // (Vulkan clip depth [0, 1], column-major). The light shines straight down.
  const float n = 0.1f, f = 100.0f, aspect = 2.0f;
  tyndall::Mat4 view{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  tyndall::Mat4 projection{1.0f / aspect, 0, 0, 0, 0, -1, 0, 0, 0, 0, f / (n - f), -1, 0, 0, f * n / (n - f), 0};
  // Orthographic light view covering x, z ∈ [−200, 200], looking down from y = 100.
  tyndall::Mat4 worldToShadow{1.0f / 200, 0, 0, 0, 0, 0, -1.0f / 200, 0, 0, -1.0f / 200, 0, 0, 0, 0, 0.5f, 1};

  const std::array<tyndall::MediumComponent, 1> medium{{{{0.02f, 0.02f, 0.02f}, {0.0f, 0.0f, 0.0f},
                                                         tyndall::PhaseFunction::Isotropic, 0.0f}}};
  const std::array<tyndall::ShadowMapDesc, 1> shadowMaps{{
      {{shadow.image, shadow.view, VK_FORMAT_D32_SFLOAT, 0, {shadowSize, shadowSize},
        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
       worldToShadow}}};
  tyndall::FrameDesc frame;
  frame.camera.view = view;
  frame.camera.projection = projection;
  frame.light.type = tyndall::LightType::Directional;
  frame.light.direction = {0.0f, -1.0f, 0.0f};
  frame.light.intensity = 10.0f;
  frame.medium = medium;
  frame.shadowMaps = shadowMaps;
  frame.depth = {depth.image, depth.view, VK_FORMAT_D32_SFLOAT, 0, extent,
                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  frame.color = {color.image, color.view, colorFormat, 0, extent, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  frame.scatteringOutput = {aov.image, aov.view, VK_FORMAT_R32G32B32A32_SFLOAT, 0, extent,
                            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
  frame.profile = tyndall::Profile::Reference;
  if (tyndall::Outcome o = context->record(cmd, frame); !o) return 1;

  // Read L_in back.
  VkBufferCreateInfo bufferInfo{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bufferInfo.size = VkDeviceSize(extent.width) * extent.height * 16;
  bufferInfo.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer;
  CHECK(vkCreateBuffer(device, &bufferInfo, nullptr, &buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = memoryType(gpu, req.memoryTypeBits,
                                     VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory bufferMemory;
  CHECK(vkAllocateMemory(device, &alloc, nullptr, &bufferMemory));
  CHECK(vkBindBufferMemory(device, buffer, bufferMemory, 0));
  transition(cmd, aov.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, aov.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
  VkMemoryBarrier hostRead{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  hostRead.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  hostRead.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &hostRead, 0,
                       nullptr, 0, nullptr);
  CHECK(vkEndCommandBuffer(cmd));

  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  CHECK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  CHECK(vkQueueSubmit(queue, 1, &submit, fence));
  CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));

  // The centre pixel looks (almost) straight down −Z through unshadowed fog to the far plane:
  // L_in = σ_s · p · E · (1 − e^{−σ_t s}) / σ_t with s ≈ far, p = 1/4π.
  void* mapped = nullptr;
  CHECK(vkMapMemory(device, bufferMemory, 0, VK_WHOLE_SIZE, 0, &mapped));
  const float* pixels = static_cast<const float*>(mapped);
  const std::size_t centre = (std::size_t(extent.height / 2) * extent.width + extent.width / 2) * 4;
  const float got = pixels[centre];
  vkUnmapMemory(device, bufferMemory);
  // Pixel centre (16.5, 8.5) of 32×16: a ray 1/32 off the axis in x and y; s = far / cos.
  const double x = (2.0 * 16.5 / 32 - 1) * aspect, y = 2.0 * 8.5 / 16 - 1;
  const double s = f * std::sqrt(1.0 + x * x + y * y);
  const double expected = 0.02 * (1.0 / (4.0 * M_PI)) * 10.0 * (1.0 - std::exp(-0.02 * s)) / 0.02;
  std::printf("minimal integration: L_in at the centre %.6f, expected %.6f (%s)\n", got, expected,
              to_string(context->stats().technique));

  // --- Shut down: the GPU is idle (fence waited), so the context may go. ----------------------
  context.reset();
  vkDestroyFence(device, fence, nullptr);
  vkDestroyBuffer(device, buffer, nullptr);
  vkFreeMemory(device, bufferMemory, nullptr);
  vkDestroyCommandPool(device, pool, nullptr);
  for (Image* image : {&depth, &shadow, &color, &aov}) destroyImage(device, *image);
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
  return std::abs(got - expected) <= 1e-3 * expected ? 0 : 1;
}
