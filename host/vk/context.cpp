#include "vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "util/error.h"
#include "util/memory.h"
#include "vk/check.h"

namespace strata::vk {
namespace {

std::atomic<std::uint64_t> gValidationMessages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        gValidationMessages.fetch_add(1);
        std::fprintf(stderr, "vulkan validation: %s\n", data->pMessage ? data->pMessage : "");
    }
    return VK_FALSE;
}

std::string versionString(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

const char* typeName(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
        default: return "other";
    }
}

DeviceInfo describe(VkPhysicalDevice device, std::uint32_t index) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    driver.pNext = &subgroup;
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &props);
    DeviceInfo info;
    info.index = index;
    info.name = props.properties.deviceName;
    info.vkType = props.properties.deviceType;
    info.type = typeName(props.properties.deviceType);
    info.driver = std::string(driver.driverName);
    if (driver.driverInfo[0]) info.driver += std::string(" ") + driver.driverInfo;
    info.apiVersion = versionString(props.properties.apiVersion);
    info.subgroupSize = std::max(1u, subgroup.subgroupSize);
    return info;
}

bool hasLayer(const char* name) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

VkInstance createInstance(bool validation, const std::vector<std::string>& wanted = {}) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "strata";
    app.pEngineName = "strata";
    app.apiVersion = VK_API_VERSION_1_1;
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (validation) {
        if (!hasLayer("VK_LAYER_KHRONOS_validation"))
            throw Error("strata: error: validation requested but VK_LAYER_KHRONOS_validation is "
                        "not installed (Debian package vulkan-validationlayers)");
        layers.push_back("VK_LAYER_KHRONOS_validation");
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    for (const std::string& e : wanted) extensions.push_back(e.c_str());
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = vkCreateInstance(&info, nullptr, &instance);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
        throw DeviceError(std::string("no Vulkan driver found (") + resultName(r) +
                          "); install mesa-vulkan-drivers for the CPU device");
    VK_CHECK(r);
    return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

int preferenceRank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

// The device ContextOptions::deviceIndex picks among `devices`: the index
// asked for, else the first of the most preferred type; -1 for an index
// past the list.
int chooseDevice(const std::vector<VkPhysicalDevice>& devices, int deviceIndex) {
    if (deviceIndex >= 0) return static_cast<std::size_t>(deviceIndex) < devices.size() ? deviceIndex : -1;
    int chosen = 0, best = 1 << 30;
    for (std::uint32_t i = 0; i < devices.size(); ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        const int rank = preferenceRank(p.deviceType);
        if (rank < best) best = rank, chosen = static_cast<int>(i);
    }
    return chosen;
}

}  // namespace

DeviceMemory deviceMemory(const VkPhysicalDeviceMemoryProperties& memory, VkPhysicalDeviceType type) {
    DeviceMemory m{0, "its largest device-local heap"};
    for (std::uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            m.bytes = std::max<std::uint64_t>(m.bytes, memory.memoryHeaps[i].size);
    const std::uint64_t host = type == VK_PHYSICAL_DEVICE_TYPE_CPU ? hostMemoryBudget() : 0;
    if (host > 0 && (m.bytes == 0 || host < m.bytes)) m = {host, "the host memory available: a CPU device's memory is the host's"};
    return m;
}

std::optional<DeviceMemoryProbe> probeDeviceMemory(int deviceIndex) {
    VkInstance instance = VK_NULL_HANDLE;
    try {
        instance = createInstance(false);
        const auto devices = physicalDevices(instance);
        const int chosen = devices.empty() ? -1 : chooseDevice(devices, deviceIndex);
        std::optional<DeviceMemoryProbe> out;
        if (chosen >= 0) {
            VkPhysicalDeviceProperties p;
            VkPhysicalDeviceMemoryProperties memory;
            vkGetPhysicalDeviceProperties(devices[std::size_t(chosen)], &p);
            vkGetPhysicalDeviceMemoryProperties(devices[std::size_t(chosen)], &memory);
            out = DeviceMemoryProbe{p.deviceName, deviceMemory(memory, p.deviceType)};
        }
        vkDestroyInstance(instance, nullptr);
        return out;
    } catch (...) {
        if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
        return std::nullopt;  // the device's own errors come when it is opened
    }
}

std::uint64_t validationMessageCount() { return gValidationMessages.load(); }

void resetValidationMessageCount() { gValidationMessages.store(0); }

bool validationRequestedByEnvironment() {
    const char* v = std::getenv("STRATA_VALIDATION");
    return v && *v && std::strcmp(v, "0") != 0;
}

std::vector<DeviceInfo> listDevices() {
    VkInstance instance = createInstance(false);
    std::vector<DeviceInfo> out;
    try {
        auto devices = physicalDevices(instance);
        for (std::uint32_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], i));
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
    vkDestroyInstance(instance, nullptr);
    return out;
}

