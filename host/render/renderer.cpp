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
#include "util/error.h"
#include "vk/check.h"
#include "vk/kernel.h"
#include "vk/timer.h"
#include <cstdlib>
#include <strata_spirv.h>

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


// EXPERIMENT (branch exp/wavefront): the path tracer as stages, every
// traversal in the trace kernel (with its work queue) over the live rays,
// shading in shaders/wavefront.comp. The shade stage appends the live paths
// and the shadow rays to lists on the device (an atomic per subgroup), a
// resolve stage adds the unoccluded shadow rays' contributions; the host
// reads the two counts after each shade stage to size the next dispatches.
// deviceSeconds counts the dispatches only (not the submissions).
RenderResult renderWavefrontExperiment(const vk::Context& ctx, const DeviceScene& dev, const GpuScene& scene,
                                       const RenderSettings& s, const vk::Buffer& frame,
                                       const vk::Buffer& filterTable) {
    using namespace gpu;
    const std::uint32_t n = static_cast<std::uint32_t>(s.width * s.height);
    constexpr VkBufferUsageFlags st = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    auto devBuf = [&](VkDeviceSize bytes) {
        return vk::Buffer(ctx, std::max<VkDeviceSize>(16, bytes), st, vk::MemoryUse::Device);
    };
    vk::Buffer stateBuf = devBuf(VkDeviceSize(n) * 48), hitBuf = devBuf(VkDeviceSize(n) * 16),
               shadowBuf = devBuf(VkDeviceSize(n) * 32), contribBuf = devBuf(VkDeviceSize(n) * 16),
               shadowSlotBuf = devBuf(VkDeviceSize(n) * 4), shadowHitBuf = devBuf(VkDeviceSize(n) * 16);
    vk::Buffer rays[2] = {devBuf(VkDeviceSize(n) * 32), devBuf(VkDeviceSize(n) * 32)};
    vk::Buffer live[2] = {devBuf(VkDeviceSize(n) * 4), devBuf(VkDeviceSize(n) * 4)};
    vk::Buffer counts(ctx, 16, st, vk::MemoryUse::Readback);
    vk::Buffer stateBack(ctx, VkDeviceSize(n) * 48, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    constexpr std::size_t kRaysPerDispatch = 1u << 18;
    const std::size_t slots = (n + kRaysPerDispatch - 1) / kRaysPerDispatch;
    vk::Buffer workBuf(ctx, std::max<VkDeviceSize>(16, slots * kQueueWords * 4),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                       vk::MemoryUse::Device);
    const bool queue = useWorkQueue(ctx, s.workQueue);

    auto makeTrace = [&](std::uint32_t mode) {
        std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1, 0u);
        setTraversalSpec(dev, spec);
        spec[SPEC_FEATURES] = scene.features.bits;
        spec[SPEC_TRACE_MODE] = mode;
        spec[SPEC_WORK_QUEUE] = queue ? 1u : 0u;
        std::vector<vk::BindingDesc> b = sceneBindings();
        b.insert(b.end(), {{BINDING_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_WORK, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}});
        auto k = std::make_unique<vk::Kernel>(ctx, traversalShader(dev, false), std::move(b), sizeof(TraceParams), spec);
        bindTraversal(*k, dev);
        k->bind(BINDING_WORK, workBuf);
        return k;
    };
    auto closest = makeTrace(kTraceClosest);
    auto anyHit = makeTrace(kTraceAny);
    anyHit->bind(BINDING_RAYS, shadowBuf);
    anyHit->bind(BINDING_HITS, shadowHitBuf);
    closest->bind(BINDING_HITS, hitBuf);
    auto makeStage = [&](std::uint32_t stage) {
        std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1, 0u);
        setTraversalSpec(dev, spec);
        spec[SPEC_HAS_EMITTERS] = scene.features.emitters ? 1u : 0u;
        spec[SPEC_SAMPLER] = s.sampler;
        spec[SPEC_FEATURES] = scene.features.bits;
        spec[SPEC_MIS] = s.mis;
        spec[SPEC_TRACE_MODE] = stage;
        std::vector<vk::BindingDesc> b = sceneBindings();
        b.insert(b.end(), {{BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                           {BINDING_EMITTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_EMITTERS_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                           {BINDING_FILTER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_ENV_TEXELS, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                           {BINDING_ENV_CDF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_ENV_CDF_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER}});
        for (std::uint32_t i = 28; i <= 38; ++i) b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        auto k = std::make_unique<vk::Kernel>(
            ctx, std::span<const std::uint32_t>(kSpirvPtr_wavefront, kSpirvSize_wavefront / 4), std::move(b), 16, spec);
        bindTraversal(*k, dev);
        k->bind(BINDING_FRAME, frame);
        bindArray(*k, BINDING_EMITTERS, BINDING_EMITTERS_TEXEL, dev.emitters);
        k->bind(BINDING_FILTER, filterTable);
        k->bind(BINDING_ENV_TEXELS, dev.envTexelView);
        bindArray(*k, BINDING_ENV_CDF, BINDING_ENV_CDF_TEXEL, dev.envTables);
        k->bind(28, stateBuf);
        k->bind(30, hitBuf);
        k->bind(32, shadowBuf);
        k->bind(33, contribBuf);
        k->bind(36, shadowSlotBuf);
        k->bind(37, counts);
        k->bind(38, shadowHitBuf);
        return k;
    };
    auto camera = makeStage(0), shade = makeStage(1), resolve = makeStage(2);
    // Path lists ping-pong between rays[0]/live[0] and rays[1]/live[1].
    auto bindLists = [&](int cur) {
        closest->bind(BINDING_RAYS, rays[cur]);
        for (vk::Kernel* k : {camera.get(), shade.get(), resolve.get()}) {
            k->bind(29, live[cur]);
            k->bind(34, rays[cur]);
            k->bind(31, rays[1 - cur]);
            k->bind(35, live[1 - cur]);
        }
    };

    vk::OneShot submit(ctx);
    vk::DeviceTimer timer(ctx);
    double device = 0.0;
    double part[5] = {0, 0, 0, 0, 0};  // camera, closest, any, shade, resolve
    const auto barrier = [](VkCommandBuffer cmd) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
                              VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                              VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_HOST_READ_BIT |
                              VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    };
    auto run = [&](int which, auto&& record) {
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        record(cmd);
        timer.end(cmd);
        barrier(cmd);
        submit.submitAndWait();
        device += timer.seconds();
        part[which] += timer.seconds();
    };
    auto trace = [&](vk::Kernel& k, std::uint32_t count, int which) {
        run(which, [&](VkCommandBuffer cmd) {
            if (queue) {
                vkCmdFillBuffer(cmd, workBuf.handle(), 0, VK_WHOLE_SIZE, 0u);
                barrier(cmd);
            }
            for (std::size_t first = 0, slot = 0; first < count; first += kRaysPerDispatch, ++slot) {
                TraceParams p{};
                p.count = static_cast<std::uint32_t>(std::min<std::size_t>(kRaysPerDispatch, count - first));
                p.first = static_cast<std::uint32_t>(first);
                p.slot = static_cast<std::uint32_t>(slot);
                if (!queue) {
                    k.dispatch(cmd, &p, (p.count + 63) / 64);
                    continue;
                }
                const std::uint64_t subgroups = (std::uint64_t{p.count} + kQueueRaysPerSubgroup - 1) / kQueueRaysPerSubgroup;
                const std::uint64_t perGroup = std::max<std::uint32_t>(1, 64 / ctx.info.subgroupSize);
                k.dispatch(cmd, &p, static_cast<std::uint32_t>((subgroups + perGroup - 1) / perGroup));
                barrier(cmd);
                p.pass = 1;
                k.dispatchIndirect(cmd, &p, workBuf, (slot * kQueueWords + 2) * sizeof(std::uint32_t));
            }
        });
    };
    auto stage = [&](vk::Kernel& k, std::uint32_t count, std::uint32_t sampleIndex, int which, bool zeroCounts) {
        run(which, [&](VkCommandBuffer cmd) {
            if (zeroCounts) {
                vkCmdFillBuffer(cmd, counts.handle(), 0, VK_WHOLE_SIZE, 0u);
                barrier(cmd);
            }
            std::uint32_t p[4] = {count, sampleIndex, 0, 0};
            k.dispatch(cmd, p, (count + 63) / 64);
        });
    };

    RenderResult result;
    result.film = Film(s.width, s.height);
    result.reads = dev.reads;
    result.bvhWidth = dev.wide ? 4 : 2;
    result.bvhStack = bvhStackName(dev);
    result.pipelineMs = shade->pipelineMs();
    std::vector<float> sums(std::size_t(n) * kAccumVec4PerPixel * 4);
    const auto* countWords = static_cast<const std::uint32_t*>(counts.mapped());
    const auto start = Clock::now();
    for (std::uint32_t sample = 0; sample < s.spp; ++sample) {
        int cur = 1;  // the camera stage writes its rays and list to rays[0], live[0]
        bindLists(cur);
        stage(*camera, n, sample, 0, false);
        cur = 0;
        std::uint32_t count = n;
        while (count > 0) {
            bindLists(cur);
            trace(*closest, count, 1);
            result.closestRays += count;
            stage(*shade, count, sample, 3, true);
            counts.invalidate();
            const std::uint32_t next = countWords[0], shadows = countWords[1];
            if (shadows > 0) {
                trace(*anyHit, shadows, 2);
                result.shadowRays += shadows;
                stage(*resolve, shadows, sample, 4, false);
            }
            count = next;
            cur = 1 - cur;
        }
        {
            VkCommandBuffer cmd = submit.begin();
            VkBufferCopy region{0, 0, VkDeviceSize(n) * 48};
            vkCmdCopyBuffer(cmd, stateBuf.handle(), stateBack.handle(), 1, &region);
            barrier(cmd);
            submit.submitAndWait();
        }
        stateBack.invalidate();
        const auto* stt = static_cast<const float*>(stateBack.mapped());
        for (std::uint32_t k = 0; k < n; ++k) {
            const glm::vec3 L(stt[12 * k + 4], stt[12 * k + 5], stt[12 * k + 6]);
            float* a = &sums[std::size_t(k) * kAccumVec4PerPixel * 4];
            a[0] = L.x; a[1] = L.y; a[2] = L.z; a[3] = 1.0f;
            a[4] = L.x * L.x; a[5] = L.y * L.y; a[6] = L.z * L.z; a[7] = 0.0f;
        }
        result.film.fold(sums.data());
        ++result.spp;
    }
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    result.deviceSeconds = device;
    std::fprintf(stderr,
                 "wavefront: camera %.3f s, closest %.3f s (%llu rays), any %.3f s (%llu rays), shade %.3f s, "
                 "resolve %.3f s\n",
                 part[0], part[1], (unsigned long long)result.closestRays, part[2],
                 (unsigned long long)result.shadowRays, part[3], part[4]);
    return result;
}

}  // namespace

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
    std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1);
    setTraversalSpec(dev, spec);
    spec[SPEC_HAS_EMITTERS] = scene.features.emitters ? 1u : 0u;
    spec[SPEC_SAMPLER] = s.sampler;
    spec[SPEC_FEATURES] = scene.features.bits;
    spec[SPEC_MIS] = s.mis;
    spec[SPEC_COUNT_RAYS] = s.countRays ? 1u : 0u;
    spec[SPEC_WORK_QUEUE] = useWorkQueue(ctx, s.workQueue) ? 1u : 0u;
    vk::Kernel kernel(ctx, traversalShader(dev, true),
                      std::move(bindings), sizeof(DispatchParams), spec, s.reusePipeline);
    kernel.bind(BINDING_FRAME, frame);
    bindTraversal(kernel, dev);
    bindArray(kernel, BINDING_EMITTERS, BINDING_EMITTERS_TEXEL, dev.emitters);
    kernel.bind(BINDING_ACCUM, accum);
    kernel.bind(BINDING_COUNTERS, counters);
    kernel.bind(BINDING_FILTER, filterTable);
    kernel.bind(BINDING_ENV_TEXELS, dev.envTexelView);
    bindArray(kernel, BINDING_ENV_CDF, BINDING_ENV_CDF_TEXEL, dev.envTables);

    if (std::getenv("STRATA_EXP_WAVEFRONT")) return renderWavefrontExperiment(ctx, dev, scene, s, frame, filterTable);

    RenderResult result;
    result.film = Film(s.width, s.height);
    result.reads = dev.reads;
    result.bvhWidth = dev.wide ? 4 : 2;
    result.bvhStack = bvhStackName(dev);
    result.uploadMs = dev.uploadMs;
    result.sceneBytes = dev.packedBytes;
    result.sceneDeviceBytes = dev.deviceBytes;
    result.pipelineMs = kernel.pipelineMs();
    result.pipelineReused = kernel.reusedProgram();
    vk::OneShot submit(ctx);
    vk::DeviceTimer timer(ctx);
    if (s.warmUp) {  // first-use costs of the pipeline, measured apart; the clear below undoes it
        DispatchParams p{};
        p.tileW = std::min(64u, static_cast<std::uint32_t>(s.width));
        p.tileH = std::min(64u, static_cast<std::uint32_t>(s.height));
        p.blockStride = blockStride(p.tileW, p.tileH);
        const auto w0 = Clock::now();
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        kernel.dispatch(cmd, &p, (p.tileW + 7) / 8, (p.tileH + 7) / 8);
        timer.end(cmd);
        submit.submitAndWait();
        result.warmUpHostSeconds = std::chrono::duration<double>(Clock::now() - w0).count();
        result.warmUpDeviceSeconds = timer.supported() ? timer.seconds() : result.warmUpHostSeconds;
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
    const std::uint32_t tile = std::max(8u, s.tileSize);
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
                    kernel.dispatch(cmd, &p, (p.tileW + 7) / 8, (p.tileH + 7) / 8);
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
        result.deviceSeconds += timer.supported() ? timer.seconds() : secs;
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
    result.peakDeviceBytes = vk::peakDeviceMemoryBytes();
    return result;
}

}  // namespace strata
