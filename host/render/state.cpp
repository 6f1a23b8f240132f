#include "render/state.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "render/sampler_kind.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/interrupt.h"

namespace strata {
namespace {

constexpr char kMagic[8] = {'S', 'T', 'R', 'A', 'T', 'A', 's', 't'};

nlohmann::ordered_json vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

const char* misName(std::uint32_t mis) {
    return mis == gpu::kMisBsdf ? "bsdf" : mis == gpu::kMisLight ? "light" : "power";
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// Writes through a Hash64, so the checksum covers every byte before it.
struct Writer {
    std::FILE* f;
    Hash64 hash;
    bool ok = true;
    void bytes(const void* p, std::size_t n) {
        if (n == 0) return;  // an empty array's data() may be null, which fwrite must not get
        hash.add(p, n);
        ok = ok && std::fwrite(p, 1, n, f) == n;
    }
    template <class T>
    void array(const std::vector<T>& v) { bytes(v.data(), v.size() * sizeof(T)); }
};

struct Reader {
    const std::string& path;
    std::FILE* f;
    std::uint64_t size;      // of the file
    std::uint64_t offset = 0;
    Hash64 hash;
    void bytes(void* p, std::size_t n, std::uint64_t expected) {
        if (n == 0) return;  // as Writer::bytes
        if (offset + n > size || std::fread(p, 1, n, f) != n)
            fail(path, "truncated state file: " + std::to_string(size) + " bytes, its header describes " +
                           std::to_string(expected));
        hash.add(p, n);
        offset += n;
    }
    template <class T>
    void array(std::vector<T>& v, std::size_t count, std::uint64_t expected) {
        v.resize(count);
        bytes(v.data(), count * sizeof(T), expected);
    }
};

std::uint32_t getU32(const nlohmann::ordered_json& j, const char* key, const std::string& path) {
    if (!j.contains(key) || !j[key].is_number_unsigned() || j[key].get<std::uint64_t>() > 0xffffffffu)
        fail(path, std::string("corrupted state file: the header's '") + key + "' is missing or not a count");
    return j[key].get<std::uint32_t>();
}

}  // namespace

std::string sceneContentHash(const GpuScene& g, const Camera& camera) {
    Hash64 h;
    h.addVector(g.tris);
    h.addVector(g.shading);
    h.addVector(g.materials);
    h.addVector(g.texcoords);
    h.addVector(g.tangents);
    h.addVector(g.colors);
    h.addVector(g.textureRefs);
    h.addVector(g.texels);
    h.addVector(g.emitters);
    h.addVector(g.envTexels);
    h.addVector(g.envTables);
    h.add(&g.environment, sizeof g.environment);
    h.add(&g.envScale, sizeof g.envScale);
    h.add(&g.envRotation, sizeof g.envRotation);
    h.add(&g.envWidth, sizeof g.envWidth);
    h.add(&g.envHeight, sizeof g.envHeight);
    h.add(&g.features.bits, sizeof g.features.bits);
    h.addVector(g.instances);
    if (!g.lightTree.empty()) h.addVector(g.lightTree);  // scenes without it keep their hash
    h.add(&camera.position, sizeof camera.position);
    h.add(&camera.forward, sizeof camera.forward);
    h.add(&camera.up, sizeof camera.up);
    h.add(&camera.yfov, sizeof camera.yfov);
    h.addVector(camera.motion);
    return h.hex();
}

nlohmann::ordered_json stateSettings(const RenderSettings& s, const Camera& camera, bool lightTree) {
    nlohmann::ordered_json j;
    j["width"] = s.width;
    j["height"] = s.height;
    const SamplerInfo& sampler = samplerByKind(s.sampler);
    j["sampler"] = sampler.name;
    if (!sampler.prefixesAreSamplings) j["spp"] = s.spp;  // sizes the pattern
    j["seed"] = s.seed;
    j["max-depth"] = s.maxDepth;
    j["filter"] = filterName(s.filter.kind);
    j["filter-radius"] = s.filter.radius;
    j["mis"] = misName(s.mis);
    if (lightTree) j["light-candidates"] = s.lightCandidateCount();  // scenes without the tree keep their header
    j["aov"] = s.aov;
    if (s.adaptive()) {  // a state without them renders every pixel to the cap
        j["noise-threshold"] = s.noiseThreshold;
        j["min-spp"] = s.minSpp;
    }
    j["lens-radius"] = s.lensRadius;
    if (s.lensRadius > 0.0f) {
        j["focus-distance"] = s.focusDistance;
        j["aperture-blades"] = s.apertureBlades;
    }
    if (s.shutter) {
        j["shutter"] = {s.shutterOpen, s.shutterClose};
        j["animation"] = s.animation;
    }
    j["camera"] = {{"position", vec3(camera.position)}, {"forward", vec3(camera.forward)},
                   {"up", vec3(camera.up)}, {"yfov", camera.yfov}};
    return j;
}

nlohmann::ordered_json stateImplementation(const std::string& device, const std::string& driver,
                                           const RenderSettings& s) {
    return {{"device", device},
            {"driver", driver},
            {"integrator", s.integrator == IntegratorKind::Wavefront ? "wavefront" : "megakernel"},
            {"bvh", s.bvhWidth}};
}

bool sameImplementation(const StateInfo& a, const StateInfo& b) {
    // A merge of several implementations is the same as none.
    return a.implementation == b.implementation && !a.implementation.contains("others");
}

std::string implementationText(const nlohmann::ordered_json& j) {
    const auto field = [&](const char* key) {  // any JSON a header holds, as text
        const auto it = j.find(key);
        if (it == j.end()) return std::string("?");
        return it->is_string() ? it->get<std::string>() : it->dump();
    };
    return field("device") + " (" + field("driver") + "), " + field("integrator") + ", bvh " + field("bvh");
}

SampleRange shardRange(std::uint32_t spp, std::uint32_t i, std::uint32_t k, std::uint32_t batch) {
    if (k == 0 || i >= k)
        throw Error("strata: error: --shard " + std::to_string(i) + "/" + std::to_string(k) +
                    ": I must be below K (shards count from 0)");
    const std::uint64_t batches = (std::uint64_t(spp) + batch - 1) / batch;
    if (batches < k)
        throw Error("strata: error: --shard " + std::to_string(i) + "/" + std::to_string(k) + ": " +
                    std::to_string(spp) + " spp make " + std::to_string(batches) + " batch(es) of " +
                    std::to_string(batch) + " samples, fewer than " + std::to_string(k) +
                    " shards; shards are whole batches so that merging is exact (raise --spp or lower K)");
    const auto at = [&](std::uint64_t j) {
        return static_cast<std::uint32_t>(std::min<std::uint64_t>(spp, batches * j / k * batch));
    };
    return {at(i), at(i + 1)};
}

void writeState(const std::string& path, const RenderState& st) {
    const Accumulation& a = st.acc;
    const StateInfo& in = st.info;
    nlohmann::ordered_json h;
    h["format"] = "strata state";
    h["scene"] = in.scene;
    h["sceneHash"] = in.sceneHash;
    h["settings"] = in.settings;
    h["implementation"] = in.implementation;
    h["spp"] = in.spp;
    if (in.shards) h["shard"] = {in.shard, in.shards};
    h["batch"] = in.batch;
    h["width"] = a.film.width;
    h["height"] = a.film.height;
    h["aov"] = a.film.aov;
    h["begin"] = a.begin;
    h["folded"] = a.folded;
    h["end"] = a.end;
    h["overflowed"] = a.film.overflowed;
    h["nonFinite"] = a.nonFinite;
    const std::string header = h.dump();

    const std::string tmp = path + ".tmp";
    const TempFileGuard guard(tmp);  // removed by a second SIGINT or SIGTERM
    bool ok = false;
    {
        File f(std::fopen(tmp.c_str(), "wb"));
        if (f) {
            Writer w{f.get()};
            const std::uint32_t version = kStateVersion, length = static_cast<std::uint32_t>(header.size());
            w.bytes(kMagic, sizeof kMagic);
            w.bytes(&version, sizeof version);
            w.bytes(&length, sizeof length);
            w.bytes(header.data(), header.size());
            w.array(a.film.count);
            w.array(a.film.sum);
            w.array(a.film.sumSq);
            w.array(a.film.aovSum);
            w.array(a.pending);
            const std::uint64_t digest = w.hash.digest();
            ok = w.ok && std::fwrite(&digest, 1, sizeof digest, f.get()) == sizeof digest;
            ok = std::fflush(f.get()) == 0 && ok;
        }
    }
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(tmp.c_str());
        fail(path, "cannot write the state file (" + why + ")");
    }
}

RenderState readState(const std::string& path) {
    File f(std::fopen(path.c_str(), "rb"));
    if (!f) fail(path, std::string("cannot read the state file (") + std::strerror(errno) + ")");
    if (std::fseek(f.get(), 0, SEEK_END) != 0) fail(path, "cannot read the state file");
    const long size = std::ftell(f.get());
    std::rewind(f.get());
    if (size < 0) fail(path, "cannot read the state file");
    Reader r{path, f.get(), static_cast<std::uint64_t>(size)};

    char magic[8];
    std::uint32_t version = 0, length = 0;
    if (r.size < sizeof magic + 8) fail(path, "not a strata state file (" + std::to_string(r.size) + " bytes)");
    r.bytes(magic, sizeof magic, 16);
    if (std::memcmp(magic, kMagic, sizeof magic) != 0) fail(path, "not a strata state file");
    r.bytes(&version, sizeof version, 16);
    if (version != kStateVersion)
        fail(path, "state file format version " + std::to_string(version) + "; this strata reads version " +
                       std::to_string(kStateVersion));
    r.bytes(&length, sizeof length, 16);
    if (length > (1u << 24)) fail(path, "corrupted state file: a header of " + std::to_string(length) + " bytes");
    std::string header(length, '\0');
    r.bytes(header.data(), length, 16 + std::uint64_t(length));
    const nlohmann::ordered_json h = nlohmann::ordered_json::parse(header, nullptr, false);
    if (h.is_discarded() || !h.is_object() || !h.contains("format") || h["format"] != "strata state")
        fail(path, "corrupted state file: its header is not readable");

    RenderState st;
    StateInfo& in = st.info;
    const auto text = [&](const char* key) {
        if (!h.contains(key) || !h[key].is_string())
            fail(path, std::string("corrupted state file: the header's '") + key + "' is missing");
        return h[key].get<std::string>();
    };
    in.scene = text("scene");
    in.sceneHash = text("sceneHash");
    if (!h.contains("settings") || !h["settings"].is_object() || !h.contains("implementation") ||
        !h["implementation"].is_object())
        fail(path, "corrupted state file: the header's settings are missing");
    in.settings = h["settings"];
    in.implementation = h["implementation"];
    in.spp = getU32(h, "spp", path);
    in.batch = getU32(h, "batch", path);
    if (h.contains("shard")) {
        const auto& s = h["shard"];
        if (!s.is_array() || s.size() != 2 || !s[0].is_number_unsigned() || !s[1].is_number_unsigned())
            fail(path, "corrupted state file: the header's 'shard' is not [I, K]");
        in.shard = s[0].get<std::uint32_t>();
        in.shards = s[1].get<std::uint32_t>();
        if (in.shards == 0 || in.shard >= in.shards)
            fail(path, "corrupted state file: shard " + std::to_string(in.shard) + "/" + std::to_string(in.shards) +
                           " (I must be below K)");
    }
    Accumulation& a = st.acc;
    const std::uint32_t width = getU32(h, "width", path), height = getU32(h, "height", path);
    if (width == 0 || height == 0 || width > 16384 || height > 16384)
        fail(path, "corrupted state file: an image of " + std::to_string(width) + "x" + std::to_string(height));
    if (!h.contains("aov") || !h["aov"].is_boolean()) fail(path, "corrupted state file: the header's 'aov' is missing");
    a.begin = getU32(h, "begin", path);
    a.folded = getU32(h, "folded", path);
    a.end = getU32(h, "end", path);
    if (in.batch == 0 || a.begin > a.folded || a.folded > a.end || a.end > in.spp || a.begin % in.batch != 0 ||
        a.folded % in.batch != 0 || (a.end > a.folded && a.end - a.folded >= in.batch))
        fail(path, "corrupted state file: samples " + std::to_string(a.begin) + "-" + std::to_string(a.end) +
                       " (folded to " + std::to_string(a.folded) + ") of " + std::to_string(in.spp) +
                       " in batches of " + std::to_string(in.batch));
    if (!h.contains("overflowed") || !h["overflowed"].is_number_unsigned() || !h.contains("nonFinite") ||
        !h["nonFinite"].is_number_unsigned())
        fail(path, "corrupted state file: the header's sample counts are missing");
    a.film = Film(int(width), int(height), h["aov"].get<bool>());
    a.film.overflowed = h["overflowed"].get<std::uint64_t>();
    a.nonFinite = h["nonFinite"].get<std::uint64_t>();

    const std::size_t n = a.film.pixels();
    const bool pending = a.end > a.folded;
    const std::uint64_t expected = 16 + std::uint64_t(length) + n * 8 + n * 6 * sizeof(FixedSum) +
                                   a.film.aovSum.size() * sizeof(FixedSum) +
                                   (pending ? a.film.batchFloats() * sizeof(float) : 0) + 8;
    if (r.size < expected)
        fail(path, "truncated state file: " + std::to_string(r.size) + " bytes, its header describes " +
                       std::to_string(expected));
    if (r.size > expected)
        fail(path, "corrupted state file: " + std::to_string(r.size) + " bytes, its header describes " +
                       std::to_string(expected));
    r.array(a.film.count, n, expected);
    r.array(a.film.sum, n * 3, expected);
    r.array(a.film.sumSq, n * 3, expected);
    if (a.film.aov) r.array(a.film.aovSum, n * Film::kAovSums, expected);
    if (pending) r.array(a.pending, a.film.batchFloats(), expected);
    const std::uint64_t digest = r.hash.digest();
    std::uint64_t stored = 0;
    r.bytes(&stored, sizeof stored, expected);
    if (stored != digest) fail(path, "corrupted state file: its checksum does not match its content");
    return st;
}

std::string stateMismatch(const StateInfo& a, const std::string& aName, const StateInfo& b,
                          const std::string& bName) {
    if (a.sceneHash != b.sceneHash)
        return "not the same scene: " + bName + " has content hash " + b.sceneHash + ", " + aName + " " +
               a.sceneHash + " (" + a.scene + ")";
    if (a.batch != b.batch)
        return "batches of " + std::to_string(b.batch) + " samples in " + bName + ", " + std::to_string(a.batch) +
               " in " + aName;
    const auto shown = [](const nlohmann::ordered_json& s, const std::string& key) {
        return s.contains(key) ? s[key].dump() : std::string("unset");
    };
    for (const auto* side : {&a.settings, &b.settings})
        for (const auto& item : side->items()) {
            const std::string& key = item.key();
            if (!a.settings.contains(key) || !b.settings.contains(key) || a.settings[key] != b.settings[key])
                return "settings differ: " + key + " is " + shown(b.settings, key) + " in " + bName + ", " +
                       shown(a.settings, key) + " in " + aName;
        }
    return "";
}

}  // namespace strata
