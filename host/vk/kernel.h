// A compute kernel: shader module + descriptor set layout + one descriptor
// set + pipeline with specialization constants and a push-constant block.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/buffer.h"
#include "vk/context.h"

namespace strata::vk {

struct BindingDesc {
    std::uint32_t binding;
    VkDescriptorType type;  // STORAGE_BUFFER, UNIFORM_BUFFER or UNIFORM_TEXEL_BUFFER
};

// A VkBufferView over the first `range` bytes of a buffer (VK_WHOLE_SIZE: all
// of it; RGBA32UI texels by default), move-only.
class TexelView {
public:
    TexelView() = default;
    TexelView(const Context& ctx, const Buffer& buffer, VkFormat format = VK_FORMAT_R32G32B32A32_UINT,
              VkDeviceSize range = VK_WHOLE_SIZE);
    ~TexelView();
    TexelView(TexelView&& o) noexcept;
    TexelView& operator=(TexelView&& o) noexcept;
    TexelView(const TexelView&) = delete;
    TexelView& operator=(const TexelView&) = delete;
    VkBufferView handle() const { return view_; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkBufferView view_ = VK_NULL_HANDLE;
};

class Kernel {
public:
    // `spirv` is the module's words; specialization constant i gets value
    // specConstants[i] (all 32-bit).
    Kernel(const Context& ctx, std::span<const std::uint32_t> spirv,
           std::vector<BindingDesc> bindings, std::uint32_t pushConstantBytes,
           std::vector<std::uint32_t> specConstants);
    ~Kernel();
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;

    // Binds the first `range` bytes of `buffer` (VK_WHOLE_SIZE: all of it).
    void bind(std::uint32_t binding, const Buffer& buffer, VkDeviceSize range = VK_WHOLE_SIZE);
    void bind(std::uint32_t binding, const TexelView& view);

    // Binds pipeline + set, pushes `push` (pushConstantBytes) and dispatches.
    void dispatch(VkCommandBuffer cmd, const void* push, std::uint32_t groupsX,
                  std::uint32_t groupsY = 1, std::uint32_t groupsZ = 1) const;
    // The same with the group counts read from `args` at `offset`
    // (VkDispatchIndirectCommand, written by an earlier dispatch).
    void dispatchIndirect(VkCommandBuffer cmd, const void* push, const Buffer& args, VkDeviceSize offset) const;

    // Host milliseconds vkCreateComputePipelines took for this kernel.
    double pipelineMs() const { return pipelineMs_; }

private:
    VkDescriptorType typeOf(std::uint32_t binding) const;
    void record(VkCommandBuffer cmd, const void* push) const;  // binds pipeline and set, pushes
    const Context& ctx_;
    std::vector<BindingDesc> bindings_;
    std::uint32_t pushBytes_ = 0;
    double pipelineMs_ = 0.0;
    VkShaderModule module_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace strata::vk
