// Device time of command-buffer ranges from Vulkan timestamp queries.
#pragma once
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace strata::vk {

// Two timestamps around a range of commands in one command buffer. When the
// queue cannot write timestamps (timestampValidBits == 0) `supported()` is
// false and the recording calls do nothing.
class DeviceTimer {
public:
    explicit DeviceTimer(const Context& ctx);
    ~DeviceTimer();
    DeviceTimer(const DeviceTimer&) = delete;
    DeviceTimer& operator=(const DeviceTimer&) = delete;

    bool supported() const { return pool_ != VK_NULL_HANDLE; }
    void begin(VkCommandBuffer cmd);  // resets the queries, writes the first timestamp
    void end(VkCommandBuffer cmd);    // after the last timed command
    // Seconds between the two timestamps of the last completed submission.
    double seconds() const;

private:
    const Context& ctx_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    double nsPerTick_ = 1.0;
    std::uint64_t mask_ = ~0ull;
};

}  // namespace strata::vk
