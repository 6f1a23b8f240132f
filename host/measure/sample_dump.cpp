#include "measure/sample_dump.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "spirv/cache.h"

#include "../../shaders/shared/bindings.h"
#include "../../shaders/shared/types.h"
#include "integrate/kernels.h"
#include "pack/textures.h"
#include "upload/device_scene.h"
#include "settings/filter.h"
#include "render/sampler_kind.h"
#include "vk/buffer.h"
#include "vk/kernel.h"

namespace strata {

std::vector<glm::vec4> runSampleKernel(const vk::Context& ctx, const gpu::SampleTestParams& params,
                                       std::uint32_t sampler, const std::vector<gpu::Emitter>& emitters,
                                       const PixelFilter& filter, const GpuScene* lights,
                                       std::uint32_t features) {
    using namespace gpu;
    const GpuScene none;
    const GpuScene& scene = lights ? *lights : none;
    const DeviceArray em = uploadArray(ctx, lights ? lights->emitters : emitters, sceneLimits(ctx));
    const DeviceArray tree = uploadArray(ctx, scene.lightTree, sceneLimits(ctx));
    FrameUniforms fu{};
    setLightUniforms(fu, scene);
    vk::Buffer frame(ctx, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);
    std::memcpy(frame.mapped(), &fu, sizeof fu);
    DeviceScene env;
    uploadEnvironment(ctx, scene, env, sceneLimits(ctx));
    vk::Buffer table = vk::uploadVector(ctx, filterInverseCdf(filter), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    // The BSDF's sheen reads its albedo table from the texel words.
    vk::Buffer texels = vk::uploadVector(ctx, sheenAlbedoWords(), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    vk::TexelView texelsView(ctx, texels, VK_FORMAT_R32_UINT);
    const VkDeviceSize bytes = std::max<VkDeviceSize>(16, VkDeviceSize(params.count) * sizeof(glm::vec4));
    vk::Buffer out(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                   vk::MemoryUse::Device);
    vk::Buffer back(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    std::vector<std::uint32_t> spec(4, 0u);
    spec[SPEC_SAMPLER] = sampler;
    spec[SPEC_FEATURES] = scene.features.bits | features;
    spirv::VariantInputs inputs;
    inputs.features = spec[SPEC_FEATURES];
    vk::Kernel kernel(ctx, spirv::moduleFor(spirv::chooseVariant(spirv::KernelId::SampleTest, inputs)),
                      {{BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                       {BINDING_EMITTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_EMITTERS_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                       {BINDING_LIGHT_TREE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_LIGHT_TREE_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                       {BINDING_SAMPLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_FILTER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_ENV_TEXELS, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                       {BINDING_ENV_CDF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_ENV_CDF_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                       {BINDING_TEXELS, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER}},
                      sizeof(SampleTestParams), spec, /*reuse=*/true);
    kernel.bind(BINDING_FRAME, frame);
    kernel.bind(BINDING_ENV_TEXELS, env.envTexelView);
    bindArray(kernel, BINDING_ENV_CDF, BINDING_ENV_CDF_TEXEL, env.envTables);
    bindArray(kernel, BINDING_EMITTERS, BINDING_EMITTERS_TEXEL, em);
    bindArray(kernel, BINDING_LIGHT_TREE, BINDING_LIGHT_TREE_TEXEL, tree);
    kernel.bind(BINDING_SAMPLES, out);
    kernel.bind(BINDING_FILTER, table);
    kernel.bind(BINDING_TEXELS, texelsView);
    vk::OneShot submit(ctx);
    VkCommandBuffer cmd = submit.begin();
    kernel.dispatch(cmd, &params, (params.count + 63) / 64);
    vk::recordReadback(cmd, out, back, bytes);
    submit.submitAndWait();
    back.invalidate();
    std::vector<glm::vec4> samples(params.count);
    std::memcpy(samples.data(), back.mapped(), samples.size() * sizeof(glm::vec4));
    return samples;
}

std::vector<glm::vec4> drawPixelSamples(const vk::Context& ctx, const PixelSampleRequest& req) {
    checkSamplerSettings(samplerByKind(req.sampler), req.spp, static_cast<int>(req.width),
                         static_cast<int>(req.height));
    const std::uint64_t w = req.blockWidth, h = req.blockHeight;
    if (w == 0 || h == 0 || req.pixelX + w > req.width || req.pixelY + h > req.height)
        throw std::invalid_argument("drawPixelSamples: the pixel block is empty or leaves the image");
    const std::uint64_t count = std::uint64_t(req.spp) * w * h;
    if (count > kMaxPixelSamples) throw std::invalid_argument("drawPixelSamples: too many samples for one dispatch");
    gpu::SampleTestParams p{};
    p.count = static_cast<std::uint32_t>(count);
    p.blockWidth = req.blockWidth;
    p.routine = gpu::kSamplePixel;
    p.seed = req.seed;
    p.pixelX = req.pixelX;
    p.pixelY = req.pixelY;
    p.width = req.width;
    p.spp = req.spp;
    return runSampleKernel(ctx, p, req.sampler);
}

}  // namespace strata
