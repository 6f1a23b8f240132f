// Hostile input (docs/security.md): uris confined to relative paths and
// data: URIs, --restrict-paths, and the limits checked before allocating
// (image sizes, JSON nesting); each a one-line error naming the file.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "cli_util.h"
#include "gltf_util.h"
#include "scene/scene.h"
#include "util/error.h"
#include "util/files.h"

namespace strata::test {
namespace {

void writeBytes(const std::string& path, const std::string& bytes) {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

// One triangle whose positions are in the buffer `uri` (36 bytes), and an
// image `imageUri` used as its base colour texture when not empty.
std::string triangleGltf(const std::string& uri, const std::string& imageUri = "") {
    std::string json = R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
                       R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                       R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
                       R"("min":[0,0,0],"max":[1,1,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
                       R"("buffers":[{"byteLength":36,"uri":")" + uri + "\"}]";
    if (!imageUri.empty())
        json += R"(,"images":[{"uri":")" + imageUri + R"("}],"textures":[{"source":0}],)"
                R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}])";
    return json + "}";
}

std::string positions() {
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    return std::string(reinterpret_cast<const char*>(p), sizeof p);
}

std::string loadErrorWith(const std::string& path, const LoadOptions& options) {
    CerrCapture capture;
    try {
        loadGltf(path, options);
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

void checkRefused(const std::string& path, const std::string& phrase, const LoadOptions& options = {}) {
    const std::string message = loadErrorWith(path, options);
    CAPTURE(message);
    REQUIRE_MESSAGE(!message.empty(), "loaded without an error");
    CHECK(isOneLine(message));
    CHECK(message.rfind(path + ": error: ", 0) == 0);
    CHECK(message.find(phrase) != std::string::npos);
}

// A PNG of its signature and IHDR chunk only: the size a header claims.
std::string pngHeader(std::uint32_t width, std::uint32_t height) {
    auto be = [](std::uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    std::string ihdr = "IHDR" + be(width) + be(height) + std::string("\x08\x06\x00\x00\x00", 5);
    return std::string("\x89PNG\r\n\x1a\n", 8) + be(13) + ihdr + be(0) /* CRC, not checked */;
}

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("hostile: a uri must be a relative path or a data: URI") {
    TempDir dir;
    writeBytes(dir / "tri.bin", positions());
    struct Case {
        std::string uri, phrase;
    };
    const Case cases[] = {
        {(dir.path / "tri.bin").string(), "is an absolute path; a glTF uri is a path relative to the scene's folder"},
        {"%2Fetc%2Fpasswd", "uri \"/etc/passwd\" is an absolute path"},
        {"file:///etc/passwd", "has the scheme \"file:\"; strata reads paths relative to the scene's folder and data: URIs only"},
        {"file:tri.bin", "has the scheme \"file:\""},
        {"https://example.com/tri.bin", "has the scheme \"https:\""},
        {"C:/tri.bin", "is an absolute (drive letter) path"},
        {"\\\\\\\\server\\\\tri.bin", "is an absolute path"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.uri);
        const std::string path = dir / "scene.gltf";
        writeBytes(path, triangleGltf(c.uri));
        checkRefused(path, c.phrase);
    }
    // An image uri is held to the same rules.
    writeBytes(dir / "image.gltf", triangleGltf("tri.bin", "/etc/hostname"));
    checkRefused(dir / "image.gltf", "uri \"/etc/hostname\" is an absolute path");
    // Relative paths resolve against the scene's folder, also through "..".
    writeBytes(dir / "sub/up.gltf", triangleGltf("../tri.bin"));
    CerrCapture quiet;
    CHECK(loadGltf(dir / "sub/up.gltf").triangles.size() == 1);
}

TEST_CASE("hostile: --restrict-paths refuses what resolves outside its folder, symlinks followed") {
    TempDir dir;
    writeBytes(dir / "outside/tri.bin", positions());
    writeBytes(dir / "jail/tri.bin", positions());
    writeBytes(dir / "jail/scene.gltf", triangleGltf("tri.bin"));
    writeBytes(dir / "jail/up.gltf", triangleGltf("../outside/tri.bin"));
    writeBytes(dir / "jail/link.gltf", triangleGltf("link.bin"));
    std::filesystem::create_symlink(dir.path / "outside/tri.bin", dir.path / "jail/link.bin");
    writeBytes(dir / "outside/scene.gltf", triangleGltf("tri.bin"));
    std::filesystem::create_symlink(dir.path / "outside/scene.gltf", dir.path / "jail/scene-link.gltf");
    LoadOptions options;
    options.restrictPaths = restrictRoot(dir / "jail");
    {
        CerrCapture quiet;
        CHECK(loadGltf(dir / "jail/scene.gltf", options).triangles.size() == 1);
        CHECK(loadGltf(dir / "jail/up.gltf").triangles.size() == 1);  // allowed without the option
    }
    const std::string outside = std::filesystem::canonical(dir.path / "outside/tri.bin").string();
    checkRefused(dir / "jail/up.gltf",
                 "uri \"../outside/tri.bin\" resolves to " + outside + ", outside --restrict-paths " + options.restrictPaths,
                 options);
    checkRefused(dir / "jail/link.gltf", "uri \"link.bin\" resolves to " + outside, options);
    checkRefused(dir / "jail/scene-link.gltf", "the scene resolves to " + std::filesystem::canonical(dir.path / "outside/scene.gltf").string(),
                 options);
    CHECK_THROWS_WITH_AS(restrictRoot(dir / "none"), ("strata: error: --restrict-paths " + dir / "none" +
                                                      ": not an existing folder").c_str(), Error);
}

TEST_CASE("hostile: the command line's --restrict-paths: exit 2, one line, nothing written") {
    TempDir dir;
    writeBytes(dir / "outside/tri.bin", positions());
    writeBytes(dir / "jail/link.gltf", triangleGltf("link.bin"));
    std::filesystem::create_symlink(dir.path / "outside/tri.bin", dir.path / "jail/link.bin");
    expectError("render " + dir / "jail/link.gltf" + " --restrict-paths " + dir / "jail", dir / "jail/link.gltf" + ": error: uri \"link.bin\" resolves to ");
    expectError("render " + dir / "jail/link.gltf" + " --restrict-paths " + dir / "nowhere",
                "strata: error: --restrict-paths " + dir / "nowhere" + ": not an existing folder");
}

TEST_CASE("hostile: an image whose header claims 60000x60000 is refused before decoding") {
    TempDir dir;
    writeBytes(dir / "tri.bin", positions());
    writeBytes(dir / "huge.png", pngHeader(60000, 60000));
    writeBytes(dir / "wide.png", pngHeader(16385, 1));
    writeBytes(dir / "huge.gltf", triangleGltf("tri.bin", "huge.png"));
    writeBytes(dir / "wide.gltf", triangleGltf("tri.bin", "wide.png"));
    checkRefused(dir / "huge.gltf", "image 0 (\"huge.png\"): 60000x60000 pixels is over the limit of 16384 on a side "
                                    "and 134217728 in all (refused before decoding)");
    checkRefused(dir / "wide.gltf", "16385x1 pixels is over the limit");
}

TEST_CASE("hostile: JSON nested deeper than 128 is refused before parsing") {
    TempDir dir;
    writeBytes(dir / "tri.bin", positions());
    const std::size_t depth = 200000;  // deep enough to overflow a recursive parser's stack
    std::string json = triangleGltf("tri.bin");
    json.insert(json.size() - 1, ",\"extras\":" + std::string(depth, '[') + std::string(depth, ']'));
    writeBytes(dir / "deep.gltf", json);
    checkRefused(dir / "deep.gltf", "invalid glTF: JSON nested deeper than 128 objects and arrays (at byte ");
    // Brackets inside strings are text, not nesting.
    std::string text = triangleGltf("tri.bin");
    text.insert(text.size() - 1, ",\"extras\":{\"s\":\"" + std::string(1000, '[') + "\\\"{\"}");
    writeBytes(dir / "text.gltf", text);
    CerrCapture quiet;
    CHECK(loadGltf(dir / "text.gltf").triangles.size() == 1);
}

TEST_CASE("hostile: flattened triangles beyond the host memory are refused before they are made") {
    // 2 x 10^4 placements of an emitting mesh of 10^5 triangles (emitters
    // are never instanced): 2 x 10^9 triangles.
    const std::string path = dataPath("fuzz/gltf/hostile-flatten-bomb.gltf");
    LoadOptions options;
    options.hostMemory = std::uint64_t(8) << 30;
    checkRefused(path, "the scene's 20001 placed nodes flatten into 2000000000 triangles (2000000000 of them "
                       "emitters), which need about 953.7 GiB of host memory to load and build; 8.0 GiB are available",
                 options);
}

TEST_CASE("hostile: flattened emitters count their light tree's host memory") {
    // 8 x 10^6 emitting triangles: 0.95 GiB at kHostBytesPerTriangle alone,
    // which let them through the fuzz target's 1 GiB until their light tree
    // took its process past 4 GiB; with kHostBytesPerEmitter, 3.8 GiB.
    const std::string path = dataPath("fuzz/gltf/oom-emitters-light-tree.gltf");
    LoadOptions options;
    options.hostMemory = std::uint64_t(1) << 30;
    checkRefused(path, "the scene's 8001 placed nodes flatten into 8000000 triangles (8000000 of them emitters), which "
                       "need about 3.8 GiB of host memory to load and build; 1.0 GiB are available", options);
    CHECK(std::uint64_t(8000000) * kHostBytesPerTriangle < options.hostMemory);
}

TEST_CASE("hostile: flattened emitters beyond the device's memory are refused before they are made") {
    // The same file with the host memory to hold it, on a device of 2 GiB
    // (lavapipe's heap; the render command answers with the device's): its
    // arrays alone need 96 bytes a triangle and 80 an emitter, and the
    // loader asks with that.
    const std::string path = dataPath("fuzz/gltf/hostile-flatten-bomb.gltf");
    LoadOptions options;
    options.hostMemory = std::uint64_t(1) << 40;
    std::uint64_t asked = 0;
    options.deviceMemory = [&](std::uint64_t needed) {
        asked = needed;
        return DeviceBudget{std::uint64_t(2) << 30, "llvmpipe (its largest device-local heap)"};
    };
    checkRefused(path, "the scene's 20001 placed nodes flatten into 2000000000 triangles (2000000000 of them emitters, "
                       "which are always flattened), whose arrays need at least 327.83 GiB of device memory, more than "
                       "the 2.00 GiB of llvmpipe (its largest device-local heap)", options);
    CHECK(asked == std::uint64_t(2000000000) * (kDeviceBytesPerTriangle + kDeviceBytesPerEmitter));
}

TEST_CASE("hostile: instances past the index limit or the host memory are refused before their transforms are read") {
    // Nodes sharing an accessor of 2^20 zero translations (make_hostile.py).
    checkRefused(dataPath("fuzz/gltf/hostile-instance-count.gltf"),
                 "the scene places its instanced meshes 269484032 times, more than the 268435456 instances strata "
                 "can index");
    LoadOptions options;
    options.hostMemory = std::uint64_t(8) << 30;
    checkRefused(dataPath("fuzz/gltf/hostile-instance-bomb.gltf"),
                 "the scene's 209715200 instances need about 50.0 GiB of host memory to load and build; 8.0 GiB are "
                 "available",
                 options);
}

TEST_CASE("hostile: the real binary refuses every hand-written hostile input within 60 s and 4 GiB") {
    // tests/data/make_hostile.py wrote them; under `ulimit -v` (4 GiB of
    // address space) and `timeout 60`, each must be one line, exit 2, and
    // no file written.
    std::size_t count = 0;
    for (const auto& e : std::filesystem::directory_iterator(dataPath("fuzz/gltf"))) {
        const std::string file = e.path().string();
        if (e.path().filename().string().rfind("hostile-", 0) != 0) continue;
        ++count;
        TempDir out;
#if defined(__SANITIZE_ADDRESS__)
        const std::string limit = "";  // AddressSanitizer reserves terabytes of address space
#else
        const std::string limit = "ulimit -v 4194304; ";
#endif
        const Run r = runShell(limit + "timeout 60 " + std::string(STRATA_EXE) + " render " + file + " -o " +
                               out / "a.exr" + " -o " + out / "a.png" + " --spp 1 --width 8 --height 8 --quiet");
        CAPTURE(file);
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(lines(r.output) == 1);
        CHECK(r.output.rfind(file + ": error: ", 0) == 0);
        CHECK(out.empty());
    }
    CHECK(count >= 11);
}

TEST_SUITE_END();

}  // namespace strata::test
