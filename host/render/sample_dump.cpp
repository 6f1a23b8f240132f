#include "render/sample_dump.h"

#include <cstring>

#include <strata_spirv.h>

#include "../../shaders/shared/bindings.h"
#include "../../shaders/shared/types.h"
#include "render/filter.h"
#include "render/sampler_kind.h"
#include "vk/buffer.h"
#include "vk/kernel.h"

namespace strata {

std::vector<glm::vec4> drawPixelSamples(const vk::Context& ctx, const PixelSampleRequest& req) {
    using namespace gpu;
    checkSamplerSettings(samplerByKind(req.sampler), req.spp, static_cast<int>(req.width),
                         static_cast<int>(req.height));
    const std::vector<Emitter> none;
    vk::Buffer em = vk::uploadVector(ctx, none, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vk::Buffer filterTable = vk::uploadVector(ctx, filterInverseCdf(PixelFilter{}), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(req.spp) * sizeof(glm::vec4);
    vk::Buffer out(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                   vk::MemoryUse::Device);
    vk::Buffer back(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    std::vector<std::uint32_t> spec(3, 0u);
    spec[SPEC_SAMPLER] = req.sampler;
    vk::Kernel kernel(ctx, {kSpirvPtr_sample_test, kSpirvSize_sample_test / 4},
                      {{BINDING_EMITTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_SAMPLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_FILTER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                      sizeof(SampleTestParams), spec);
    kernel.bind(BINDING_EMITTERS, em);
    kernel.bind(BINDING_SAMPLES, out);
    kernel.bind(BINDING_FILTER, filterTable);
    vk::OneShot submit(ctx);
    VkCommandBuffer cmd = submit.begin();
    SampleTestParams p{};
    p.count = req.spp;
    p.routine = kSamplePixel;
    p.seed = req.seed;
    p.pixelX = req.pixelX;
    p.pixelY = req.pixelY;
    p.width = req.width;
    p.spp = req.spp;
    kernel.dispatch(cmd, &p, (req.spp + 63) / 64);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, out.handle(), back.handle(), 1, &region);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    submit.submitAndWait();
    back.invalidate();
    std::vector<glm::vec4> samples(req.spp);
    std::memcpy(samples.data(), back.mapped(), bytes);
    return samples;
}

}  // namespace strata
