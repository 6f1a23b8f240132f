// KHR_draco_mesh_compression and EXT_meshopt_compression through the real
// decoders, on files that tests/data/make_compressed.cpp encodes with the
// real encoders at build time (STRATA_COMPRESSED_DIR): the decoded scene
// against its uncompressed twin, the filters against their precision,
// compressed data preferred to different fallback data, and every broken
// file one error line. In a build without a decoder (STRATA_DRACO=0 or
// STRATA_MESHOPT=0) the same files check the fallback and the error.
#include <doctest/doctest.h>

#ifdef STRATA_COMPRESSED_DIR

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "scene/gltf_internal.h"
#include "scene/scene.h"
#include "test_util.h"
#include "util/error.h"

using namespace strata;

namespace {

const LoadOptions kNoRequirements{false, false};

std::string compressedPath(const std::string& name) { return std::string(STRATA_COMPRESSED_DIR) + "/" + name; }

Scene load(const std::string& name) { return loadGltf(compressedPath(name), kNoRequirements); }

// The one-line message of loading `name`, or "" when it loads.
std::string loadError(const std::string& name) {
    try {
        load(name);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every mesh's primitives of a file as the loader decodes them (the meshopt
// views decoded first, as loadGltf does).
std::vector<std::vector<gltf::LocalPrimitive>> decodeMeshes(const std::string& name) {
    const std::string path = compressedPath(name);
    tinygltf::Model model = gltf::parseModel(path);
    gltf::checkExtensions(path, model);
    gltf::decodeMeshoptViews(path, model);
    std::vector<std::vector<gltf::LocalPrimitive>> out;
    for (std::size_t m = 0; m < model.meshes.size(); ++m)
        out.push_back(gltf::decodeMesh(path, model, static_cast<int>(m)).primitives);
    return out;
}

// The local primitives of two files (positions, normals, TEXCOORD_0/1,
// TANGENT, indices, material) equal bit for bit; the scenes' triangles
// (world space) and texture coordinates too.
void checkSameScene(const std::string& nameA, const std::string& nameB) {
    const auto pa = decodeMeshes(nameA), pb = decodeMeshes(nameB);
    REQUIRE(pa.size() == pb.size());
    std::size_t withTangents = 0;
    for (std::size_t m = 0; m < pa.size(); ++m) {
        REQUIRE(pa[m].size() == pb[m].size());
        for (std::size_t p = 0; p < pa[m].size(); ++p) {
            CAPTURE(m);
            const gltf::LocalPrimitive &x = pa[m][p], &y = pb[m][p];
            CHECK(sameBits(x.positions, y.positions));
            CHECK(sameBits(x.normals, y.normals));
            CHECK(sameBits(x.texcoord(0), y.texcoord(0)));
            CHECK(sameBits(x.texcoord(1), y.texcoord(1)));
            CHECK(sameBits(x.tangents, y.tangents));
            CHECK(x.indices == y.indices);
            CHECK(x.material == y.material);
            withTangents += !x.tangents.empty() && !x.texcoord(1).empty();
        }
    }
    CHECK(withTangents == 2);  // the boxes
    const Scene a = load(nameA), b = load(nameB);
    REQUIRE(a.triangles.size() == b.triangles.size());
    std::size_t differing = 0;
    for (std::size_t t = 0; t < a.triangles.size(); ++t) {
        const Triangle &x = a.triangles[t], &y = b.triangles[t];
        differing += std::memcmp(x.v, y.v, sizeof x.v) != 0 || std::memcmp(x.n, y.n, sizeof x.n) != 0 ||
                     x.material != y.material;
    }
    CHECK(differing == 0);
    CHECK(sameBits(a.texcoords, b.texcoords));
    CHECK(!a.texcoords.empty());
}

#if STRATA_DRACO
// A triangle as 27 floats (vertices, normals, first texture coordinates)
// starting at its smallest vertex, the winding kept: the same for any
// rotation of its corners.
std::array<float, 27> canonical(const Scene& s, std::size_t t) {
    const Triangle& tri = s.triangles[t];
    auto key = [&](int k) { return std::array<float, 3>{tri.v[k].x, tri.v[k].y, tri.v[k].z}; };
    int first = 0;
    for (int k = 1; k < 3; ++k) first = key(k) < key(first) ? k : first;
    std::array<float, 27> out{};
    for (int i = 0; i < 3; ++i) {
        const int k = (first + i) % 3;
        const glm::vec4 uv = s.texcoords[t][static_cast<std::size_t>(k)];
        const float values[9] = {tri.v[k].x, tri.v[k].y, tri.v[k].z, tri.n[k].x, tri.n[k].y, tri.n[k].z,
                                 uv.x, uv.y, static_cast<float>(tri.material)};
        std::copy(values, values + 9, out.begin() + 9 * i);
    }
    return out;
}

std::vector<std::array<float, 27>> triangleSet(const Scene& s) {
    std::vector<std::array<float, 27>> out;
    for (std::size_t t = 0; t < s.triangles.size(); ++t) out.push_back(canonical(s, t));
    std::sort(out.begin(), out.end());
    return out;
}
#endif

// The lines of broken/expected.txt: file name, then a part of its error.
std::vector<std::pair<std::string, std::string>> brokenFiles() {
    std::ifstream in(compressedPath("broken/expected.txt"));
    std::vector<std::pair<std::string, std::string>> out;
    for (std::string line; std::getline(in, line);) {
        const auto tab = line.find('\t');
        if (tab != std::string::npos) out.emplace_back(line.substr(0, tab), line.substr(tab + 1));
    }
    return out;
}

#if STRATA_MESHOPT
// The bytes of the bufferView named `name` after decodeMeshoptViews.
const unsigned char* viewBytes(const tinygltf::Model& model, const std::string& name, std::size_t& size) {
    for (const auto& view : model.bufferViews) {
        if (view.name != name) continue;
        size = view.byteLength;
        return model.buffers[static_cast<std::size_t>(view.buffer)].data.data() + view.byteOffset;
    }
    FAIL("no bufferView named " << name);
    return nullptr;
}

std::vector<float> floatsOf(const tinygltf::Model& model, const std::string& name) {
    std::size_t size = 0;
    const unsigned char* p = viewBytes(model, name, size);
    std::vector<float> out(size / 4);
    std::memcpy(out.data(), p, size);
    return out;
}

// The signed normalized integers of a view (8 or 16 bits) as floats c / max.
std::vector<float> snormsOf(const tinygltf::Model& model, const std::string& name, int bits) {
    std::size_t size = 0;
    const unsigned char* p = viewBytes(model, name, size);
    std::vector<float> out;
    for (std::size_t i = 0; i < size; i += static_cast<std::size_t>(bits / 8)) {
        if (bits == 8) {
            out.push_back(static_cast<float>(static_cast<std::int8_t>(p[i])) / 127.0f);
        } else {
            std::int16_t v;
            std::memcpy(&v, p + i, 2);
            out.push_back(static_cast<float>(v) / 32767.0f);
        }
    }
    return out;
}

// The largest distance between the xyz (or xyzw, `n` = 4) of each element.
double largestError(const std::vector<float>& a, const std::vector<float>& b, int n, bool eitherSign = false) {
    REQUIRE(a.size() == b.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); i += 4) {
        double plus = 0.0, minus = 0.0;
        for (int c = 0; c < n; ++c) {
            const double x = a[i + static_cast<std::size_t>(c)], y = b[i + static_cast<std::size_t>(c)];
            plus += (x - y) * (x - y);
            minus += (x + y) * (x + y);
        }
        worst = std::max(worst, std::sqrt(eitherSign ? std::min(plus, minus) : plus));
    }
    return worst;
}
#endif

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("compressed gltf: Draco, a lossless sequential stream decodes to the uncompressed scene bit for bit") {
    REQUIRE(load("cornell.glb").triangles.size() == 36);
#if STRATA_DRACO
    checkSameScene("cornell-draco.glb", "cornell.glb");
#else
    const std::string e = loadError("cornell-draco.glb");
    CHECK(e == compressedPath("cornell-draco.glb") +
                   ": error: required extension KHR_draco_mesh_compression cannot be read: strata was "
                   "built without the Draco decoder (libdraco)");
#endif
}

#if STRATA_DRACO
TEST_CASE("compressed gltf: Draco, an edgebreaker stream decodes to the uncompressed scene's set of triangles") {
    const Scene twin = load("cornell.glb");
    const Scene edgebreaker = load("cornell-draco-edgebreaker.glb");
    CHECK(triangleSet(edgebreaker) == triangleSet(twin));
}

// Draco quantizes a primitive's positions on a grid of step range / (2^14 - 1),
// range being the bounding box's longest side (2 for the walls, the longest
// here): every coordinate is within half a step, plus float rounding.
TEST_CASE("compressed gltf: Draco, 14-bit quantized positions are within half a quantization step of the source") {
    const Scene twin = load("cornell.glb");
    const Scene quantized = load("cornell-draco-quantized.glb");
    REQUIRE(quantized.triangles.size() == twin.triangles.size());
    const double bound = 2.0 / ((1 << 14) - 1) / 2.0 + 1e-6;
    double worst = 0.0;
    for (std::size_t t = 0; t < twin.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(double(quantized.triangles[t].v[k][c]) - twin.triangles[t].v[k][c]));
            }
        }
    }
    CHECK(worst <= bound);
    CHECK(worst > 0.0);  // it was quantized
}
#endif

