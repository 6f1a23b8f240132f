#include "spirv/cache.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <unistd.h>

#include "spirv/compile.h"
#include "spirv/sources.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/interrupt.h"

namespace strata::spirv {
namespace {

namespace fs = std::filesystem;

// An entry's file: this header, then `words` 32-bit words.
struct EntryHeader {
    char magic[8];            // kMagic
    std::uint64_t key;        // moduleKey's hash
    std::uint64_t words;
    std::uint64_t checksum;   // Hash64 of the words
};
constexpr char kMagic[8] = {'s', 't', 'r', 'a', 't', 'a', 'S', '1'};
constexpr std::uint32_t kSpirvMagic = 0x07230203u;

struct State {
    std::mutex mutex;
    std::optional<std::string> dir;  // set: --shader-cache given ("" = off)
    bool warnedUnwritable = false;
    std::map<std::string, std::unique_ptr<std::vector<std::uint32_t>>> modules;
    ShaderCacheStats stats;
};

State& state() {
    static State s;
    return s;
}

std::string defaultDir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg == '/')
        return std::string(xdg) + "/strata/shaders";
    if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
        return std::string(home) + "/.cache/strata/shaders";
    return "";
}

std::string dirLocked(State& s) { return s.dir ? *s.dir : defaultDir(); }

std::uint64_t keyHash(const Variant& v) {
    Hash64 h;
    const std::uint64_t sources = sourcesHash();
    h.add(&sources, sizeof sources);
    h.addString(compilerVersion());
    h.addString("vulkan1.1 spv1.3 no-opt no-debug");  // compile.cpp's options
    h.addString(kernelInfo(v.kernel).source);
    for (const std::string& d : variantDefines(v)) h.addString(d);
    return h.digest();
}

std::string hex(std::uint64_t x) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(x));
    return buf;
}

std::uint64_t checksum(const std::vector<std::uint32_t>& words) {
    Hash64 h;
    h.add(words.data(), words.size() * sizeof(std::uint32_t));
    return h.digest();
}

enum class Read { Missing, Ok, Bad };

Read readEntry(const std::string& path, std::uint64_t key, std::vector<std::uint32_t>& words) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return Read::Missing;
    EntryHeader h{};
    if (!f.read(reinterpret_cast<char*>(&h), sizeof h)) return Read::Bad;
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.key != key || h.words == 0 || h.words > (1u << 26))
        return Read::Bad;
    words.resize(h.words);
    if (!f.read(reinterpret_cast<char*>(words.data()), std::streamsize(h.words * sizeof(std::uint32_t))))
        return Read::Bad;
    if (f.peek() != std::ifstream::traits_type::eof()) return Read::Bad;
    if (words[0] != kSpirvMagic || checksum(words) != h.checksum) return Read::Bad;
    return Read::Ok;
}

// Writes the entry under a name no other process uses, then renames it over
// `path`. False when the folder cannot be written.
bool writeEntry(const std::string& path, std::uint64_t key, const std::vector<std::uint32_t>& words) {
    static std::atomic<unsigned> counter{0};
    const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    const TempFileGuard guard(tmp);
    EntryHeader h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.key = key;
    h.words = words.size();
    h.checksum = checksum(words);
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(&h), sizeof h);
        f.write(reinterpret_cast<const char*>(words.data()), std::streamsize(words.size() * sizeof(std::uint32_t)));
        if (!f) {
            std::remove(tmp.c_str());
            return false;
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        return false;
    }
    return true;
}

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void setShaderCache(const std::string& dirOrOff) {
    State& s = state();
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.dir = dirOrOff == "off" ? std::string() : dirOrOff;
}

std::string shaderCacheDir() {
    State& s = state();
    const std::lock_guard<std::mutex> lock(s.mutex);
    return dirLocked(s);
}

std::string moduleKey(const Variant& v) { return hex(keyHash(v)); }

std::vector<std::uint32_t> cachedModule(const Variant& v, const std::string& dir, ShaderCacheStats& stats,
                                        bool* unwritable) {
    const std::uint64_t key = keyHash(v);
    const std::string path = dir.empty() ? std::string() : dir + "/" + variantName(v) + "-" + hex(key) + ".spv";
    std::vector<std::uint32_t> words;
    if (!path.empty()) {
        const auto t0 = std::chrono::steady_clock::now();
        const Read r = readEntry(path, key, words);
        if (r == Read::Ok) {
            ++stats.loaded;
            stats.loadMs += msSince(t0);
            return words;
        }
        if (r == Read::Bad) {
            ++stats.rejected;
            warn(path, "shader cache entry is corrupt or of another build; compiling it again");
        }
    }
    const auto t0 = std::chrono::steady_clock::now();
    words = compileGlsl(kernelInfo(v.kernel).source, variantDefines(v));
    ++stats.compiled;
    stats.compileMs += msSince(t0);
    if (!path.empty()) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        const bool ok = !ec && writeEntry(path, key, words);
        if (unwritable != nullptr) *unwritable = !ok;
        else if (!ok) warn(dir, "cannot write the shader cache; compiling the shaders in memory");
    }
    return words;
}

std::span<const std::uint32_t> moduleFor(const Variant& v) {
    State& s = state();
    const std::string name = variantName(v);
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (auto it = s.modules.find(name); it != s.modules.end()) return *it->second;
    bool unwritable = false;
    auto words = std::make_unique<std::vector<std::uint32_t>>(cachedModule(v, dirLocked(s), s.stats, &unwritable));
    if (unwritable && !s.warnedUnwritable) {
        s.warnedUnwritable = true;
        warn(dirLocked(s), "cannot write the shader cache; compiling the shaders in memory");
    }
    return *s.modules.emplace(name, std::move(words)).first->second;
}

ShaderCacheStats shaderCacheStats() {
    State& s = state();
    const std::lock_guard<std::mutex> lock(s.mutex);
    return s.stats;
}

}  // namespace strata::spirv
