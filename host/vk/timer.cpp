#include "vk/timer.h"

#include <vector>

#include "vk/check.h"

namespace strata::vk {

DeviceTimer::DeviceTimer(const Context& ctx) : ctx_(ctx) {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical, &count, families.data());
    const std::uint32_t bits = families[ctx.queueFamily].timestampValidBits;
    if (bits == 0) return;
    mask_ = bits >= 64 ? ~0ull : ((1ull << bits) - 1ull);
    nsPerTick_ = ctx.properties.limits.timestampPeriod;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2;
    VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &pool_));
}

DeviceTimer::~DeviceTimer() {
    if (pool_) vkDestroyQueryPool(ctx_.device, pool_, nullptr);
}

void DeviceTimer::begin(VkCommandBuffer cmd) {
    if (!pool_) return;
    vkCmdResetQueryPool(cmd, pool_, 0, 2);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_, 0);
}

void DeviceTimer::end(VkCommandBuffer cmd) {
    if (!pool_) return;
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 1);
}

double DeviceTimer::seconds() const {
    if (!pool_) return 0.0;
    std::uint64_t t[2] = {0, 0};
    VK_CHECK(vkGetQueryPoolResults(ctx_.device, pool_, 0, 2, sizeof t, t, sizeof(std::uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const std::uint64_t ticks = ((t[1] & mask_) - (t[0] & mask_)) & mask_;
    return static_cast<double>(ticks) * nsPerTick_ * 1e-9;
}

}  // namespace strata::vk
