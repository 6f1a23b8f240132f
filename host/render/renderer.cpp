#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include <unistd.h>

#include "../../shaders/shared/bindings.h"
#include "render/sampler_kind.h"
#include "render/wavefront.h"
#include "util/error.h"
#include "vk/check.h"
#include "vk/kernel.h"
#include "vk/timer.h"

namespace strata {
namespace {

using Clock = std::chrono::steady_clock;

// DispatchParams::blockStride for a tile: the integer nearest 0.618 times
// its count of 8x8 blocks that shares no factor with it, so that workgroup w
// shading block (w * stride) mod blocks visits every block once and any run
// of consecutive workgroups (one lavapipe thread's share) spreads evenly over
// the tile, as a rank-1 lattice with the golden ratio does. 1 (row order)
// above 65536 blocks, where w * stride would not fit the shader's 32 bits.
std::uint32_t blockStride(std::uint32_t tileW, std::uint32_t tileH) {
    const std::uint32_t blocks = ((tileW + 7) / 8) * ((tileH + 7) / 8);
    if (blocks > 65536) return 1;
    std::uint32_t stride = std::max(1u, static_cast<std::uint32_t>(std::lround(blocks * 0.6180339887498949)));
    while (std::gcd(stride, blocks) != 1) ++stride;
    return stride;
}

gpu::FrameUniforms frameUniforms(const DeviceScene& dev, const GpuScene& scene, const Camera& cam,
                                 const RenderSettings& s) {
    gpu::FrameUniforms f{};
    const float tanHalf = std::tan(cam.yfov * 0.5f);
    const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
    const glm::vec3 right = glm::normalize(glm::cross(cam.forward, cam.up));
    const glm::vec3 up = glm::cross(right, cam.forward);
    f.camOrigin = glm::vec4(cam.position, 0.0f);
    f.camForward = glm::vec4(cam.forward, 0.0f);
    f.camRight = glm::vec4(right * tanHalf * aspect, 0.0f);
    f.camUp = glm::vec4(up * tanHalf, 0.0f);
    f.image = glm::uvec4(s.width, s.height, s.maxDepth, s.seed);
    f.counts = glm::uvec4(scene.emitters.size(), dev.triangles, dev.nodeCount, s.spp);
    f.scene = glm::vec4(static_cast<float>(scene.totalPower), 0.0f, 0.0f, 0.0f);
    setLightUniforms(f, scene);
    return f;
}

void printProgress(std::uint32_t done, std::uint32_t total, double elapsed, double msps) {
    const double eta = done ? elapsed / done * (total - done) : 0.0;
    std::fprintf(stderr, "\rstrata: %u/%u spp  %.1f s  ETA %.1f s  %.2f Msamples/s   ", done, total,
                 elapsed, eta, msps);
    std::fflush(stderr);
}

}  // namespace

std::vector<vk::BindingDesc> pathBindings() {
    using namespace gpu;
    std::vector<vk::BindingDesc> bindings = sceneBindings();
    bindings.insert(bindings.end(), {
        {BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
        {BINDING_EMITTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_EMITTERS_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
        {BINDING_ACCUM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_COUNTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_FILTER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_ENV_TEXELS, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
        {BINDING_ENV_CDF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_ENV_CDF_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
    });
    return bindings;
}

void bindPathInputs(vk::Kernel& kernel, const DeviceScene& dev, const vk::Buffer& frame, const vk::Buffer& filterTable,
                    const vk::Buffer& accum, const vk::Buffer& counters) {
    using namespace gpu;
    bindTraversal(kernel, dev);
    kernel.bind(BINDING_FRAME, frame);
    bindArray(kernel, BINDING_EMITTERS, BINDING_EMITTERS_TEXEL, dev.emitters);
    kernel.bind(BINDING_ACCUM, accum);
    kernel.bind(BINDING_COUNTERS, counters);
    kernel.bind(BINDING_FILTER, filterTable);
    kernel.bind(BINDING_ENV_TEXELS, dev.envTexelView);
    bindArray(kernel, BINDING_ENV_CDF, BINDING_ENV_CDF_TEXEL, dev.envTables);
}

std::vector<std::uint32_t> pathSpec(const DeviceScene& dev, const GpuScene& scene, const RenderSettings& s) {
    using namespace gpu;
    std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1, 0u);
    setTraversalSpec(dev, spec);
    spec[SPEC_HAS_EMITTERS] = scene.features.emitters ? 1u : 0u;
    spec[SPEC_SAMPLER] = s.sampler;
    spec[SPEC_FEATURES] = scene.features.bits;
    spec[SPEC_MIS] = s.mis;
    return spec;
}

void checkImageFits(const vk::Context& ctx, const RenderSettings& s) {
    // The sample sums are one device buffer (and one readback buffer).
    const std::uint64_t bytes = std::uint64_t(s.width) * std::uint64_t(s.height) * gpu::kAccumVec4PerPixel * 16;
    const std::uint64_t largest = sceneLimits(ctx, s.limits).allocation;
    if (bytes > largest)
        throw Error("strata: error: a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image needs " +
                    sizeText(bytes) + " for its sample sums, more than the device's maxMemoryAllocationSize (" +
                    sizeText(largest) + "); render a smaller image");
}

RenderResult render(const vk::Context& ctx, const GpuScene& scene, const Camera& camera,
                    const RenderSettings& s, const Checkpoints& checkpoints) {
    checkSamplerSettings(samplerByKind(s.sampler), s.spp, s.width, s.height);
    const DeviceScene dev = uploadScene(ctx, scene, s.traversal, s.bvhWidth, s.bvhStack, s.limits);
    return render(ctx, dev, scene, camera, s, checkpoints);
}

RenderResult render(const vk::Context& ctx, const DeviceScene& dev, const GpuScene& scene, const Camera& camera,
                    const RenderSettings& s, const Checkpoints& checkpoints) {
    using namespace gpu;
    checkSamplerSettings(samplerByKind(s.sampler), s.spp, s.width, s.height);
    const std::size_t pixels = static_cast<std::size_t>(s.width) * s.height;
    const VkDeviceSize accumBytes = pixels * kAccumVec4PerPixel * 16;
    checkImageFits(ctx, s);

    vk::Buffer frame(ctx, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);
    const FrameUniforms fu = frameUniforms(dev, scene, camera, s);
    std::memcpy(frame.mapped(), &fu, sizeof fu);
    constexpr VkBufferUsageFlags xfer = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    vk::Buffer accum(ctx, accumBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | xfer, vk::MemoryUse::Device);
    vk::Buffer readback(ctx, accumBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    vk::Buffer counters(ctx, sizeof(RenderCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | xfer,
                        vk::MemoryUse::Device);
    vk::Buffer countersBack(ctx, sizeof(RenderCounters), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            vk::MemoryUse::Readback);
    vk::Buffer filterTable = vk::uploadVector(ctx, filterInverseCdf(s.filter), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    const std::uint32_t tile = std::max(8u, s.tileSize);
    // The megakernel (pathtrace.comp), or the wavefront integrator's stages.
    std::unique_ptr<vk::Kernel> mega;
    std::unique_ptr<WavefrontIntegrator> wave;
    if (s.integrator == Integrator::Wavefront) {
        const std::uint32_t maxPaths = std::min<std::uint32_t>(tile, s.width) * std::min<std::uint32_t>(tile, s.height);
        wave = std::make_unique<WavefrontIntegrator>(ctx, dev, scene, s, maxPaths, frame, filterTable, accum, counters);
    } else {
        std::vector<std::uint32_t> spec = pathSpec(dev, scene, s);
        spec[SPEC_COUNT_RAYS] = s.countRays ? 1u : 0u;
        spec[SPEC_WORK_QUEUE] = useWorkQueue(ctx, s.workQueue) ? 1u : 0u;
        mega = std::make_unique<vk::Kernel>(ctx, traversalShader(dev, true), pathBindings(), sizeof(DispatchParams),
                                            spec, s.reusePipeline);
        bindPathInputs(*mega, dev, frame, filterTable, accum, counters);
    }

    RenderResult result;
    result.film = Film(s.width, s.height);
    result.reads = dev.reads;
    result.bvhWidth = dev.wide ? 4 : 2;
    result.bvhStack = bvhStackName(dev);
    result.uploadMs = dev.uploadMs;
    result.sceneBytes = dev.packedBytes;
    result.sceneDeviceBytes = dev.deviceBytes;
    result.pipelineMs = mega ? mega->pipelineMs() : wave->pipelineMs();
    result.pipelineReused = mega ? mega->reusedProgram() : wave->reusedProgram();
    vk::OneShot submit(ctx);
    vk::DeviceTimer timer(ctx);
    if (s.warmUp) {  // first-use costs of the pipeline, measured apart; the clear below undoes it
        DispatchParams p{};
        p.tileW = std::min(64u, static_cast<std::uint32_t>(s.width));
        p.tileH = std::min(64u, static_cast<std::uint32_t>(s.height));
        p.blockStride = blockStride(p.tileW, p.tileH);
        const auto w0 = Clock::now();
        double device = 0.0;
        if (wave) {
            device = wave->sample(0, 0, p.tileW, p.tileH, 0);
            wave->resetCounts();  // its rays are not the render's
        } else {
            VkCommandBuffer cmd = submit.begin();
            timer.begin(cmd);
            mega->dispatch(cmd, &p, (p.tileW + 7) / 8, (p.tileH + 7) / 8);
            timer.end(cmd);
            submit.submitAndWait();
            device = timer.seconds();
        }
        result.warmUpHostSeconds = std::chrono::duration<double>(Clock::now() - w0).count();
        result.warmUpDeviceSeconds = timer.supported() ? device : result.warmUpHostSeconds;
        result.warmUpPixels = p.tileW * p.tileH;
    }
    {
        VkCommandBuffer cmd = submit.begin();
        vkCmdFillBuffer(cmd, accum.handle(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, counters.handle(), 0, VK_WHOLE_SIZE, 0);
        submit.submitAndWait();
    }

    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const bool showProgress = s.progress && ::isatty(STDERR_FILENO);
    std::uint32_t batch = s.fixedBatch ? s.fixedBatch : 1u;  // samples in the next submission
    std::size_t nextCheckpoint = 0;

    // The device sums samples in float32 and the host folds the sums into
    // double. Folds happen at fixed sample counts (every maxBatch samples, at
    // checkpoints and at the end), never where a submission happens to end,
    // so the float rounding, and with it every bit of the image, does not
    // depend on timing.
    auto recordFold = [&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, accumBytes};
        vkCmdCopyBuffer(cmd, accum.handle(), readback.handle(), 1, &region);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        vkCmdFillBuffer(cmd, accum.handle(), 0, VK_WHOLE_SIZE, 0);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    };
    auto foldIntoFilm = [&] {
        readback.invalidate();
        result.film.fold(static_cast<const float*>(readback.mapped()));
    };
    const std::uint32_t foldEvery = std::max(1u, s.maxBatch);
    std::uint32_t unfolded = 0;  // samples summed on the device since the last fold
    double waveSeconds = 0.0;    // device time of the wavefront stages in this submission

    while (result.spp < s.spp) {
        while (nextCheckpoint < checkpoints.spp.size() && checkpoints.spp[nextCheckpoint] <= result.spp)
            ++nextCheckpoint;
        std::uint32_t limit = std::min(foldEvery - unfolded, s.spp - result.spp);
        if (nextCheckpoint < checkpoints.spp.size())
            limit = std::min(limit, checkpoints.spp[nextCheckpoint] - result.spp);
        batch = std::clamp(batch, 1u, limit);
        const std::uint32_t after = result.spp + batch;
        const bool atCheckpoint = nextCheckpoint < checkpoints.spp.size() && checkpoints.spp[nextCheckpoint] == after;
        const bool fold = unfolded + batch == foldEvery || after == s.spp || atCheckpoint;

        const auto t0 = Clock::now();
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        for (std::uint32_t k = 0; k < batch; ++k) {
            for (std::uint32_t ty = 0; ty < static_cast<std::uint32_t>(s.height); ty += tile)
                for (std::uint32_t tx = 0; tx < static_cast<std::uint32_t>(s.width); tx += tile) {
                    DispatchParams p{};
                    p.tileX = tx;
                    p.tileY = ty;
                    p.tileW = std::min<std::uint32_t>(tile, s.width - tx);
                    p.tileH = std::min<std::uint32_t>(tile, s.height - ty);
                    p.sampleIndex = result.spp + k;
                    p.blockStride = blockStride(p.tileW, p.tileH);
                    if (wave) {  // submits its stages itself
                        waveSeconds += wave->sample(p.tileX, p.tileY, p.tileW, p.tileH, p.sampleIndex);
                        continue;
                    }
                    mega->dispatch(cmd, &p, (p.tileW + 7) / 8, (p.tileH + 7) / 8);
                    ++result.dispatches;
                }
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                              VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                              VK_PIPELINE_STAGE_TRANSFER_BIT,
                              VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                              VK_ACCESS_TRANSFER_READ_BIT);
        }
        timer.end(cmd);
        if (fold) recordFold(cmd);
        submit.submitAndWait();
        const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
        result.hostSubmitSeconds += secs;
        result.deviceSeconds += timer.supported() ? timer.seconds() + waveSeconds : secs;
        waveSeconds = 0.0;
        result.spp = after;
        unfolded += batch;
        ++result.submissions;
        if (fold) {
            foldIntoFilm();
            unfolded = 0;
        }
        if (atCheckpoint && checkpoints.onReached) {
            result.seconds = elapsed();
            checkpoints.onReached(result);
        }

        const double perSample = secs / batch;
        if (s.timeLimit > 0.0 && elapsed() >= s.timeLimit) break;
        double target = s.submitSeconds;
        if (s.timeLimit > 0.0) target = std::min(target, s.timeLimit - elapsed());
        batch = s.fixedBatch ? s.fixedBatch
                             : static_cast<std::uint32_t>(std::max(1.0, target / std::max(perSample, 1e-6)));
        if (showProgress)
            printProgress(result.spp, s.spp, elapsed(),
                          static_cast<double>(pixels) * result.spp / elapsed() * 1e-6);
    }
    if (unfolded > 0) {  // stopped by --time inside a fold group
        recordFold(submit.begin());
        submit.submitAndWait();
        foldIntoFilm();
    }
    result.seconds = elapsed();
    if (showProgress) std::fprintf(stderr, "\n");

    {
        VkCommandBuffer cmd = submit.begin();
        VkBufferCopy region{0, 0, sizeof(RenderCounters)};
        vkCmdCopyBuffer(cmd, counters.handle(), countersBack.handle(), 1, &region);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        submit.submitAndWait();
        countersBack.invalidate();
        RenderCounters c;
        std::memcpy(&c, countersBack.mapped(), sizeof c);
        result.nonFinite = c.nonFinite + result.film.overflowed;
        result.closestRays = (static_cast<std::uint64_t>(c.closestHi) << 32) | c.closestLo;
        result.shadowRays = (static_cast<std::uint64_t>(c.shadowHi) << 32) | c.shadowLo;
    }
    if (wave) {  // counted on the host, from the lists' lengths
        result.closestRays = s.countRays ? wave->closestRays() : 0;
        result.shadowRays = s.countRays ? wave->shadowRays() : 0;
        result.dispatches = wave->dispatches();
    }
    result.peakDeviceBytes = vk::peakDeviceMemoryBytes();
    return result;
}

}  // namespace strata
