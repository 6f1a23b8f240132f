#include "integrate/wavefront.h"

#include <algorithm>
#include <span>
#include <vector>


#include "../../shaders/shared/bindings.h"
#include "integrate/kernels.h"
#include "vk/buffer.h"
#include "vk/kernel.h"
#include "vk/timer.h"

namespace strata {

namespace {

constexpr VkBufferUsageFlags kListUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

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
    vk::Buffer state, hits, hitInstances, shadowRays, contrib, shadowSlots, shadowHits, work, counts, cones, treeVertex;
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

WavefrontIntegrator::WavefrontIntegrator(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                                         const RenderTuning& t, std::uint32_t maxPaths, const FilmBuffers& film)
    : impl_(std::make_unique<Impl>(ctx, useWorkQueue(ctx, t.workQueue))), countRays_(t.countRays), adaptive_(s.adaptive()) {
    using namespace gpu;
    Impl& m = *impl_;
    const VkDeviceSize n = std::max<std::uint32_t>(1, maxPaths);
    auto list = [&](VkDeviceSize bytes) { return vk::Buffer(ctx, n * bytes, kListUsage, vk::MemoryUse::Device); };
    m.state = list(sizeof(PathState));
    m.hits = list(sizeof(TraceHit));
    m.hitInstances = list(4);  // read only with the inst axis (STRATA_INSTANCING)
    m.shadowRays = list(sizeof(TraceRay));
    m.contrib = list(16);
    m.shadowSlots = list(4);
    m.shadowHits = list(sizeof(TraceHit));
    m.rays[0] = list(sizeof(TraceRay));
    m.rays[1] = list(sizeof(TraceRay));
    m.live[0] = list(4);
    m.live[1] = list(4);
    // A list that only the shader variants of one feature read: a 16-byte
    // placeholder binding where the scene lacks it.
    auto featureList = [&](std::uint32_t feature, VkDeviceSize bytes) {
        return (dev.features.bits & feature) != 0u ? list(bytes)
                                                   : vk::Buffer(ctx, 16, kListUsage, vk::MemoryUse::Device);
    };
    m.cones = featureList(kFeatureTextureLod, 8);         // the paths' ray cones (STRATA_TEXTURE_LOD)
    m.treeVertex = featureList(kFeatureLightTree, 32);    // their last points and normals (STRATA_LIGHT_TREE)
    m.counts = vk::Buffer(ctx, 16, kListUsage, vk::MemoryUse::Readback);
    m.work = vk::Buffer(ctx, traceWorkBytes(n),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                            VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        vk::MemoryUse::Device);

    auto trace = [&](std::uint32_t mode) {
        auto k = makeTraceKernel(ctx, dev, mode, m.queue, t.reusePipeline);
        k->bind(BINDING_WORK, m.work);
        return k;
    };
    m.closest = trace(kTraceClosest);
    m.closest->bind(BINDING_HITS, m.hits);
    m.closest->bind(BINDING_HIT_INSTANCES, m.hitInstances);
    m.anyHit = trace(kTraceAny);
    m.anyHit->bind(BINDING_RAYS, m.shadowRays);
    m.anyHit->bind(BINDING_HITS, m.shadowHits);
    m.anyHit->bind(BINDING_HIT_INSTANCES, m.hitInstances);  // not written by any-hit

    for (std::uint32_t stage = kStageCamera; stage <= kStageAccumulate; ++stage) {
        std::vector<std::uint32_t> spec = pathSpec(dev, s);  // SPEC_ADAPTIVE included
        spec.resize(std::max<std::size_t>(spec.size(), SPEC_WAVE_STAGE + 1), 0u);
        spec[SPEC_WAVE_STAGE] = stage;
        std::vector<vk::BindingDesc> b = pathBindings();
        for (std::uint32_t i = BINDING_WAVE_STATE; i <= BINDING_WAVE_SHADOW_HITS; ++i)
            b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        b.push_back({BINDING_HIT_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        b.push_back({BINDING_WAVE_CONES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        b.push_back({BINDING_WAVE_TREE_VERTEX, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        auto k = std::make_unique<vk::Kernel>(
            ctx, wavefrontShader(dev), std::move(b),
            sizeof(WaveParams), spec, t.reusePipeline);
        bindPathInputs(*k, dev, film);
        k->bind(BINDING_WAVE_STATE, m.state);
        k->bind(BINDING_WAVE_HITS, m.hits);
        k->bind(BINDING_WAVE_SHADOW_RAYS, m.shadowRays);
        k->bind(BINDING_WAVE_CONTRIB, m.contrib);
        k->bind(BINDING_WAVE_SHADOW_SLOTS, m.shadowSlots);
        k->bind(BINDING_WAVE_COUNTS, m.counts);
        k->bind(BINDING_WAVE_SHADOW_HITS, m.shadowHits);
        k->bind(BINDING_HIT_INSTANCES, m.hitInstances);
        k->bind(BINDING_WAVE_CONES, m.cones);
        k->bind(BINDING_WAVE_TREE_VERTEX, m.treeVertex);
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

RayCounts WavefrontIntegrator::rays(const gpu::RenderCounters&) const {
    return countRays_ ? RayCounts{closestRays_, shadowRays_} : RayCounts{};
}

double WavefrontIntegrator::addSample(VkCommandBuffer, const gpu::DispatchParams& tile) {
    using namespace gpu;
    Impl& m = *impl_;
    const std::uint32_t x = tile.tileX, y = tile.tileY, w = tile.tileW, h = tile.tileH;
    const std::uint32_t sampleIndex = tile.sampleIndex;
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
        dispatches_ += recordTrace(cmd, m.ctx, k, m.work, count, m.queue);
    };

    bindLists(1);  // the camera stage writes the first bounce's lists, rays[0] and live[0]
    seconds += m.run([&](VkCommandBuffer cmd) {
        if (adaptive_) {  // the paths of the blocks still sampled are appended
            vkCmdFillBuffer(cmd, m.counts.handle(), 0, VK_WHOLE_SIZE, 0u);
            barrier(cmd);
        }
        stage(cmd, kStageCamera, n);
    });
    const auto* counts = static_cast<const std::uint32_t*>(m.counts.mapped());
    if (adaptive_) m.counts.invalidate();
    std::uint32_t count = adaptive_ ? counts[0] : n;
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
