// The meshopt filters' file and the broken compressed files of
// tests/data/make_compressed.cpp.
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <draco/compression/decode.h>
#include <meshoptimizer.h>

#include "make_compressed.h"

namespace makecompressed {

namespace {

// Deterministic bytes (a 32-bit LCG, Numerical Recipes' constants).
struct Lcg {
    std::uint32_t state;
    unsigned char next() {
        state = state * 1664525u + 1013904223u;
        return static_cast<unsigned char>(state >> 24);
    }
};

// n unit vectors spread over the sphere (a Fibonacci lattice) as x, y, z, w
// with w = +-1.
std::vector<float> unitVectors(std::size_t n) {
    std::vector<float> out;
    for (std::size_t i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * static_cast<double>(i) + 1.0) / static_cast<double>(n);
        const double r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * static_cast<double>(i);
        out.insert(out.end(), {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                               static_cast<float>(z), i % 2 ? -1.0f : 1.0f});
    }
    return out;
}

// n unit quaternions (x, y, z, w) of rotations about the lattice's axes.
std::vector<float> unitQuaternions(std::size_t n) {
    const std::vector<float> axes = unitVectors(n);
    std::vector<float> out;
    for (std::size_t i = 0; i < n; ++i) {
        const double half = 0.05 + 3.0 * static_cast<double>(i) / static_cast<double>(n);
        const auto s = static_cast<float>(std::sin(half));
        out.insert(out.end(), {axes[4 * i] * s, axes[4 * i + 1] * s, axes[4 * i + 2] * s,
                               static_cast<float>(std::cos(half))});
    }
    return out;
}

// A view of `count` elements of `stride` bytes, filtered by `filter` (the
// filtered bytes in `filtered`), compressed into buffer 0 with its own
// buffer the placeholder 1; the source floats go in a plain view named
// NAME + " source".
void addFilteredView(Doc& doc, const std::string& name, const Bytes& filtered, const std::vector<float>& source,
                     std::size_t count, std::size_t stride, const std::string& filter) {
    const int view = meshoptView(doc, 1, filtered.size(), encodeMeshopt("ATTRIBUTES", filtered.data(), count, stride, 0),
                                 count, stride, "ATTRIBUTES", filter, nullptr);
    doc.json["bufferViews"][static_cast<std::size_t>(view)]["name"] = name;
    const int plain = doc.addPlainView(0, source.data(), source.size() * 4);
    doc.json["bufferViews"][static_cast<std::size_t>(plain)]["name"] = name + " source";
}

Bytes filterOct(const std::vector<float>& v, std::size_t stride, int bits) {
    Bytes out(v.size() / 4 * stride);
    meshopt_encodeFilterOct(out.data(), v.size() / 4, stride, bits, v.data());
    return out;
}

// ---- broken files ----

struct Broken {
    std::ofstream expected;
    fs::path dir;
    void write(const std::string& name, const Doc& doc, const std::string& message) {
        writeGlb(dir / name, doc);
        expected << name << "\t" << message << "\n";
    }
};

// The bufferView of attribute `semantic` (or "indices") of mesh m's primitive.
Json& accessorOf(Doc& doc, std::size_t m, const std::string& semantic) {
    Json& prim = doc.json["meshes"][m]["primitives"][0];
    const auto a = semantic == "indices" ? prim["indices"].get<std::size_t>()
                                         : prim["attributes"][semantic].get<std::size_t>();
    return doc.json["accessors"][a];
}
Json& viewOf(Doc& doc, std::size_t m, const std::string& semantic) {
    return doc.json["bufferViews"][accessorOf(doc, m, semantic)["bufferView"].get<std::size_t>()];
}

// Overwrites bytes [from, end) of a view's data in buffer 0 with LCG bytes,
// trying seeds until `decodes` refuses the result.
void garble(Doc& doc, std::size_t offset, std::size_t length, std::size_t from,
            const std::function<bool(const unsigned char*, std::size_t)>& decodes) {
    for (std::uint32_t seed = 1;; ++seed) {
        Lcg lcg{seed};
        unsigned char* p = doc.buffers[0].data() + offset;
        for (std::size_t i = from; i < length; ++i) p[i] = lcg.next();
        if (from == 0) p[0] = 0;  // no codec's header byte
        if (!decodes(p, length)) return;
        if (seed > 1000) throw std::runtime_error("no garbage that fails to decode");
    }
}

bool dracoDecodes(const unsigned char* p, std::size_t n) {
    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char*>(p), n);
    return draco::Decoder().DecodeMeshFromBuffer(&in).ok();
}