TEST_CASE("compressed gltf: Draco, the compressed stream is read, not the accessors' different fallback data") {
#if STRATA_DRACO
    checkSameScene("cornell-draco-fallback.glb", "cornell.glb");
#else
    checkSameScene("cornell-draco-fallback.glb", "cornell-shifted.glb");
#endif
}

#if STRATA_DRACO
TEST_CASE("compressed gltf: Draco, attributes outside the stream are read from their accessors") {
    // POSITION and NORMAL in the stream; TEXCOORD_0/1 and TANGENT plain.
    checkSameScene("cornell-draco-mixed.glb", "cornell.glb");
}

TEST_CASE("compressed gltf: Draco with TRIANGLE_STRIP, the decoded index sequence is converted as a strip") {
    // Mesh 0 the plain strip of vertices (0,1) (0,0) (1,1) (1,0) (2,1) (2,0),
    // indices 0-5; mesh 1 the same in a Draco stream of triangles (0,1,2)
    // (3,4,5): both give the strip's triangles (glTF 2.0 3.7.2.1).
    const Scene s = load("draco-strip.glb");
    REQUIRE(s.triangles.size() == 8);
    const glm::vec3 v[6] = {{0, 1, 0}, {0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {2, 1, 0}, {2, 0, 0}};
    const int expected[4][3] = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {3, 5, 4}};
    for (std::size_t t = 0; t < 8; ++t) {
        CAPTURE(t);
        for (int k = 0; k < 3; ++k) CHECK(s.triangles[t].v[k] == v[expected[t % 4][k]]);
    }
}

