// VK_CHECK: every Vulkan call is checked, always (not only in debug builds).
// A failure throws strata::DeviceError naming the call site and VkResult.
#pragma once
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace strata::vk {

// A Vulkan call failed, or the device stopped answering. Not a user error:
// main reports it as one line and exits with status 3.
struct DeviceError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

const char* resultName(VkResult result);

[[noreturn]] void throwVkError(VkResult result, const char* call, const char* file, int line);

}  // namespace strata::vk

#define VK_CHECK(call)                                                              \
    do {                                                                            \
        VkResult vkCheckResult_ = (call);                                           \
        if (vkCheckResult_ != VK_SUCCESS)                                           \
            ::strata::vk::throwVkError(vkCheckResult_, #call, __FILE__, __LINE__);  \
    } while (0)