void writeBrokenDraco(Broken& out) {
    const std::vector<Prim> prims = {cornell()[5], cornell()[6]};  // the light and a box
    const auto make = [&] {
        Doc doc = scene(prims, [](Doc& d, const Prim& p, std::size_t) { return dracoPrimitive(d, p, {}, nullptr); });
        addExtension(doc.json, "KHR_draco_mesh_compression", true);
        return doc;
    };
    const auto stream = [](Doc& doc) -> Json& {
        const auto v = doc.json["meshes"][1]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
        return doc.json["bufferViews"][v.get<std::size_t>()];
    };
    {
        Doc doc = make();
        stream(doc)["byteLength"] = stream(doc)["byteLength"].get<std::size_t>() / 2;
        out.write("draco-truncated.glb", doc, "corrupt Draco stream");
    }
    for (const std::size_t from : {std::size_t(0), std::size_t(16)}) {
        Doc doc = make();
        const Json& v = stream(doc);
        garble(doc, v["byteOffset"], v["byteLength"], from, dracoDecodes);
        out.write(from ? "draco-garbage-body.glb" : "draco-garbage.glb", doc,
                  from ? "corrupt Draco stream" : "not a Draco stream");
    }
    {
        Doc doc = make();
        accessorOf(doc, 1, "POSITION")["count"] = accessorOf(doc, 1, "POSITION")["count"].get<int>() + 1;
        out.write("draco-count-mismatch.glb", doc, "but the Draco stream decodes 24 points");
    }
    {
        Doc doc = make();
        accessorOf(doc, 1, "indices")["count"] = accessorOf(doc, 1, "indices")["count"].get<int>() - 3;
        out.write("draco-indices-mismatch.glb", doc, "but the Draco stream decodes 12 triangles");
    }
    {
        Doc doc = make();
        stream(doc)["byteOffset"] = doc.buffers[0].size();
        out.write("draco-view-out-of-range.glb", doc, "is out of range of buffer 0");
    }
    {
        Doc doc = make();
        doc.json["meshes"][1]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
        out.write("draco-missing-attribute.glb", doc, "Draco attribute id 9 is not in the Draco stream");
    }
    {
        Doc doc = make();
        doc.json["meshes"][1]["primitives"][0]["mode"] = 6;
        out.write("draco-fan.glb", doc, "mode 6 is not allowed with Draco; only TRIANGLES (4) and TRIANGLE_STRIP (5)");
    }
    {
        // TEXCOORD_0 outside the stream, one element short.
        Doc doc = scene(prims, [](Doc& d, const Prim& p, std::size_t) {
            return dracoPrimitive(d, p, {true, 0, {"POSITION", "NORMAL"}}, nullptr);
        });
        addExtension(doc.json, "KHR_draco_mesh_compression", true);
        accessorOf(doc, 1, "TEXCOORD_0")["count"] = 23;
        out.write("draco-mixed-count.glb", doc, "TEXCOORD_0 has 23 elements but POSITION has 24");
    }
    {
        Doc doc = make();
        doc.json["meshes"][1]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 999;
        out.write("draco-view-missing.glb", doc, "bufferView 999 does not exist");
    }
}