Context::Context(const ContextOptions& options) {
    validation = options.validation || validationRequestedByEnvironment();
    instance = createInstance(validation, options.instanceExtensions);
    try {
        if (validation) {
            VkDebugUtilsMessengerCreateInfoEXT info{
                VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
            info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
            info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
            info.pfnUserCallback = onValidationMessage;
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
            if (!create) throw DeviceError("vkCreateDebugUtilsMessengerEXT is not available");
            VK_CHECK(create(instance, &info, nullptr, &messenger));
        }

        if (options.makeSurface) surface = options.makeSurface(instance);
        auto devices = physicalDevices(instance);
        if (devices.empty()) throw DeviceError("no Vulkan device found");
        const int pick = chooseDevice(devices, options.deviceIndex);
        if (pick < 0)
            throw Error("strata: error: --device " + std::to_string(options.deviceIndex) + " does not exist (" +
                        std::to_string(devices.size()) + " device(s); see 'strata devices')");
        const auto chosen = static_cast<std::uint32_t>(pick);
        physical = devices[chosen];
        info = describe(physical, chosen);
        vkGetPhysicalDeviceProperties(physical, &properties);
        vkGetPhysicalDeviceMemoryProperties(physical, &memory);
        if (properties.apiVersion < VK_API_VERSION_1_1)
            throw DeviceError("device " + info.name + " supports only Vulkan " + info.apiVersion +
                              "; strata needs 1.1");

        std::uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, families.data());
        bool found = false;
        for (std::uint32_t i = 0; i < familyCount && !found; ++i) {
            VkBool32 present = VK_TRUE;
            if (surface) VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(physical, i, surface, &present));
            if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && present) queueFamily = i, found = true;
        }
        if (!found && surface)
            throw Error("strata: error: device " + info.name + " has no queue that computes and presents to the window");
        if (!found) throw DeviceError("device " + info.name + " has no compute queue");
        const char* swapchain = VK_KHR_SWAPCHAIN_EXTENSION_NAME;

        float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queueInfo.queueFamilyIndex = queueFamily;
        queueInfo.queueCount = 1;
        queueInfo.pQueuePriorities = &priority;
        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        deviceInfo.queueCreateInfoCount = 1;
        deviceInfo.pQueueCreateInfos = &queueInfo;
        if (surface) {
            deviceInfo.enabledExtensionCount = 1;
            deviceInfo.ppEnabledExtensionNames = &swapchain;
        }
        VK_CHECK(vkCreateDevice(physical, &deviceInfo, nullptr, &device));
        vkGetDeviceQueue(device, queueFamily, 0, &queue);

        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        poolInfo.queueFamilyIndex = queueFamily;
        VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &commandPool));
    } catch (...) {
        release();
        throw;
    }
}

Context::~Context() { release(); }

void Context::destroySurface() {
    if (surface && instance) vkDestroySurfaceKHR(instance, surface, nullptr);
    surface = VK_NULL_HANDLE;
}

void Context::release() {
    if (device) {
        vkDeviceWaitIdle(device);
        programs.clear();
        if (commandPool) vkDestroyCommandPool(device, commandPool, nullptr);
        vkDestroyDevice(device, nullptr);
        device = VK_NULL_HANDLE;
        commandPool = VK_NULL_HANDLE;
    }
    destroySurface();
    if (messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance, messenger, nullptr);
        messenger = VK_NULL_HANDLE;
    }
    if (instance) {
        vkDestroyInstance(instance, nullptr);
        instance = VK_NULL_HANDLE;
    }
}

std::uint32_t Context::findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags want) const {
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & want) == want) return i;
    throw DeviceError("no Vulkan memory type with the required properties");
}

}  // namespace strata::vk
