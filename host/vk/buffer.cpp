#include "vk/buffer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>

#include "util/memory.h"
#include "vk/check.h"

namespace strata::vk {
namespace {

std::atomic<std::uint64_t> gDeviceBytes{0};
std::atomic<std::uint64_t> gPeakDeviceBytes{0};

void countAllocation(std::uint64_t bytes) {
    const std::uint64_t now = gDeviceBytes += bytes;
    std::uint64_t peak = gPeakDeviceBytes.load();
    while (now > peak && !gPeakDeviceBytes.compare_exchange_weak(peak, now)) {
    }
}

// STRATA_FAULT=device-lost:N or out-of-device-memory:N makes the process's
// Nth submission (counted from 1) end in that VkResult once the device has
// run it, and, for a lost device, every later one too. No driver loses a
// device or runs out of memory on request, so the tests of the failure path
// (docs/testing.md) inject it here; unset, it costs one comparison.
VkResult injectedFault() {
    struct Fault {
        VkResult result = VK_SUCCESS;
        unsigned long at = 0;
    };
    static const Fault fault = [] {
        Fault f;
        const char* env = std::getenv("STRATA_FAULT");
        if (!env || !*env) return f;
        const std::string s = env;
        const std::size_t colon = s.find(':');
        const std::string kind = s.substr(0, colon);
        char* end = nullptr;
        const unsigned long at = colon == std::string::npos ? 0 : std::strtoul(s.c_str() + colon + 1, &end, 10);
        if (at == 0 || *end != '\0' || (kind != "device-lost" && kind != "out-of-device-memory"))
            throw DeviceError("STRATA_FAULT=" + s + ": expected device-lost:N or out-of-device-memory:N, N >= 1");
        f.result = kind == "device-lost" ? VK_ERROR_DEVICE_LOST : VK_ERROR_OUT_OF_DEVICE_MEMORY;
        f.at = at;
        return f;
    }();
    if (fault.at == 0) return VK_SUCCESS;
    static std::atomic<unsigned long> submissions{0};
    const unsigned long n = ++submissions;
    return n == fault.at || (n > fault.at && fault.result == VK_ERROR_DEVICE_LOST) ? fault.result : VK_SUCCESS;
}

}  // namespace

std::uint64_t deviceMemoryBytes() { return gDeviceBytes.load(); }
std::uint64_t peakDeviceMemoryBytes() { return gPeakDeviceBytes.load(); }

Buffer::Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use)
    : device_(ctx.device), size_(size) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer_));

    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer_, &req);
    std::uint32_t type = 0;
    switch (use) {
        case MemoryUse::Device:
            type = ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
            break;
        case MemoryUse::Upload:
            type = ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                              VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
            break;
        case MemoryUse::Readback:
            try {
                type = ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                  VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
            } catch (const DeviceError&) {
                type = ctx.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
            }
            break;
    }
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    VkResult r = vkAllocateMemory(device_, &alloc, nullptr, &memory_);
    if (r != VK_SUCCESS) {
        reset();
        throwVkError(r, "vkAllocateMemory", __FILE__, __LINE__);
    }
    allocated_ = req.size;
    countAllocation(allocated_);
    VK_CHECK(vkBindBufferMemory(device_, buffer_, memory_, 0));
    const VkMemoryPropertyFlags flags = ctx.memory.memoryTypes[type].propertyFlags;
    coherent_ = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    constexpr VkMemoryPropertyFlags hostCoherent =
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (use != MemoryUse::Device || (flags & hostCoherent) == hostCoherent)
        VK_CHECK(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

Buffer::~Buffer() { reset(); }

Buffer::Buffer(Buffer&& o) noexcept { *this = std::move(o); }

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        reset();
        std::swap(device_, o.device_);
        std::swap(buffer_, o.buffer_);
        std::swap(memory_, o.memory_);
        std::swap(size_, o.size_);
        std::swap(allocated_, o.allocated_);
        std::swap(mapped_, o.mapped_);
        std::swap(coherent_, o.coherent_);
    }
    return *this;
}

