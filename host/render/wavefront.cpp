#include "render/wavefront.h"

#include <algorithm>
#include <span>
#include <vector>

#include <strata_spirv.h>

#include "../../shaders/shared/bindings.h"

namespace strata {

namespace {

constexpr VkBufferUsageFlags kListUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
// Rays per trace dispatch (as DeviceTracer): bounds one dispatch's work queue.
constexpr std::uint32_t kRaysPerDispatch = 1u << 18;

void barrier(VkCommandBuffer cmd) {
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT |
                          VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT);
}

}  // namespace

struct WavefrontIntegrator::Impl {
    const vk::Context& ctx;
    bool queue;
    vk::Buffer state, hits, shadowRays, contrib, shadowSlots, shadowHits, work, counts;
    vk::Buffer rays[2], live[2];  // each bounce's list and the next one's, in turn
    std::unique_ptr<vk::Kernel> closest, anyHit, stages[4];  // stages by kStage*
    vk::OneShot submit;
    vk::DeviceTimer timer;

    Impl(const vk::Context& c, bool q) : ctx(c), queue(q), submit(c), timer(c) {}

    // Records `record`, submits it and waits; returns its device time.
    template <class F>
    double run(F&& record) {
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        record(cmd);
        timer.end(cmd);
        barrier(cmd);
        submit.submitAndWait();
        return timer.seconds();
    }
};

WavefrontIntegrator::WavefrontIntegrator(const vk::Context& ctx, const DeviceScene& dev, const GpuScene& scene,
                                         const RenderSettings& s, std::uint32_t maxPaths, const vk::Buffer& frame,
                                         const vk::Buffer& filterTable, const vk::Buffer& accum,
                                         const vk::Buffer& counters)
    : impl_(std::make_unique<Impl>(ctx, useWorkQueue(ctx, s.workQueue))) {
    using namespace gpu;
    Impl& m = *impl_;
    const VkDeviceSize n = std::max<std::uint32_t>(1, maxPaths);
    auto list = [&](VkDeviceSize bytes) { return vk::Buffer(ctx, n * bytes, kListUsage, vk::MemoryUse::Device); };
    m.state = list(sizeof(PathState));
    m.hits = list(sizeof(TraceHit));
    m.shadowRays = list(sizeof(TraceRay));
    m.contrib = list(16);
    m.shadowSlots = list(4);
    m.shadowHits = list(sizeof(TraceHit));
    m.rays[0] = list(sizeof(TraceRay));
    m.rays[1] = list(sizeof(TraceRay));
    m.live[0] = list(4);
    m.live[1] = list(4);
    m.counts = vk::Buffer(ctx, 16, kListUsage, vk::MemoryUse::Readback);
    const VkDeviceSize slots = (n + kRaysPerDispatch - 1) / kRaysPerDispatch;
    m.work = vk::Buffer(ctx, slots * kQueueWords * sizeof(std::uint32_t),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                            VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        vk::MemoryUse::Device);

    auto trace = [&](std::uint32_t mode) {
        std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1, 0u);
        setTraversalSpec(dev, spec);
        spec[SPEC_FEATURES] = scene.features.bits;
        spec[SPEC_TRACE_MODE] = mode;
        spec[SPEC_WORK_QUEUE] = m.queue ? 1u : 0u;
        std::vector<vk::BindingDesc> b = sceneBindings();
        b.insert(b.end(), {{BINDING_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_WORK, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}});
        auto k = std::make_unique<vk::Kernel>(ctx, traversalShader(dev, false), std::move(b), sizeof(TraceParams),
                                              spec, s.reusePipeline);
        bindTraversal(*k, dev);
        k->bind(BINDING_WORK, m.work);
        return k;
    };
    m.closest = trace(kTraceClosest);
    m.closest->bind(BINDING_HITS, m.hits);
    m.anyHit = trace(kTraceAny);
    m.anyHit->bind(BINDING_RAYS, m.shadowRays);
    m.anyHit->bind(BINDING_HITS, m.shadowHits);

    for (std::uint32_t stage = kStageCamera; stage <= kStageAccumulate; ++stage) {
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
                           {BINDING_ENV_CDF_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                           {BINDING_ACCUM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                           {BINDING_COUNTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}});
        for (std::uint32_t i = BINDING_WAVE_STATE; i <= BINDING_WAVE_SHADOW_HITS; ++i)
            b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        auto k = std::make_unique<vk::Kernel>(
            ctx, std::span<const std::uint32_t>(kSpirvPtr_wavefront, kSpirvSize_wavefront / 4), std::move(b),
            sizeof(WaveParams), spec, s.reusePipeline);
        bindTraversal(*k, dev);
        k->bind(BINDING_FRAME, frame);
        bindArray(*k, BINDING_EMITTERS, BINDING_EMITTERS_TEXEL, dev.emitters);
        k->bind(BINDING_FILTER, filterTable);
        k->bind(BINDING_ENV_TEXELS, dev.envTexelView);
        bindArray(*k, BINDING_ENV_CDF, BINDING_ENV_CDF_TEXEL, dev.envTables);
        k->bind(BINDING_ACCUM, accum);
        k->bind(BINDING_COUNTERS, counters);
        k->bind(BINDING_WAVE_STATE, m.state);
        k->bind(BINDING_WAVE_HITS, m.hits);
        k->bind(BINDING_WAVE_SHADOW_RAYS, m.shadowRays);
        k->bind(BINDING_WAVE_CONTRIB, m.contrib);
        k->bind(BINDING_WAVE_SHADOW_SLOTS, m.shadowSlots);
        k->bind(BINDING_WAVE_COUNTS, m.counts);
        k->bind(BINDING_WAVE_SHADOW_HITS, m.shadowHits);
        m.stages[stage] = std::move(k);
    }
}