void writeBrokenMeshopt(Broken& out) {
    const std::vector<Prim> prims = {cornell()[5], cornell()[6]};
    const auto make = [&] {
        Doc doc = baseDocument(prims);
        doc.addBuffer();
        for (std::size_t m = 0; m < prims.size(); ++m) {
            const Json prim = meshoptPrimitive(doc, prims[m], 1, {}, nullptr);
            doc.json["meshes"].push_back({{"name", prims[m].name}, {"primitives", {prim}}});
        }
        addExtension(doc.json, "EXT_meshopt_compression", true);
        doc.json["buffers"][1] = {{"byteLength", doc.buffers[1].size()}};
        return doc;
    };
    const auto ext = [](Json& view) -> Json& { return view["extensions"]["EXT_meshopt_compression"]; };
    {
        Doc doc = make();
        Json& e = ext(viewOf(doc, 1, "POSITION"));
        e["byteLength"] = e["byteLength"].get<std::size_t>() / 2;
        out.write("meshopt-truncated.glb", doc, "corrupt or truncated data (meshopt_decodeVertexBuffer");
    }
    for (const std::size_t from : {std::size_t(0), std::size_t(1)}) {
        Doc doc = make();
        const Json& e = ext(viewOf(doc, 1, "POSITION"));
        const std::size_t count = e["count"], stride = e["byteStride"];
        garble(doc, e["byteOffset"], e["byteLength"], from, [&](const unsigned char* p, std::size_t n) {
            Bytes scratch(count * stride);
            return meshopt_decodeVertexBuffer(scratch.data(), count, stride, p, n) == 0;
        });
        out.write(from ? "meshopt-garbage-body.glb" : "meshopt-garbage.glb", doc, "corrupt or truncated data");
    }
    {
        Doc doc = make();
        Json& e = ext(viewOf(doc, 1, "indices"));
        e["count"] = e["count"].get<std::size_t>() + 3;
        out.write("meshopt-count-mismatch.glb", doc, "is not the bufferView's byteLength");
    }
    {
        Doc doc = make();
        ext(viewOf(doc, 1, "NORMAL"))["byteOffset"] = 1 << 30;
        out.write("meshopt-data-out-of-range.glb", doc, "data is out of range of buffer 0");
    }
    {
        Doc doc = make();
        ext(viewOf(doc, 1, "POSITION"))["filter"] = "OCTAHEDRAL";
        out.write("meshopt-bad-filter.glb", doc, "filter OCTAHEDRAL with byteStride 12");
    }
    {
        Doc doc = make();
        ext(viewOf(doc, 1, "indices"))["mode"] = "LINES";
        out.write("meshopt-bad-mode.glb", doc, "mode \"LINES\" is not one of ATTRIBUTES, TRIANGLES, INDICES");
    }
    {
        Doc doc = make();
        accessorOf(doc, 1, "POSITION")["count"] = 25;
        out.write("meshopt-accessor-overrun.glb", doc, "is out of range of bufferView");
    }
    {
        // A count whose decoded size no stream of this length can hold.
        Doc doc = make();
        Json& view = viewOf(doc, 1, "POSITION");
        ext(view)["count"] = 100000000;
        view["byteLength"] = 1200000000;
        out.write("meshopt-too-large.glb", doc, "is too short to decode 1200000000 bytes");
    }
}

}  // namespace

void writeFilterFile(const fs::path& dir) {
    // A box whose coordinates are multiples of 1/8: EXPONENTIAL with a 24-bit
    // mantissa (one exponent per vertex) holds them exactly.
    const Prim dyadic = box("Dyadic", {0.25f, 0.5f, -0.125f}, {0.5f, 0.25f, 0.375f}, 0);
    Doc doc = baseDocument({dyadic});
    doc.addBuffer();
    Json prim = meshoptPrimitive(doc, dyadic, 1, {}, nullptr);
    {
        Bytes exp(dyadic.positions.size() * 4);
        meshopt_encodeFilterExp(exp.data(), dyadic.vertices(), 12, 24, dyadic.positions.data());
        const auto a = prim["attributes"]["POSITION"].get<std::size_t>();
        const int view = meshoptView(doc, 1, exp.size(), encodeMeshopt("ATTRIBUTES", exp.data(), dyadic.vertices(), 12, 0),
                                     dyadic.vertices(), 12, "ATTRIBUTES", "EXPONENTIAL", nullptr);
        doc.json["accessors"][a]["bufferView"] = view;
        doc.json["bufferViews"][static_cast<std::size_t>(view)]["name"] = "exponential";
        const int plain = doc.addPlainView(0, dyadic.positions.data(), dyadic.positions.size() * 4);
        doc.json["bufferViews"][static_cast<std::size_t>(plain)]["name"] = "exponential source";
    }
    doc.json["meshes"].push_back({{"name", "Dyadic"}, {"primitives", {prim}}});

    // Views no accessor reads: octahedral normals in 16 bits (K = 12) and 8
    // bits (K = 8), quaternions in 16 bits (K = 12).
    const std::vector<float> normals = unitVectors(64), quats = unitQuaternions(64);
    addFilteredView(doc, "octahedral16", filterOct(normals, 8, 12), normals, 64, 8, "OCTAHEDRAL");
    addFilteredView(doc, "octahedral8", filterOct(normals, 4, 8), normals, 64, 4, "OCTAHEDRAL");
    Bytes q(64 * 8);
    meshopt_encodeFilterQuat(q.data(), 64, 8, 12, quats.data());
    addFilteredView(doc, "quaternion", q, quats, 64, 8, "QUATERNION");

    addExtension(doc.json, "EXT_meshopt_compression", true);
    doc.json["buffers"][1] = {{"byteLength", doc.buffers[1].size()},
                              {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    writeGlb(dir / "meshopt-filters.glb", doc);
}

void writeBrokenFiles(const fs::path& dir) {
    Broken out{std::ofstream(dir / "broken" / "expected.txt"), dir / "broken"};
    writeBrokenDraco(out);
    writeBrokenMeshopt(out);
    if (!out.expected) throw std::runtime_error("cannot write broken/expected.txt");
}

}  // namespace makecompressed