void Buffer::reset() {
    if (!device_) return;
    if (mapped_) vkUnmapMemory(device_, memory_);
    if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
    if (memory_) vkFreeMemory(device_, memory_, nullptr);
    gDeviceBytes -= allocated_;
    allocated_ = 0;
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    device_ = VK_NULL_HANDLE;
    size_ = 0;
}

void Buffer::invalidate() const {
    if (coherent_ || !mapped_) return;
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = memory_;
    range.offset = 0;
    range.size = VK_WHOLE_SIZE;
    VK_CHECK(vkInvalidateMappedMemoryRanges(device_, 1, &range));
}

OneShot::OneShot(const Context& ctx) : ctx_(ctx) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = ctx.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &cmd_));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkResult r = vkCreateFence(ctx.device, &fenceInfo, nullptr, &fence_);
    if (r != VK_SUCCESS) {
        vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &cmd_);
        throwVkError(r, "vkCreateFence", __FILE__, __LINE__);
    }
}

OneShot::~OneShot() {
    vkDestroyFence(ctx_.device, fence_, nullptr);
    vkFreeCommandBuffers(ctx_.device, ctx_.commandPool, 1, &cmd_);
}

VkCommandBuffer OneShot::begin() {
    VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd_, &info));
    return cmd_;
}

void OneShot::submitAndWait(double timeoutSeconds) {
    VK_CHECK(vkEndCommandBuffer(cmd_));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    VK_CHECK(vkResetFences(ctx_.device, 1, &fence_));
    VK_CHECK(vkQueueSubmit(ctx_.queue, 1, &submit, fence_));
    const auto ns = static_cast<std::uint64_t>(timeoutSeconds * 1e9);
    VkResult r = vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, ns);
    if (r == VK_TIMEOUT)
        throw DeviceError("the device did not finish a submission within " +
                          std::to_string(static_cast<int>(timeoutSeconds)) + " s (hung device?)");
    if (r == VK_SUCCESS) r = injectedFault();
    if (r != VK_SUCCESS) throwVkError(r, "vkWaitForFences", __FILE__, __LINE__);
}

Buffer uploadBuffer(const Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                    bool releaseSource) {
    const VkDeviceSize size = std::max<VkDeviceSize>(16, (bytes.size() + 15) & ~VkDeviceSize(15));
    Buffer buffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    auto fill = [&](void* dst, VkDeviceSize offset, VkDeviceSize n) {
        const VkDeviceSize data = offset < bytes.size() ? std::min<VkDeviceSize>(n, bytes.size() - offset) : 0;
        if (data > 0) std::memcpy(dst, bytes.data() + offset, data);
        if (data < n) std::memset(static_cast<std::byte*>(dst) + data, 0, n - data);
        if (releaseSource && data > 0) discardPages(bytes.data() + offset, data);
    };
    const VkDeviceSize chunk = std::min(size, kStagingBytes);
    if (buffer.mapped()) {  // host-visible, coherent device memory: no copy on the device
        adviseHugePages(buffer.mapped(), size);  // host memory on lavapipe, touched here first
        for (VkDeviceSize offset = 0; offset < size; offset += chunk)
            fill(static_cast<std::byte*>(buffer.mapped()) + offset, offset, std::min(chunk, size - offset));
        return buffer;
    }
    Buffer staging(ctx, chunk, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
    OneShot once(ctx);
    for (VkDeviceSize offset = 0; offset < size; offset += chunk) {
        const VkDeviceSize n = std::min(chunk, size - offset);
        fill(staging.mapped(), offset, n);
        VkCommandBuffer cmd = once.begin();
        VkBufferCopy region{0, offset, n};
        vkCmdCopyBuffer(cmd, staging.handle(), buffer.handle(), 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
        once.submitAndWait();
    }
    return buffer;
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dst, VkAccessFlags dstAccess) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void recordReadback(VkCommandBuffer cmd, const Buffer& src, const Buffer& dst, VkDeviceSize bytes) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

}  // namespace strata::vk