TEST_CASE("compressed gltf: Draco, JOINTS_0 and WEIGHTS_0 in the stream skin as the plain twin's") {
    // draco-skin.glb: a box (12 triangles) skinned by two joints, weights
    // by height; mesh 0 plain, mesh 1 with its skin attributes in the stream.
    const Scene s = load("draco-skin.glb");
    REQUIRE(s.triangles.size() == 24);
    std::size_t moved = 0;
    for (std::size_t t = 0; t < 12; ++t) {
        CAPTURE(t);
        CHECK(std::memcmp(s.triangles[t].v, s.triangles[t + 12].v, sizeof s.triangles[t].v) == 0);
        CHECK(std::memcmp(s.triangles[t].n, s.triangles[t + 12].n, sizeof s.triangles[t].n) == 0);
        for (const glm::vec3& v : s.triangles[t].v) moved += std::abs(v.x) > 0.2f + 1e-6f;
    }
    CHECK(moved > 0);  // the turned joint moved vertices outside the bind box's |x| <= 0.2
}

TEST_CASE("compressed gltf: Draco, COLOR_0 in the stream decodes to the plain twin's colours") {
    // draco-strip.glb's two strips with a float COLOR_0 (0.125 i, 1 - 0.125 i, 0.5, 0.25) of vertex i.
    const Scene s = load("draco-colors.glb");
    REQUIRE(s.triangles.size() == 8);
    REQUIRE(s.colors.size() == 8);
    for (std::size_t t = 0; t < 4; ++t) {
        CAPTURE(t);
        CHECK(s.colors[t] == s.colors[t + 4]);
    }
    CHECK(s.colors[0][0] == glm::vec4(0.0f, 1.0f, 0.5f, 0.25f));  // vertex 0 of triangle (0, 1, 2)
}
#endif

TEST_CASE("compressed gltf: meshopt, ATTRIBUTES, TRIANGLES and INDICES views without a filter decode to the uncompressed scene exactly") {
#if STRATA_MESHOPT
    checkSameScene("cornell-meshopt.gltf", "cornell.glb");  // a tagged fallback buffer without uri
    checkSameScene("cornell-meshopt.glb", "cornell.glb");   // an untagged placeholder in a GLB; INDICES of u32
#else
    for (const char* name : {"cornell-meshopt.gltf", "cornell-meshopt.glb"}) {
        CHECK(loadError(name) == compressedPath(name) +
                                     ": error: required extension EXT_meshopt_compression cannot be read: "
                                     "strata was built without the meshopt decoder (libmeshoptimizer)");
    }
#endif
}

TEST_CASE("compressed gltf: meshopt, the compressed data is read, not the fallback buffer's different data") {
#if STRATA_MESHOPT
    checkSameScene("cornell-meshopt-fallback.gltf", "cornell.glb");
#else
    checkSameScene("cornell-meshopt-fallback.gltf", "cornell-shifted.glb");
#endif
}

