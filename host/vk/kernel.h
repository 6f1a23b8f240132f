// A compute kernel: shader module + descriptor set layout + one descriptor
// set + pipeline with specialization constants and a push-constant block.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
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

// What a Kernel compiles: shader module, set and pipeline layouts, pipeline.
struct Program {
    double pipelineMs = 0.0;  // host milliseconds vkCreateComputePipelines took
    VkDevice device = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    Program() = default;
    ~Program();
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;
};

class Kernel {
public:
    // `spirv` is the module's words; specialization constant i gets value
    // specConstants[i] (all 32-bit). With `reuse`, a Program compiled for a
    // Kernel of the same words, bindings, push-constant size and constants
    // is shared instead of compiled again (lavapipe's pipeline cache keeps
    // nothing, and LLVM compiles the path tracer anew each time); each
    // Kernel still has its own descriptor set.
    Kernel(const Context& ctx, std::span<const std::uint32_t> spirv,
           std::vector<BindingDesc> bindings, std::uint32_t pushConstantBytes,
           std::vector<std::uint32_t> specConstants, bool reuse = false);
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

    // Host milliseconds vkCreateComputePipelines took for this kernel (0
    // when it reused a Program).
    double pipelineMs() const { return pipelineMs_; }
    bool reusedProgram() const { return reused_; }

private:
    VkDescriptorType typeOf(std::uint32_t binding) const;
    // One descriptor of set_: a buffer range or a texel view.
    void write(std::uint32_t binding, const VkDescriptorBufferInfo* buffer, const VkBufferView* view);
    void record(VkCommandBuffer cmd, const void* push) const;  // binds pipeline and set, pushes
    const Context& ctx_;
    std::vector<BindingDesc> bindings_;
    std::uint32_t pushBytes_ = 0;
    double pipelineMs_ = 0.0;
    bool reused_ = false;
    std::shared_ptr<Program> program_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace strata::vk
