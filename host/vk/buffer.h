// Buffers: a move-only RAII handle over VkBuffer + its own VkDeviceMemory,
// persistently mapped when host-visible.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace strata::vk {

enum class MemoryUse {
    Device,    // device-local; filled through a staging copy
    Upload,    // host-visible, coherent (staging, uniforms)
    Readback,  // host-visible, cached when available
};

class Buffer {
public:
    Buffer() = default;
    Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);
    ~Buffer();
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    VkDeviceSize allocationSize() const { return allocated_; }  // bytes of its VkDeviceMemory
    // Host pointer to the memory: always for Upload and Readback; for Device
    // where device-local memory is also host-visible and coherent (lavapipe,
    // integrated GPUs, resizable BAR), else null.
    void* mapped() const { return mapped_; }
    // Makes device writes visible to the host for non-coherent memory.
    void invalidate() const;

private:
    void reset();
    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkDeviceSize allocated_ = 0;
    void* mapped_ = nullptr;
    bool coherent_ = true;
};

// Records and submits one command buffer, waiting on a fence. A wait longer
// than `timeoutSeconds` is reported as a hung device (DeviceError).
class OneShot {
public:
    explicit OneShot(const Context& ctx);
    ~OneShot();
    OneShot(const OneShot&) = delete;
    OneShot& operator=(const OneShot&) = delete;

    VkCommandBuffer begin();
    void submitAndWait(double timeoutSeconds = 120.0);

private:
    const Context& ctx_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

// Device memory (every VkDeviceMemory of a Buffer, all memory types) held by
// the process now, and the most it held at once.
std::uint64_t deviceMemoryBytes();
std::uint64_t peakDeviceMemoryBytes();

// A device-local buffer filled with `bytes`: written in place where that
// memory is host-visible, else copied through a staging buffer of at most
// kStagingBytes, reused chunk by chunk. Size is rounded up to 16 bytes and
// never zero (texel views need >= 1 element); the padding is zero.
// releaseSource: the caller reads `bytes` no more, so the whole pages of each
// chunk copied are handed back to the kernel as the copy goes
// (discardPages): the host never holds a large array twice, also where
// device memory is host memory (lavapipe).
inline constexpr VkDeviceSize kStagingBytes = VkDeviceSize(64) << 20;
Buffer uploadBuffer(const Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                    bool releaseSource = false);

template <class T>
Buffer uploadVector(const Context& ctx, const std::vector<T>& v, VkBufferUsageFlags usage) {
    return uploadBuffer(ctx, std::as_bytes(std::span<const T>(v)), usage);
}

// Memory barrier between two compute/transfer stages on the whole queue.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dst, VkAccessFlags dstAccess);

// Records the copy of the first `bytes` of `src` (written by compute shaders)
// into the host-readable `dst`, with the barriers before and after it.
void recordReadback(VkCommandBuffer cmd, const Buffer& src, const Buffer& dst, VkDeviceSize bytes);

}  // namespace strata::vk
