#include "render/merge.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "image/image_io.h"
#include "render/command.h"
#include "render/state.h"
#include "util/error.h"
#include "util/files.h"

namespace strata {
namespace {

std::string rangeText(std::uint32_t begin, std::uint32_t end) {
    return "samples " + std::to_string(begin) + "-" + std::to_string(end);
}

// The shards of `spp` that hold none of [begin, end) ("shard 2/4"), where the
// states are shards of K.
std::string missingShards(const StateInfo& in, std::uint32_t begin, std::uint32_t end) {
    if (!in.shards) return "";
    std::string out;
    for (std::uint32_t i = 0; i < in.shards; ++i) {
        const SampleRange r = shardRange(in.spp, i, in.shards, in.batch);
        if (r.begin >= begin && r.end <= end)
            out += (out.empty() ? "" : ", ") + std::to_string(i) + "/" + std::to_string(in.shards);
    }
    return out.empty() ? "" : " (shard " + out + ")";
}

// The implementations an earlier merge of several recorded beside its first.
std::vector<std::string> otherImplementations(const StateInfo& in) {
    std::vector<std::string> out;
    const auto it = in.implementation.find("others");
    if (it != in.implementation.end() && it->is_array())
        for (const auto& o : *it)
            if (o.is_string()) out.push_back(o.get<std::string>());
    return out;
}

}  // namespace

int runMerge(const MergeCommand& cmd) {
    for (const auto& out : cmd.outputs) requireImageSupport(out);  // reject bad input before any work
    for (const auto& out : cmd.outputs) checkOutputPath(out);
    for (const auto& out : cmd.states) checkOutputPath(out);
    if (cmd.dryRun) {
        std::printf("strata: dry run: would merge %zu state(s) into %zu image(s) and %zu state(s)\n",
                    cmd.inputs.size(), cmd.outputs.size(), cmd.states.size());
        return 0;
    }
    const auto t0 = std::chrono::steady_clock::now();

    // Each state is read, checked against the first and added in turn, so
    // only two are held at once; the sum does not depend on the order.
    struct Part {
        std::string path;
        std::uint32_t begin, folded, end;
    };
    std::vector<Part> parts;
    RenderState merged;
    std::vector<float> pending;  // the last range's batch in progress
    std::uint32_t pendingFrom = 0;
    std::vector<std::string> others;  // implementations other than the first's
    for (const std::string& path : cmd.inputs) {
        RenderState st = readState(path);
        if (parts.empty()) {
            merged.info = st.info;
            others = otherImplementations(st.info);  // an earlier merge of several
            merged.acc.film = std::move(st.acc.film);
            merged.acc.nonFinite = st.acc.nonFinite;
        } else {
            const std::string mismatch = stateMismatch(merged.info, cmd.inputs[0], st.info, path);
            if (!mismatch.empty()) fail(path, "cannot merge: " + mismatch);
            if (st.info.spp != merged.info.spp)
                fail(path, "cannot merge: a render of " + std::to_string(st.info.spp) + " spp, " + cmd.inputs[0] +
                               " of " + std::to_string(merged.info.spp));
            if (!sameImplementation(st.info, merged.info)) {
                std::vector<std::string> texts = otherImplementations(st.info);
                texts.push_back(implementationText(st.info.implementation));
                const std::string first = implementationText(merged.info.implementation);
                for (const std::string& text : texts)
                    if (text != first && std::find(others.begin(), others.end(), text) == others.end())
                        others.push_back(text);
            }
            merged.acc.film.add(st.acc.film);
            merged.acc.nonFinite += st.acc.nonFinite;
        }
        if (!st.acc.pending.empty()) {
            pending = std::move(st.acc.pending);
            pendingFrom = st.acc.folded;
        }
        for (const Part& p : parts)
            if (st.acc.begin < p.end && p.begin < st.acc.end)
                fail(path, "cannot merge: its " + rangeText(st.acc.begin, st.acc.end) + " overlap " + p.path + "'s " +
                               rangeText(p.begin, p.end));
        parts.push_back({path, st.acc.begin, st.acc.folded, st.acc.end});
    }
    if (parts.empty()) throw Error("strata: error: merge needs at least one .state file");

    std::sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.begin < b.begin; });
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
        const Part& p = parts[i];
        if (p.end != parts[i + 1].begin)
            fail(parts[i + 1].path, "cannot merge: " + rangeText(p.end, parts[i + 1].begin) + " of " +
                                        std::to_string(merged.info.spp) + " are in no state" +
                                        missingShards(merged.info, p.end, parts[i + 1].begin));
        if (p.folded != p.end)  // a batch cut in two: its float sums are not a shard's
            fail(p.path, "cannot merge: its " + rangeText(p.begin, p.end) + " end inside a batch of " +
                             std::to_string(merged.info.batch) + " samples, and " + parts[i + 1].path +
                             " goes on from there; resume it to the end of its shard first");
    }
    const std::uint32_t begin = parts.front().begin, end = parts.back().end;
    if (!pending.empty() && pendingFrom != parts.back().folded)
        fail(parts.back().path, "cannot merge: internal: the batch in progress is not the last range's");
    const bool whole = begin == 0 && end == merged.info.spp;
    if (!cmd.outputs.empty() && !whole) {
        const std::string& named = begin != 0 ? parts.front().path : parts.back().path;
        const std::uint32_t from = begin != 0 ? 0 : end, to = begin != 0 ? begin : merged.info.spp;
        fail(named, "cannot merge into an image: " + rangeText(from, to) + " of " + std::to_string(merged.info.spp) +
                        " are in no state" + missingShards(merged.info, from, to) +
                        " (a merge into a .state alone may cover part of the render)");
    }
    merged.acc.begin = begin;
    merged.acc.folded = parts.back().folded;
    merged.acc.end = end;
    merged.acc.pending = std::move(pending);
    if (whole) merged.info.shard = merged.info.shards = 0;  // the whole render
    if (!others.empty()) merged.info.implementation["others"] = others;
    const double readMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    for (const std::string& path : cmd.states) writeState(path, merged);
    try {
        if (!cmd.outputs.empty())
            writeFilmImages(cmd.outputs, merged.acc.image(), cmd.variance,
                            {{"strata:spp", int(end - begin)}, {"strata:sppRequested", int(merged.info.spp)}});
    } catch (...) {
        for (const std::string& path : cmd.states) std::remove(path.c_str());
        throw;
    }
    if (!cmd.quiet) {
        if (!others.empty())
            std::fprintf(stderr,
                         "strata: note: the states come from %zu implementations (%s, and %s): the image is "
                         "statistically equivalent to a single render, not the same bits\n",
                         others.size() + 1, implementationText(merged.info.implementation).c_str(),
                         others.front().c_str());
        const double allMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::fprintf(stderr, "strata: merged %zu state(s), %s of %u, in %.0f ms (reading and summing %.0f ms)\n",
                     parts.size(), rangeText(begin, end).c_str(), merged.info.spp, allMs, readMs);
        for (const auto& out : cmd.states) std::fprintf(stderr, "strata: wrote %s\n", out.c_str());
        for (const auto& out : cmd.outputs) std::fprintf(stderr, "strata: wrote %s\n", out.c_str());
    }
    return 0;
}

}  // namespace strata