WavefrontIntegrator::~WavefrontIntegrator() = default;

double WavefrontIntegrator::pipelineMs() const {
    double ms = impl_->closest->pipelineMs() + impl_->anyHit->pipelineMs();
    for (const auto& k : impl_->stages) ms += k->pipelineMs();
    return ms;
}

bool WavefrontIntegrator::reusedProgram() const { return impl_->stages[gpu::kStageShade]->reusedProgram(); }

double WavefrontIntegrator::sample(std::uint32_t x, std::uint32_t y, std::uint32_t w, std::uint32_t h,
                                   std::uint32_t sampleIndex) {
    using namespace gpu;
    Impl& m = *impl_;
    const std::uint32_t n = w * h;
    double seconds = 0.0;
    // The lists of bounce `cur`: rays[cur] and live[cur] are traced and
    // shaded; the shade stage appends to rays[1 - cur] and live[1 - cur].
    auto bindLists = [&](int cur) {
        m.closest->bind(BINDING_RAYS, m.rays[cur]);
        for (auto& k : m.stages) {
            k->bind(BINDING_WAVE_LIVE, m.live[cur]);
            k->bind(BINDING_WAVE_RAYS, m.rays[cur]);
            k->bind(BINDING_WAVE_NEXT_RAYS, m.rays[1 - cur]);
            k->bind(BINDING_WAVE_NEXT_LIVE, m.live[1 - cur]);
        }
    };
    auto stage = [&](VkCommandBuffer cmd, std::uint32_t which, std::uint32_t count) {
        WaveParams p{};
        p.count = count;
        p.sampleIndex = sampleIndex;
        p.tileX = x;
        p.tileY = y;
        p.tileW = w;
        m.stages[which]->dispatch(cmd, &p, (count + 63) / 64);
        ++dispatches_;
    };
    auto trace = [&](VkCommandBuffer cmd, vk::Kernel& k, std::uint32_t count) {
        if (m.queue) {
            vkCmdFillBuffer(cmd, m.work.handle(), 0, VK_WHOLE_SIZE, 0u);
            barrier(cmd);
        }
        for (std::uint32_t first = 0, slot = 0; first < count; first += kRaysPerDispatch, ++slot) {
            TraceParams p{};
            p.count = std::min(kRaysPerDispatch, count - first);
            p.first = first;
            p.slot = slot;
            ++dispatches_;
            if (!m.queue) {
                k.dispatch(cmd, &p, (p.count + 63) / 64);
                continue;
            }
            // As DeviceTracer: a subgroup per kQueueRaysPerSubgroup rays, then
            // the second pass its last subgroup sized.
            const std::uint64_t subgroups = (std::uint64_t{p.count} + kQueueRaysPerSubgroup - 1) / kQueueRaysPerSubgroup;
            const std::uint64_t perGroup = std::max<std::uint32_t>(1, 64 / m.ctx.info.subgroupSize);
            k.dispatch(cmd, &p, static_cast<std::uint32_t>((subgroups + perGroup - 1) / perGroup));
            barrier(cmd);
            p.pass = 1;
            k.dispatchIndirect(cmd, &p, m.work, (slot * kQueueWords + 2) * sizeof(std::uint32_t));
        }
    };

    bindLists(1);  // the camera stage writes the first bounce's lists, rays[0] and live[0]
    seconds += m.run([&](VkCommandBuffer cmd) { stage(cmd, kStageCamera, n); });
    const auto* counts = static_cast<const std::uint32_t*>(m.counts.mapped());
    std::uint32_t count = n;
    for (int cur = 0; count > 0; cur = 1 - cur) {
        bindLists(cur);
        seconds += m.run([&](VkCommandBuffer cmd) {
            trace(cmd, *m.closest, count);
            barrier(cmd);
            vkCmdFillBuffer(cmd, m.counts.handle(), 0, VK_WHOLE_SIZE, 0u);
            barrier(cmd);
            stage(cmd, kStageShade, count);
        });
        closestRays_ += count;
        m.counts.invalidate();
        const std::uint32_t next = counts[0], shadows = counts[1];
        if (shadows > 0) {
            seconds += m.run([&](VkCommandBuffer cmd) {
                trace(cmd, *m.anyHit, shadows);
                barrier(cmd);
                stage(cmd, kStageResolve, shadows);
            });
            shadowRays_ += shadows;
        }
        count = next;
    }
    seconds += m.run([&](VkCommandBuffer cmd) { stage(cmd, kStageAccumulate, n); });
    return seconds;
}

}  // namespace strata
