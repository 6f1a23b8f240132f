#include "vk/kernel.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "vk/check.h"

namespace strata::vk {

TexelView::TexelView(const Context& ctx, const Buffer& buffer, VkFormat format, VkDeviceSize range)
    : device_(ctx.device) {
    VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    info.buffer = buffer.handle();
    info.format = format;
    info.offset = 0;
    info.range = range;
    VK_CHECK(vkCreateBufferView(device_, &info, nullptr, &view_));
}

TexelView::~TexelView() {
    if (view_) vkDestroyBufferView(device_, view_, nullptr);
}

TexelView::TexelView(TexelView&& o) noexcept { *this = std::move(o); }

TexelView& TexelView::operator=(TexelView&& o) noexcept {
    std::swap(device_, o.device_);
    std::swap(view_, o.view_);
    return *this;
}

Program::~Program() {
    if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
    if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
    if (setLayout) vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
    if (module) vkDestroyShaderModule(device, module, nullptr);
}

namespace {

std::shared_ptr<Program> compileProgram(VkDevice dev, std::span<const std::uint32_t> spirv,
                                        const std::vector<BindingDesc>& bindings, std::uint32_t pushBytes,
                                        const std::vector<std::uint32_t>& specConstants) {
    auto p = std::make_shared<Program>();
    p->device = dev;
    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = spirv.size_bytes();
    moduleInfo.pCode = spirv.data();
    VK_CHECK(vkCreateShaderModule(dev, &moduleInfo, nullptr, &p->module));

    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    for (const auto& b : bindings) {
        VkDescriptorSetLayoutBinding lb{};
        lb.binding = b.binding;
        lb.descriptorType = b.type;
        lb.descriptorCount = 1;
        lb.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        layoutBindings.push_back(lb);
    }
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = static_cast<std::uint32_t>(layoutBindings.size());
    setInfo.pBindings = layoutBindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(dev, &setInfo, nullptr, &p->setLayout));

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &p->setLayout;
    layoutInfo.pushConstantRangeCount = pushBytes ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(dev, &layoutInfo, nullptr, &p->layout));

    std::vector<VkSpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < specConstants.size(); ++i)
        entries.push_back({i, i * 4u, 4u});
    VkSpecializationInfo spec{};
    spec.mapEntryCount = static_cast<std::uint32_t>(entries.size());
    spec.pMapEntries = entries.data();
    spec.dataSize = specConstants.size() * 4u;
    spec.pData = specConstants.data();

    VkComputePipelineCreateInfo pipeInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipeInfo.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeInfo.stage.module = p->module;
    pipeInfo.stage.pName = "main";
    pipeInfo.stage.pSpecializationInfo = specConstants.empty() ? nullptr : &spec;
    pipeInfo.layout = p->layout;
    const auto t0 = std::chrono::steady_clock::now();
    VK_CHECK(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &pipeInfo, nullptr, &p->pipeline));
    p->pipelineMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return p;
}

// Everything a Program depends on: the bindings, the push-constant size,
// the constants and the module's words themselves.
std::string programKey(std::span<const std::uint32_t> spirv, const std::vector<BindingDesc>& bindings,
                       std::uint32_t pushBytes, const std::vector<std::uint32_t>& specConstants) {
    std::string key = std::to_string(pushBytes) + ":";
    for (const auto& b : bindings) key += std::to_string(b.binding) + "/" + std::to_string(int(b.type)) + ",";
    key += ":";
    for (std::uint32_t v : specConstants) key += std::to_string(v) + ",";
    key += ":";
    key.append(reinterpret_cast<const char*>(spirv.data()), spirv.size_bytes());
    return key;
}

}  // namespace

Kernel::Kernel(const Context& ctx, std::span<const std::uint32_t> spirv,
               std::vector<BindingDesc> bindings, std::uint32_t pushConstantBytes,
               std::vector<std::uint32_t> specConstants, bool reuse)
    : ctx_(ctx), bindings_(std::move(bindings)), pushBytes_(pushConstantBytes) {
    VkDevice dev = ctx.device;
    if (reuse) {
        const std::string key = programKey(spirv, bindings_, pushBytes_, specConstants);
        std::lock_guard<std::mutex> lock(ctx.programsMutex);
        auto& list = ctx.programs;
        const auto hit = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == key; });
        if (hit != list.end()) {
            list.splice(list.begin(), list, hit);  // most recently used first
            program_ = std::static_pointer_cast<Program>(list.front().second);
            reused_ = true;
        } else {
            program_ = compileProgram(dev, spirv, bindings_, pushBytes_, specConstants);
            list.emplace_front(key, program_);
            if (list.size() > Context::kMaxReusedPrograms) list.pop_back();
        }
    } else {
        program_ = compileProgram(dev, spirv, bindings_, pushBytes_, specConstants);
    }
    pipelineMs_ = reused_ ? 0.0 : program_->pipelineMs;

    std::map<VkDescriptorType, std::uint32_t> typeCounts;
    for (const auto& b : bindings_) ++typeCounts[b.type];
    std::vector<VkDescriptorPoolSize> sizes;
    for (auto [type, count] : typeCounts) sizes.push_back({type, count});
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
    poolInfo.pPoolSizes = sizes.data();
    VK_CHECK(vkCreateDescriptorPool(dev, &poolInfo, nullptr, &pool_));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &program_->setLayout;
    VK_CHECK(vkAllocateDescriptorSets(dev, &alloc, &set_));
}

Kernel::~Kernel() {
    if (pool_) vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);
}

VkDescriptorType Kernel::typeOf(std::uint32_t binding) const {
    for (const auto& b : bindings_)
        if (b.binding == binding) return b.type;
    throw DeviceError("kernel has no binding " + std::to_string(binding));
}

void Kernel::write(std::uint32_t binding, const VkDescriptorBufferInfo* buffer, const VkBufferView* view) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = typeOf(binding);
    write.pBufferInfo = buffer;
    write.pTexelBufferView = view;
    vkUpdateDescriptorSets(ctx_.device, 1, &write, 0, nullptr);
}

void Kernel::bind(std::uint32_t binding, const Buffer& buffer, VkDeviceSize range) {
    const VkDescriptorBufferInfo info{buffer.handle(), 0, range};
    write(binding, &info, nullptr);
}

void Kernel::bind(std::uint32_t binding, const TexelView& view) {
    const VkBufferView handle = view.handle();
    write(binding, nullptr, &handle);
}

void Kernel::record(VkCommandBuffer cmd, const void* push) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program_->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program_->layout, 0, 1, &set_, 0, nullptr);
    if (pushBytes_) vkCmdPushConstants(cmd, program_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes_, push);
}

void Kernel::dispatch(VkCommandBuffer cmd, const void* push, std::uint32_t gx, std::uint32_t gy,
                      std::uint32_t gz) const {
    record(cmd, push);
    vkCmdDispatch(cmd, gx, gy, gz);
}

void Kernel::dispatchIndirect(VkCommandBuffer cmd, const void* push, const Buffer& args, VkDeviceSize offset) const {
    record(cmd, push);
    vkCmdDispatchIndirect(cmd, args.handle(), offset);
}

}  // namespace strata::vk