#if STRATA_MESHOPT
// Bounds (the spec, Appendix B). OCTAHEDRAL with K bits rounds x and y to a
// grid of h = 1 / (2^(K-1) - 1); the decoded vector (before normalizing,
// L1 norm 1, L2 norm >= 1/sqrt3) moves by at most h sqrt(1.5), normalizing
// scales that by at most 2 sqrt3: 4.25 h, plus the output's rounding to N
// bits, under 1.5 / (2^(N-1) - 1). QUATERNION keeps three components in
// [-1/sqrt2, 1/sqrt2] on K bits (each within 0.5 / (sqrt2 (2^(K-1) - 1))),
// the fourth (>= 1/2) moves by at most sqrt3 times their distance: in all
// under 1.25 / (2^(K-1) - 1), plus the 16-bit output's rounding.
TEST_CASE("compressed gltf: meshopt, EXPONENTIAL restores positions exactly, OCTAHEDRAL and QUATERNION stay within their precision") {
    const std::string path = compressedPath("meshopt-filters.glb");
    tinygltf::Model model = gltf::parseModel(path);
    gltf::checkExtensions(path, model);
    gltf::decodeMeshoptViews(path, model);

    CHECK(floatsOf(model, "exponential") == floatsOf(model, "exponential source"));

    const std::vector<float> normals = floatsOf(model, "octahedral16 source");
    const std::vector<float> oct16 = snormsOf(model, "octahedral16", 16);
    CHECK(largestError(oct16, normals, 3) <= 4.25 / 2047.0 + 1.5 / 32767.0);
    const std::vector<float> oct8 = snormsOf(model, "octahedral8", 8);
    CHECK(largestError(oct8, normals, 3) <= 4.25 / 127.0 + 1.5 / 127.0);
    // The fourth component passes through the filter unchanged (w = +-1).
    for (std::size_t i = 3; i < normals.size(); i += 4) {
        CHECK(oct16[i] == normals[i]);
        CHECK(oct8[i] == normals[i]);
    }

    const std::vector<float> quats = floatsOf(model, "quaternion source");
    CHECK(largestError(snormsOf(model, "quaternion", 16), quats, 4, true) <= 1.25 / 2047.0 + 2.0 / 32767.0);

    const Scene scene = load("meshopt-filters.glb");
    CHECK(scene.triangles.size() == 12);
}
#endif

TEST_CASE("compressed gltf: every broken file is one error line naming the file and its problem") {
    const auto files = brokenFiles();
    REQUIRE(files.size() >= 16);
    for (const auto& [name, message] : files) {
        CAPTURE(name);
        const std::string e = loadError("broken/" + name);
        CAPTURE(e);
        CHECK(e.rfind(compressedPath("broken/" + name) + ": error: ", 0) == 0);
        CHECK(e.find('\n') == std::string::npos);
        const bool draco = name.rfind("draco", 0) == 0;
        if (draco ? STRATA_DRACO : STRATA_MESHOPT) {
            CHECK(e.find(message) != std::string::npos);
        } else {
            CHECK(e.find("strata was built without") != std::string::npos);
        }
    }
}

TEST_CASE("compressed gltf: strata render on a broken file exits 2 with one line and writes no output") {
    for (const auto& [name, message] : brokenFiles()) {
        const std::string file = compressedPath("broken/" + name);
        CAPTURE(file);
        test::TempDir out;
        const test::Run r = test::run("render " + file + " -o " + (out / "a.exr") + " -o " + (out / "a.png") +
                                      " --spp 1 --width 8 --height 8 --quiet");
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(test::lines(r.output) == 1);
        CHECK(r.output.rfind(file + ": error: ", 0) == 0);
        CHECK(out.empty());
    }
}

TEST_SUITE_END();

TEST_CASE("compressed gltf: Draco and meshopt Cornell boxes render the uncompressed twin's image bit for bit" *
          doctest::test_suite("render")) {
    RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.spp = 4;
    s.seed = 7;
    const Scene twin = loadGltf(compressedPath("cornell.glb"));
    const RenderResult reference = test::renderScene(twin, s);
    CHECK(test::imageMean(reference.film).mean > 0.0);
    std::vector<std::string> files;
    if (STRATA_DRACO) files.push_back("cornell-draco.glb");
    if (STRATA_MESHOPT) files.push_back("cornell-meshopt.glb");
    for (const std::string& name : files) {
        CAPTURE(name);
        const RenderResult r = test::renderScene(loadGltf(compressedPath(name)), s);
        CHECK(test::sameImage(r.film, reference.film));
    }
    CHECK(vk::validationMessageCount() == 0);
}

#endif  // STRATA_COMPRESSED_DIR
