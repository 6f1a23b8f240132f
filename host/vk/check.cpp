#include "vk/check.h"

#include <filesystem>

namespace strata::vk {

const char* resultName(VkResult result) {
    switch (result) {
#define STRATA_CASE(r) case r: return #r;
        STRATA_CASE(VK_SUCCESS)
        STRATA_CASE(VK_NOT_READY)
        STRATA_CASE(VK_TIMEOUT)
        STRATA_CASE(VK_EVENT_SET)
        STRATA_CASE(VK_EVENT_RESET)
        STRATA_CASE(VK_INCOMPLETE)
        STRATA_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        STRATA_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        STRATA_CASE(VK_ERROR_INITIALIZATION_FAILED)
        STRATA_CASE(VK_ERROR_DEVICE_LOST)
        STRATA_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        STRATA_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        STRATA_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        STRATA_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        STRATA_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        STRATA_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        STRATA_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        STRATA_CASE(VK_ERROR_FRAGMENTED_POOL)
        STRATA_CASE(VK_ERROR_UNKNOWN)
        STRATA_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        STRATA_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        STRATA_CASE(VK_ERROR_FRAGMENTATION)
        STRATA_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
#undef STRATA_CASE
        default: return "VK_RESULT_UNKNOWN";
    }
}

void throwVkError(VkResult result, const char* call, const char* file, int line) {
    std::string what = std::string("Vulkan call failed with ") + resultName(result) + ": " + call +
                       " (" + std::filesystem::path(file).filename().string() + ":" +
                       std::to_string(line) + ")";
    if (result == VK_ERROR_DEVICE_LOST) what = "the Vulkan device was lost: " + what;
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY) what = "the Vulkan device ran out of memory: " + what;
    if (result == VK_ERROR_OUT_OF_HOST_MEMORY) what = "the Vulkan driver ran out of host memory: " + what;
    throw DeviceError(what);
}

}  // namespace strata::vk
