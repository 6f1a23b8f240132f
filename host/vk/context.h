// Vulkan instance, physical-device choice, logical device and its compute
// queue. One Context per process; everything else borrows it.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

namespace strata::vk {

struct DeviceInfo {
    std::uint32_t index = 0;
    std::string name;
    std::string type;          // "discrete GPU", "integrated GPU", "CPU", ...
    std::string driver;        // driver name and info
    std::string apiVersion;    // "1.3.230"
    VkPhysicalDeviceType vkType = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::uint32_t subgroupSize = 1;  // VkPhysicalDeviceSubgroupProperties::subgroupSize
};

struct ContextOptions {
    int deviceIndex = -1;      // -1: discrete, else integrated, else CPU, else first
    bool validation = false;   // enable VK_LAYER_KHRONOS_validation + messenger
    // A window to present to (strata view): the instance extensions its
    // surface needs, and the surface made once the instance exists. The
    // queue must then present to it too, and the device gets
    // VK_KHR_swapchain; without a surface nothing changes.
    std::vector<std::string> instanceExtensions;
    std::function<VkSurfaceKHR(VkInstance)> makeSurface;
};

struct Context {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    DeviceInfo info;
    bool validation = false;
    VkSurfaceKHR surface = VK_NULL_HANDLE;  // ContextOptions::makeSurface's; destroyed with the
                                            // instance, or before by destroySurface
    // Compiled pipelines that Kernels built with reuse share (vk/kernel.h),
    // most recently used first, at most kMaxReusedPrograms; released before
    // the device.
    static constexpr std::size_t kMaxReusedPrograms = 8;
    mutable std::list<std::pair<std::string, std::shared_ptr<void>>> programs;
    mutable std::mutex programsMutex;

    explicit Context(const ContextOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags want) const;
    // Destroys the surface (its window is about to go); the device stays.
    void destroySurface();

private:
    void release();
};

// The memory a render may use on a device: its largest device-local heap;
// on a CPU device (lavapipe) at most the host memory budget, since its
// memory is the host's. `what` says which.
struct DeviceMemory {
    std::uint64_t bytes = 0;
    const char* what = "";
};
DeviceMemory deviceMemory(const VkPhysicalDeviceMemoryProperties& memory, VkPhysicalDeviceType type);

// The device ContextOptions{deviceIndex} would open, its name and memory,
// read without opening it (an instance made and destroyed), so that a
// scene can be refused for its size before it is built; nothing when no
// device can be found (opening it then says why).
struct DeviceMemoryProbe {
    std::string name;
    DeviceMemory memory;
};
std::optional<DeviceMemoryProbe> probeDeviceMemory(int deviceIndex);

// Messages from the validation layers (warnings and errors) since start-up.
// Tests assert this stays zero.
std::uint64_t validationMessageCount();
// Sets the count back to zero (for the test that provokes a message on purpose).
void resetValidationMessageCount();

// All Vulkan physical devices, in the loader's order.
std::vector<DeviceInfo> listDevices();

// True when STRATA_VALIDATION is set to a non-empty value other than "0".
bool validationRequestedByEnvironment();

}  // namespace strata::vk
