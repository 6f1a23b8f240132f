#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include <unistd.h>

#include "../../shaders/shared/bindings.h"
#include "render/adaptive.h"
#include "render/sampler_kind.h"
#include "integrate/integrator.h"
#include "util/error.h"
#include "util/interrupt.h"
#include "vk/check.h"
#include "vk/kernel.h"
#include "vk/timer.h"

namespace strata {
namespace {

using Clock = std::chrono::steady_clock;

// The samples a submission grows towards where the integrator takes many
// in one dispatch (RenderTuning::maxSubmitSeconds bounds its time): from 8
// on, the megakernel's lanes idled little in the measurements
// (docs/experiments/integrators.md, "Samples one after another").
constexpr double kDispatchSamples = 8.0;

// The pixel samples of a render's first submission (firstSubmissionSamples).
constexpr double kFirstSubmissionPixelSamples = 131072.0;

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

// The scene's part of the frame constants (DeviceScene::frame) with the
// camera, the image and the render's spp.
gpu::FrameUniforms frameUniforms(const DeviceScene& dev, const Camera& cam, const RenderSettings& s) {
    gpu::FrameUniforms f = dev.frame;
    const float tanHalf = std::tan(cam.yfov * 0.5f);
    const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
    const glm::vec3 right = glm::normalize(glm::cross(cam.forward, cam.up));
    const glm::vec3 up = glm::cross(right, cam.forward);
    f.camOrigin = glm::vec4(cam.position, 0.0f);
    f.camForward = glm::vec4(cam.forward, 0.0f);
    f.camRight = glm::vec4(right * tanHalf * aspect, 0.0f);
    f.camUp = glm::vec4(up * tanHalf, 0.0f);
    f.image = glm::uvec4(s.width, s.height, s.maxDepth, s.seed);
    f.scene.z = 2.0f * s.filter.radius;  // texture LOD's camera cone: the filter's footprint
    f.counts.w = s.spp;
    f.lens = glm::vec4(s.lensRadius, s.focusDistance, static_cast<float>(s.apertureBlades), 0.0f);
    if (s.cameraEffects()) {
        f.shutter = glm::vec4(float(s.shutterOpen), float(s.shutter ? s.shutterClose : s.shutterOpen),
                              float(cam.motion.size()), 0.0f);
        for (std::size_t k = 0; k < cam.motion.size() && k < gpu::kMaxCameraKeys; ++k) {
            f.cameraKeys[2 * k] = glm::vec4(cam.motion[k].time, cam.motion[k].translation);
            f.cameraKeys[2 * k + 1] = cam.motion[k].rotation;
        }
    }
    return f;
}

void printProgress(std::uint32_t done, std::uint32_t total, double elapsed, double msps) {
    const double eta = done ? elapsed / done * (total - done) : 0.0;
    std::fprintf(stderr, "\rstrata: %u/%u spp  %.1f s  ETA %.1f s  %.2f Msamples/s   ", done, total,
                 elapsed, eta, msps);
    std::fflush(stderr);
}

}  // namespace

std::uint32_t firstSubmissionSamples(std::size_t pixels, std::uint32_t samplesPerDispatch) {
    const double fit = std::floor(kFirstSubmissionPixelSamples / double(std::max<std::size_t>(pixels, 1)));
    return static_cast<std::uint32_t>(
        std::clamp(fit, 1.0, std::max(1.0, std::min(kDispatchSamples, double(samplesPerDispatch)))));
}

void checkImageFits(const vk::Context& ctx, const RenderSettings& s, const SceneLimits& limits) {
    // The sample sums are one device buffer (and one readback buffer).
    const std::uint64_t bytes = sampleSumBytes(s);
    const std::uint64_t largest = sceneLimits(ctx, limits).allocation;
    if (bytes > largest)
        throw Error("strata: error: a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image needs " +
                    sizeText(bytes) + " for its sample sums, more than the device's maxMemoryAllocationSize (" +
                    sizeText(largest) + "); render a smaller image");
}

Film Accumulation::image() const {
    Film f = film;
    if (!pending.empty()) f.fold(pending.data());
    return f;
}

RenderResult render(const vk::Context& ctx, const DeviceScene& dev, const Camera& camera, const RenderSettings& s,
                    const RenderTuning& t, const Checkpoints& checkpoints, const SampleRun& run) {
    using namespace gpu;
    checkSamplerSettings(samplerByKind(s.sampler), s.spp, s.width, s.height);
    const std::size_t pixels = static_cast<std::size_t>(s.width) * s.height;
    const VkDeviceSize accumBytes = sampleSumBytes(s);
    checkImageFits(ctx, s, t.limits);

    vk::Buffer frame(ctx, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);
    const FrameUniforms fu = frameUniforms(dev, camera, s);
    std::memcpy(frame.mapped(), &fu, sizeof fu);
    constexpr VkBufferUsageFlags xfer = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    vk::Buffer accum(ctx, accumBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | xfer, vk::MemoryUse::Device);
    vk::Buffer readback(ctx, accumBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    vk::Buffer counters(ctx, sizeof(RenderCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | xfer,
                        vk::MemoryUse::Device);
    vk::Buffer countersBack(ctx, sizeof(RenderCounters), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            vk::MemoryUse::Readback);
    vk::Buffer filterTable = vk::uploadVector(ctx, filterInverseCdf(s.filter), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    // Adaptive sampling: the blocks still sampled (render/adaptive.h); a
    // 16-byte placeholder otherwise.
    const bool adaptive = s.adaptive();
    ActiveBlocks blocks = adaptive ? ActiveBlocks(s.width, s.height) : ActiveBlocks();
    vk::Buffer activeBlocks(ctx, std::max<VkDeviceSize>(16, blocks.active.size() * sizeof(std::uint32_t)),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload);
    auto writeBlocks = [&] {  // (an empty vector's data() is null: memcpy must not see it)
        if (!blocks.active.empty())
            std::memcpy(activeBlocks.mapped(), blocks.active.data(), blocks.active.size() * sizeof(std::uint32_t));
    };
    writeBlocks();
    const FilmBuffers film{frame, filterTable, accum, counters, activeBlocks};

    const std::uint32_t tile = std::max(8u, t.tileSize);
    const std::uint32_t maxTilePixels =
        std::min<std::uint32_t>(tile, s.width) * std::min<std::uint32_t>(tile, s.height);
    const std::unique_ptr<Integrator> integrator = makeIntegrator(ctx, dev, s, t, maxTilePixels, film);

    RenderResult result;
    result.reads = dev.reads;
    result.bvhWidth = dev.wide ? 4 : 2;
    result.bvhStack = bvhStackName(dev);
    result.uploadMs = dev.uploadMs;
    result.sceneBytes = dev.packedBytes;
    result.sceneDeviceBytes = dev.deviceBytes;
    result.pipelineMs = integrator->pipelineMs();
    result.pipelineReused = integrator->reusedProgram();
    vk::OneShot submit(ctx);
    vk::DeviceTimer timer(ctx);
    if (t.warmUp) {  // first-use costs of the pipeline, measured apart; the clear below undoes it
        DispatchParams p{};
        p.tileW = std::min(64u, static_cast<std::uint32_t>(s.width));
        p.tileH = std::min(64u, static_cast<std::uint32_t>(s.height));
        p.blockStride = blockStride(p.tileW, p.tileH);
        const auto w0 = Clock::now();
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        const double own = integrator->addSample(cmd, p);
        timer.end(cmd);
        submit.submitAndWait();
        integrator->resetCounts();  // its rays and dispatches are not the render's
        result.warmUpHostSeconds = std::chrono::duration<double>(Clock::now() - w0).count();
        result.warmUpDeviceSeconds = timer.supported() ? timer.seconds() + own : result.warmUpHostSeconds;
        result.warmUpPixels = p.tileW * p.tileH;
    }

    // The samples: [begin, end), from `cur` on. Batches are the runs of
    // foldEvery indices from multiples of foldEvery (Accumulation); an
    // adaptive render folds every kAdaptiveStep samples at most, and decides
    // at its folds.
    const std::uint32_t foldEvery = std::max(1u, adaptive ? std::min(t.maxBatch, kAdaptiveStep) : t.maxBatch);
    const std::uint32_t minSpp = s.minSpp ? s.minSpp : kAdaptiveStep;
    const Accumulation* resume = run.resume;
    const std::uint32_t begin = resume ? resume->begin : run.begin;
    const std::uint32_t end = run.end ? run.end : s.spp;
    if (begin % foldEvery != 0 || end < begin || (resume && (resume->end > end || resume->folded % foldEvery != 0)))
        throw Error("strata: error: internal: samples " + std::to_string(begin) + "-" + std::to_string(end) +
                    " do not start at a batch of " + std::to_string(foldEvery));
    std::uint32_t cur = resume ? resume->end : begin;
    std::uint32_t unfolded = resume ? resume->end - resume->folded : 0;  // samples summed on the device since the last fold
    Film sums = resume ? resume->film : Film(s.width, s.height, s.aov);  // the complete batches
    // A resumed adaptive render finds the blocks retired at its last fold
    // again: the decisions there read the same film.
    if (adaptive && resume && resume->folded - begin >= minSpp) {
        retireConverged(sums, s.noiseThreshold, blocks);
        writeBlocks();
    }
    {
        VkCommandBuffer cmd = submit.begin();
        vkCmdFillBuffer(cmd, counters.handle(), 0, VK_WHOLE_SIZE, 0);
        vk::Buffer staging;
        if (unfolded > 0) {  // the resumed state's batch in progress goes back on the device
            if (resume->pending.size() * sizeof(float) != accumBytes)
                throw Error("strata: error: internal: the state's pending sums do not fit the image");
            staging = vk::Buffer(ctx, accumBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::Upload);
            std::memcpy(staging.mapped(), resume->pending.data(), accumBytes);
            VkBufferCopy region{0, 0, accumBytes};
            vkCmdCopyBuffer(cmd, staging.handle(), accum.handle(), 1, &region);
        } else {
            vkCmdFillBuffer(cmd, accum.handle(), 0, VK_WHOLE_SIZE, 0);
        }
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        submit.submitAndWait();
    }

    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const bool showProgress = s.progress && ::isatty(STDERR_FILENO);
    // Samples in the next submission: the first is one sample where the
    // render splits samples or has a time limit, which it must not pass by
    // more than a sample of unknown length.
    std::uint32_t batch = t.fixedBatch ? t.fixedBatch
                          : t.splitSamples || s.timeLimit > 0.0
                              ? 1u
                              : firstSubmissionSamples(pixels, integrator->samplesPerDispatch());
    std::size_t nextCheckpoint = 0;
    // The tiles of a sample, in dispatch order. With t.splitSamples a
    // sample slower than the submission target goes a run of `tileRun`
    // tiles per submission, from `tileNext`: each pixel still takes its
    // samples in order, so the image is the same.
    struct Tile {
        std::uint32_t x, y, w, h;
    };
    std::vector<Tile> tiles;
    for (std::uint32_t ty = 0; ty < static_cast<std::uint32_t>(s.height); ty += tile)
        for (std::uint32_t tx = 0; tx < static_cast<std::uint32_t>(s.width); tx += tile)
            tiles.push_back({tx, ty, std::min<std::uint32_t>(tile, s.width - tx),
                             std::min<std::uint32_t>(tile, s.height - ty)});
    std::size_t tileNext = 0, tileRun = tiles.size();

    // The device sums samples in float32 and the host folds each complete
    // batch into the film. Folds happen at fixed sample indices (multiples
    // of foldEvery), never where a submission happens to end, so the float
    // rounding, and with it every bit of the image, does not depend on
    // timing, on checkpoints, or on where a render was stopped and resumed.
    auto recordCopy = [&](VkCommandBuffer cmd, bool clear) {
        VkBufferCopy region{0, 0, accumBytes};
        vkCmdCopyBuffer(cmd, accum.handle(), readback.handle(), 1, &region);
        if (clear) {
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                              VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
            vkCmdFillBuffer(cmd, accum.handle(), 0, VK_WHOLE_SIZE, 0);
        }
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    };
    auto readBatch = [&]() -> const float* {
        readback.invalidate();
        return static_cast<const float*>(readback.mapped());
    };
    // The batch in progress, left on the device: its sums as they are
    // (`partial`: also when it holds only a split sample's first tiles).
    auto pendingSums = [&](bool partial = false) -> std::vector<float> {
        if (unfolded == 0 && !partial) return {};
        recordCopy(submit.begin(), false);
        submit.submitAndWait();
        const float* f = readBatch();
        return std::vector<float>(f, f + accumBytes / sizeof(float));
    };
    auto readCounters = [&]() -> RenderCounters {
        VkCommandBuffer cmd = submit.begin();
        VkBufferCopy region{0, 0, sizeof(RenderCounters)};
        vkCmdCopyBuffer(cmd, counters.handle(), countersBack.handle(), 1, &region);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        submit.submitAndWait();
        countersBack.invalidate();
        RenderCounters c;
        std::memcpy(&c, countersBack.mapped(), sizeof c);
        return c;
    };
    auto accumulation = [&](std::vector<float> pending) {
        Accumulation a{sums, std::move(pending), begin, cur - unfolded, cur, readCounters().nonFinite};
        if (resume) a.nonFinite += resume->nonFinite;
        return a;
    };
    double ownSeconds = 0.0;     // device time of what the integrator submitted on its own
    double lastCheckpoint = 0.0; // elapsed() at the last onCheckpoint

    while (cur < end && (!adaptive || blocks.activeCount() > 0)) {
        const std::uint32_t spp = cur - begin;  // in the image so far
        while (nextCheckpoint < checkpoints.spp.size() && checkpoints.spp[nextCheckpoint] <= spp) ++nextCheckpoint;
        std::uint32_t limit = std::min(foldEvery - cur % foldEvery, end - cur);
        if (nextCheckpoint < checkpoints.spp.size())
            limit = std::min(limit, checkpoints.spp[nextCheckpoint] - spp);
        batch = std::clamp(batch, 1u, limit);
        const std::uint32_t after = cur + batch;
        const bool atCheckpoint =
            nextCheckpoint < checkpoints.spp.size() && checkpoints.spp[nextCheckpoint] == after - begin;
        const bool fold = after % foldEvery == 0;

        // A split sample: its next run of tiles (batch is 1), the sample
        // complete once the last tile is in.
        const bool split = t.splitSamples && batch == 1 && (tileNext > 0 || tileRun < tiles.size());
        const std::size_t tileEnd = split ? std::min(tiles.size(), tileNext + tileRun) : tiles.size();
        const bool complete = tileEnd == tiles.size();
        const auto t0 = Clock::now();
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        const std::uint32_t perDispatch = integrator->samplesPerDispatch();  // at least 1
        for (std::uint32_t k = 0; k < batch; k += perDispatch) {
            for (std::size_t i = split ? tileNext : 0; i < tileEnd; ++i) {
                DispatchParams p{};
                p.tileX = tiles[i].x;
                p.tileY = tiles[i].y;
                p.tileW = tiles[i].w;
                p.tileH = tiles[i].h;
                p.sampleIndex = cur + k;
                p.sampleCount = std::min(perDispatch, batch - k);
                p.blockStride = blockStride(p.tileW, p.tileH);
                ownSeconds += integrator->addSample(cmd, p);
            }
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                              VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                              VK_PIPELINE_STAGE_TRANSFER_BIT,
                              VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                              VK_ACCESS_TRANSFER_READ_BIT);
        }
        timer.end(cmd);
        if (fold && complete) recordCopy(cmd, true);
        submit.submitAndWait();
        const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
        result.hostSubmitSeconds += secs;
        result.deviceSeconds += timer.supported() ? timer.seconds() + ownSeconds : secs;
        ownSeconds = 0.0;
        // A whole sample's time: this submission's per sample, or per tile
        // times the tiles (split); with t.splitSamples, the tiles that fit
        // the target next time.
        const double perSample = split ? secs / double(tileEnd - tileNext) * double(tiles.size()) : secs / batch;
        if (t.splitSamples) {
            const double perTile = perSample / double(tiles.size());
            tileRun = std::clamp<std::size_t>(std::size_t(t.submitSeconds / std::max(perTile, 1e-9)), 1, tiles.size());
        }
        if (!complete) {  // the sample goes on: the image so far, then its next tiles
            tileNext = tileEnd;
            ++result.submissions;
            if (run.onSubmission) {
                const auto image = [&] {
                    Film f = sums;
                    f.fold(pendingSums(true).data());  // a sample's tiles so far included
                    return f;
                };
                if (!run.onSubmission(cur - begin, image)) break;
            }
            if ((result.interrupted = interruptSignal()) != 0) break;
            continue;
        }
        tileNext = 0;
        cur = after;
        unfolded += batch;
        result.sppRendered += batch;
        result.samplesTaken += std::uint64_t(batch) * (adaptive ? blocks.activePixels(s.width, s.height) : pixels);
        ++result.submissions;
        if (fold) {
            sums.fold(readBatch());
            unfolded = 0;
            if (adaptive && cur - begin >= minSpp) {
                retireConverged(sums, s.noiseThreshold, blocks);
                writeBlocks();
            }
        }
        if (atCheckpoint && checkpoints.onReached) {  // the image so far, the batch in progress included
            result.spp = cur - begin;
            result.seconds = elapsed();
            result.film = sums;
            if (unfolded > 0) result.film.fold(pendingSums().data());
            checkpoints.onReached(result);
        }
        if (run.checkpointSeconds > 0.0 && run.onCheckpoint && cur < end &&
            elapsed() - lastCheckpoint >= run.checkpointSeconds) {
            run.onCheckpoint(accumulation(pendingSums()));
            lastCheckpoint = elapsed();
        }

        if (run.onSubmission) {
            const auto image = [&] {
                Film f = sums;
                if (unfolded > 0) f.fold(pendingSums().data());
                return f;
            };
            if (!run.onSubmission(cur - begin, image)) break;
        }
        if (s.timeLimit > 0.0 && elapsed() >= s.timeLimit) break;
        if ((result.interrupted = interruptSignal()) != 0) break;  // SIGINT or SIGTERM: the samples reached
        double target = t.submitSeconds;
        // The megakernel runs a submission's samples of a tile in one
        // dispatch, and its lanes idle less the more it runs (a lane whose
        // path ends starts its next sample): a render whose samples are
        // long lets a submission grow towards kDispatchSamples of them.
        if (!t.splitSamples && integrator->samplesPerDispatch() > 1)
            target = std::max(target, std::min(t.maxSubmitSeconds, perSample * kDispatchSamples));
        if (s.timeLimit > 0.0) target = std::min(target, s.timeLimit - elapsed());
        batch = t.fixedBatch ? t.fixedBatch
                             : static_cast<std::uint32_t>(std::max(1.0, target / std::max(perSample, 1e-6)));
        if (t.splitSamples && tileRun < tiles.size()) batch = 1;  // a sample is still too long
        if (showProgress)
            printProgress(cur - begin, end - begin, elapsed(), static_cast<double>(result.samplesTaken) / elapsed() * 1e-6);
    }
    // An adaptive render whose every block stopped: its image is the one at
    // each later checkpoint too (no pixel would take another sample).
    if (adaptive && cur < end && blocks.activeCount() == 0 && checkpoints.onReached) {
        result.spp = cur - begin;
        result.seconds = elapsed();
        result.film = sums;
        for (; nextCheckpoint < checkpoints.spp.size(); ++nextCheckpoint)
            if (checkpoints.spp[nextCheckpoint] > cur - begin) checkpoints.onReached(result);
    }
    // The batch in progress (the render ended, or was stopped by --time or a
    // signal, inside one): in the image, and kept apart in the state.
    std::vector<float> pending = pendingSums();
    result.seconds = elapsed();
    result.spp = cur - begin;
    if (showProgress) std::fprintf(stderr, "\n");

    const RenderCounters c = readCounters();
    if (run.keep) result.state = accumulation(pending);
    result.film = std::move(sums);
    if (!pending.empty()) result.film.fold(pending.data());
    result.nonFinite = c.nonFinite + result.film.overflowed + (resume ? resume->nonFinite : 0);
    const RayCounts rays = integrator->rays(c);
    result.closestRays = rays.closest;
    result.shadowRays = rays.shadow;
    result.dispatches = integrator->dispatches();
    result.peakDeviceBytes = vk::peakDeviceMemoryBytes();
    return result;
}

}  // namespace strata
