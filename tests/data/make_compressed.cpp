// Writes the compressed glTF files of tests/test_gltf_compressed.cpp into
// DIR (tests/CMakeLists.txt runs it at build time into the build folder):
//   make_compressed DIR
// The geometry is our own (CC0): a Cornell-like box of quads and two boxes,
// encoded by libdraco (KHR_draco_mesh_compression) and libmeshoptimizer
// (EXT_meshopt_compression) next to its uncompressed twin, a file of the
// meshopt filters, and broken variants in DIR/broken with
// DIR/broken/expected.txt: per file its name, a tab, and a part of the
// one-line error it must give.
#include "make_compressed.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <meshoptimizer.h>

namespace makecompressed {

namespace {

// A quad with normal n and corners c +- u +- v, counter-clockwise seen from n
// (u x v points along n).
Prim quad(const std::string& name, std::array<float, 3> c, std::array<float, 3> u,
          std::array<float, 3> v, std::array<float, 3> n, int material) {
    Prim p;
    p.name = name;
    p.material = material;
    const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
    for (int k = 0; k < 4; ++k) {
        for (int i = 0; i < 3; ++i) p.positions.push_back(c[i] + su[k] * u[i] + sv[k] * v[i]);
        p.normals.insert(p.normals.end(), n.begin(), n.end());
        p.uv0.push_back((su[k] + 1) / 2);
        p.uv0.push_back((sv[k] + 1) / 2);
    }
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

// Every position moved by (0.5, 0, 0): fallback data that must not be read
// where the compressed data can be.
std::vector<Prim> shifted(std::vector<Prim> prims) {
    for (Prim& p : prims) {
        for (std::size_t i = 0; i < p.positions.size(); i += 3) p.positions[i] += 0.5f;
    }
    return prims;
}

const char* typeOf(int components) {
    return components == 1 ? "SCALAR" : components == 2 ? "VEC2" : components == 3 ? "VEC3" : "VEC4";
}

Bytes indexBytes(const std::vector<std::uint32_t>& indices, std::size_t size) {
    if (size == 4) return bytesOf(indices);
    return bytesOf(std::vector<std::uint16_t>(indices.begin(), indices.end()));
}

void putU32(Bytes& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

}  // namespace

Prim box(const std::string& name, std::array<float, 3> c, std::array<float, 3> h, int material) {
    Prim p;
    p.name = name;
    p.material = material;
    for (int axis = 0; axis < 3; ++axis) {
        for (const float s : {1.0f, -1.0f}) {
            std::array<float, 3> n{}, u{}, v{}, fc = c;
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            n[axis] = s;
            fc[axis] += s * h[axis];
            u[a] = s * h[a];  // u x v = s h[a] h[b] along the axis: counter-clockwise from outside
            v[b] = h[b];
            const Prim q = quad(name, fc, u, v, n, material);
            const auto base = static_cast<std::uint32_t>(p.vertices());
            for (const auto i : q.indices) p.indices.push_back(base + i);
            p.positions.insert(p.positions.end(), q.positions.begin(), q.positions.end());
            p.normals.insert(p.normals.end(), q.normals.begin(), q.normals.end());
            p.uv0.insert(p.uv0.end(), q.uv0.begin(), q.uv0.end());
            for (int k = 0; k < 4; ++k) {
                p.uv1.push_back(q.uv0[2 * k] * 0.5f + 0.25f);
                p.uv1.push_back(q.uv0[2 * k + 1] * 0.5f);
                for (int i = 0; i < 3; ++i) p.tangents.push_back(u[i] / h[a]);
                p.tangents.push_back(s);
            }
        }
    }
    return p;
}

std::vector<Prim> cornell() {
    return {
        quad("Floor", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 0),
        quad("Ceiling", {0, 2, 0}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}, 0),
        quad("BackWall", {0, 1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0),
        quad("LeftWall", {-1, 1, 0}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, 1),
        quad("RightWall", {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, 2),
        quad("Light", {0, 1.98f, 0}, {0.23f, 0, 0}, {0, 0, 0.23f}, {0, -1, 0}, 3),
        box("ShortBox", {0.33f, 0.3f, 0.37f}, {0.3f, 0.3f, 0.3f}, 0),
        box("TallBox", {-0.36f, 0.6f, -0.31f}, {0.3f, 0.6f, 0.3f}, 0),
    };
}

std::vector<Attribute> attributesOf(const Prim& p) {
    std::vector<Attribute> out = {{"POSITION", 3, &p.positions}, {"NORMAL", 3, &p.normals},
                                  {"TEXCOORD_0", 2, &p.uv0}};
    if (!p.uv1.empty()) out.push_back({"TEXCOORD_1", 2, &p.uv1, true});
    if (!p.tangents.empty()) out.push_back({"TANGENT", 4, &p.tangents});
    if (!p.colors.empty()) out.push_back({"COLOR_0", 4, &p.colors});
    if (!p.joints.empty()) out.push_back({"JOINTS_0", 4, &p.joints, true, true});
    if (!p.weights.empty()) out.push_back({"WEIGHTS_0", 4, &p.weights});
    return out;
}

Bytes attributeBytes(const Attribute& a) {
    if (!a.u16) return bytesOf(*a.values);
    std::vector<std::uint16_t> q;
    for (const float v : *a.values) q.push_back(static_cast<std::uint16_t>(std::lround(a.integer ? v : v * 65535.0f)));
    return bytesOf(q);
}

int Doc::addBuffer() {
    buffers.emplace_back();
    json["buffers"].push_back(Json::object());
    return static_cast<int>(buffers.size() - 1);
}

std::size_t Doc::append(int b, const void* data, std::size_t size) {
    Bytes& buf = buffers[static_cast<std::size_t>(b)];
    buf.resize((buf.size() + 3) & ~std::size_t(3), 0);
    const std::size_t offset = buf.size();
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + size);
    return offset;
}

int Doc::addView(Json view) {
    json["bufferViews"].push_back(std::move(view));
    return static_cast<int>(json["bufferViews"].size() - 1);
}

int Doc::addPlainView(int b, const void* data, std::size_t size, std::size_t stride) {
    Json view = {{"buffer", b}, {"byteOffset", append(b, data, size)}, {"byteLength", size}};
    if (stride) view["byteStride"] = stride;
    return addView(view);
}

int Doc::addAccessor(Json accessor) {
    json["accessors"].push_back(std::move(accessor));
    return static_cast<int>(json["accessors"].size() - 1);
}

Doc baseDocument(const std::vector<Prim>& prims) {
    Doc doc;
    Json& j = doc.json;
    j["asset"] = {{"version", "2.0"}, {"generator", "strata tests/data/make_compressed.cpp"}};
    auto diffuse = [](const char* name, float r, float g, float b) {
        return Json{{"name", name},
                    {"pbrMetallicRoughness",
                     {{"baseColorFactor", {r, g, b, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
    };
    j["materials"] = {diffuse("White", 0.73f, 0.73f, 0.73f), diffuse("Red", 0.63f, 0.065f, 0.05f),
                      diffuse("Green", 0.14f, 0.45f, 0.09f), diffuse("Light", 0.73f, 0.73f, 0.73f)};
    j["materials"][3]["emissiveFactor"] = {1.0, 1.0, 1.0};
    j["materials"][3]["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 15.0}}}};
    j["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    j["cameras"] = {{{"type", "perspective"},
                     {"perspective", {{"yfov", 0.6981317}, {"znear", 0.01}, {"aspectRatio", 1.0}}}}};
    Json nodes = Json::array(), roots = Json::array();
    for (std::size_t m = 0; m < prims.size(); ++m) {
        nodes.push_back({{"name", prims[m].name}, {"mesh", m}});
        roots.push_back(m);
    }
    nodes.push_back({{"name", "Camera"}, {"camera", 0}, {"translation", {0.0, 1.0, 3.8}}});
    roots.push_back(prims.size());
    j["nodes"] = nodes;
    j["scenes"] = {{{"nodes", roots}}};
    j["scene"] = 0;
    j["meshes"] = Json::array();
    j["accessors"] = Json::array();
    j["bufferViews"] = Json::array();
    j["buffers"] = Json::array();
    doc.addBuffer();
    return doc;
}

void addExtension(Json& j, const char* name, bool required) {
    j["extensionsUsed"].push_back(name);
    if (required) j["extensionsRequired"].push_back(name);
}

Json accessorFor(const Attribute& a, std::size_t count) {
    Json acc = {{"componentType", a.u16 ? kU16 : kFloat}, {"count", count}, {"type", typeOf(a.components)}};
    if (a.u16 && !a.integer) acc["normalized"] = true;
    if (std::string(a.semantic) == "POSITION") {
        std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
        for (std::size_t i = 0; i < a.values->size(); ++i) {
            lo[i % 3] = std::min(lo[i % 3], (*a.values)[i]);
            hi[i % 3] = std::max(hi[i % 3], (*a.values)[i]);
        }
        acc["min"] = lo;
        acc["max"] = hi;
    }
    return acc;
}

Json plainPrimitive(Doc& doc, const Prim& p, int b) {
    Json prim = {{"material", p.material}, {"attributes", Json::object()}};
    for (const Attribute& a : attributesOf(p)) {
        Json acc = accessorFor(a, p.vertices());
        const Bytes bytes = attributeBytes(a);
        acc["bufferView"] = doc.addPlainView(b, bytes.data(), bytes.size());
        prim["attributes"][a.semantic] = doc.addAccessor(acc);
    }
    const Bytes idx = indexBytes(p.indices, 2);
    const int view = doc.addPlainView(b, idx.data(), idx.size());
    prim["indices"] = doc.addAccessor(
        {{"bufferView", view}, {"componentType", kU16}, {"count", p.indices.size()}, {"type", "SCALAR"}});
    return prim;
}

bool DracoOptions::inStream(const std::string& semantic) const {
    return compressed.empty() || std::find(compressed.begin(), compressed.end(), semantic) != compressed.end();
}

DracoStream encodeDraco(const Prim& p, const DracoOptions& o) {
    draco::Mesh mesh;
    const auto n = static_cast<std::uint32_t>(p.vertices());
    mesh.set_num_points(n);
    DracoStream out;
    for (const Attribute& a : attributesOf(p)) {
        const std::string s = a.semantic;
        if (!o.inStream(s)) continue;
        const auto type = s == "POSITION" ? draco::GeometryAttribute::POSITION
                          : s == "NORMAL" ? draco::GeometryAttribute::NORMAL
                          : s == "TANGENT" ? draco::GeometryAttribute::GENERIC
                          : s == "COLOR_0" ? draco::GeometryAttribute::COLOR
                          : s == "JOINTS_0" || s == "WEIGHTS_0" ? draco::GeometryAttribute::GENERIC
                                           : draco::GeometryAttribute::TEX_COORD;
        const Bytes bytes = attributeBytes(a);
        const std::size_t size = bytes.size() / n;  // bytes per vertex
        draco::GeometryAttribute ga;
        ga.Init(type, nullptr, static_cast<std::uint8_t>(a.components), a.u16 ? draco::DT_UINT16 : draco::DT_FLOAT32,
                a.u16 && !a.integer, static_cast<std::int64_t>(size), 0);
        const int id = mesh.AddAttribute(ga, true, n);
        for (std::uint32_t i = 0; i < n; ++i) {
            mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), bytes.data() + i * size);
        }
        out.ids[s] = mesh.attribute(id)->unique_id();
    }
    for (std::size_t t = 0; t < p.indices.size(); t += 3) {
        mesh.AddFace({draco::PointIndex(p.indices[t]), draco::PointIndex(p.indices[t + 1]),
                      draco::PointIndex(p.indices[t + 2])});
    }
    draco::Encoder encoder;
    encoder.SetEncodingMethod(o.sequential ? draco::MESH_SEQUENTIAL_ENCODING : draco::MESH_EDGEBREAKER_ENCODING);
    if (o.positionBits) encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, o.positionBits);
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
    if (!status.ok()) throw std::runtime_error("draco: " + status.error_msg_string());
    out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    draco::DecoderBuffer in;
    in.Init(buffer.data(), buffer.size());
    auto decoded = draco::Decoder().DecodeMeshFromBuffer(&in);
    if (!decoded.ok()) throw std::runtime_error("draco decode: " + decoded.status().error_msg_string());
    out.points = decoded.value()->num_points();
    out.faces = decoded.value()->num_faces();
    return out;
}

Json dracoPrimitive(Doc& doc, const Prim& p, const DracoOptions& o, const Prim* fallback) {
    const DracoStream s = encodeDraco(p, o);
    Json prim = {{"material", p.material}, {"attributes", Json::object()}};
    Json ids = Json::object();
    const auto own = attributesOf(p);
    const auto other = fallback ? attributesOf(*fallback) : own;
    for (std::size_t k = 0; k < own.size(); ++k) {
        Json acc = accessorFor(own[k], s.points);
        const bool compressed = o.inStream(own[k].semantic);
        if (fallback || !compressed) {
            const Bytes bytes = attributeBytes(compressed ? other[k] : own[k]);
            acc["bufferView"] = doc.addPlainView(0, bytes.data(), bytes.size());
        }
        prim["attributes"][own[k].semantic] = doc.addAccessor(acc);
        if (compressed) ids[own[k].semantic] = s.ids.at(own[k].semantic);
    }
    Json indices = {{"componentType", kU16}, {"count", 3 * s.faces}, {"type", "SCALAR"}};
    if (fallback) {
        const Bytes idx = indexBytes(fallback->indices, 2);
        indices["bufferView"] = doc.addPlainView(0, idx.data(), idx.size());
    }
    prim["indices"] = doc.addAccessor(indices);
    const int view = doc.addPlainView(0, s.bytes.data(), s.bytes.size());
    prim["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", view}, {"attributes", ids}};
    return prim;
}

Bytes encodeMeshopt(const std::string& mode, const void* data, std::size_t count, std::size_t stride,
                    std::size_t vertices) {
    Bytes out;
    std::size_t size = 0;
    const auto* indices = static_cast<const unsigned*>(data);
    if (mode == "ATTRIBUTES") {
        out.resize(meshopt_encodeVertexBufferBound(count, stride));
        size = meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride);
    } else if (mode == "TRIANGLES") {
        out.resize(meshopt_encodeIndexBufferBound(count, vertices));
        size = meshopt_encodeIndexBuffer(out.data(), out.size(), indices, count);
    } else {
        out.resize(meshopt_encodeIndexSequenceBound(count, vertices));
        size = meshopt_encodeIndexSequence(out.data(), out.size(), indices, count);
    }
    if (size == 0) throw std::runtime_error("meshopt: encoding failed");
    out.resize(size);
    return out;
}

int meshoptView(Doc& doc, int parent, std::size_t rawSize, const Bytes& compressed, std::size_t count,
                std::size_t stride, const std::string& mode, const std::string& filter,
                const Bytes* fallbackData) {
    std::size_t offset = 0;
    if (fallbackData) {
        offset = doc.append(parent, fallbackData->data(), fallbackData->size());
    } else {
        const Bytes zeros(rawSize, 0);  // a placeholder's byteLength covers its views
        offset = doc.append(parent, zeros.data(), zeros.size());
    }
    Json ext = {{"buffer", 0},           {"byteOffset", doc.append(0, compressed.data(), compressed.size())},
                {"byteLength", compressed.size()}, {"byteStride", stride},
                {"count", count},        {"mode", mode}};
    if (filter != "NONE") ext["filter"] = filter;
    Json view = {{"buffer", parent}, {"byteOffset", offset}, {"byteLength", rawSize},
                 {"extensions", {{"EXT_meshopt_compression", ext}}}};
    if (mode == "ATTRIBUTES") view["byteStride"] = stride;
    return doc.addView(view);
}

Json meshoptPrimitive(Doc& doc, const Prim& p, int parent, const MeshoptOptions& o, const Prim* fallback) {
    Json prim = {{"material", p.material}, {"attributes", Json::object()}};
    const auto own = attributesOf(p);
    const auto other = fallback ? attributesOf(*fallback) : own;
    for (std::size_t k = 0; k < own.size(); ++k) {
        const Bytes raw = attributeBytes(own[k]), fb = attributeBytes(other[k]);
        const std::size_t stride = raw.size() / p.vertices();
        Json acc = accessorFor(own[k], p.vertices());
        acc["bufferView"] = meshoptView(doc, parent, raw.size(),
                                        encodeMeshopt("ATTRIBUTES", raw.data(), p.vertices(), stride, 0),
                                        p.vertices(), stride, "ATTRIBUTES", "NONE", fallback ? &fb : nullptr);
        prim["attributes"][own[k].semantic] = doc.addAccessor(acc);
    }
    const Bytes raw = indexBytes(p.indices, o.indexSize);
    const Bytes fb = indexBytes(fallback ? fallback->indices : p.indices, o.indexSize);
    const int view = meshoptView(doc, parent, raw.size(),
                                 encodeMeshopt(o.indexMode, p.indices.data(), p.indices.size(), o.indexSize, p.vertices()),
                                 p.indices.size(), o.indexSize, o.indexMode, "NONE", fallback ? &fb : nullptr);
    prim["indices"] = doc.addAccessor({{"bufferView", view},
                                       {"componentType", o.indexSize == 4 ? kU32 : kU16},
                                       {"count", p.indices.size()},
                                       {"type", "SCALAR"}});
    return prim;
}

Doc scene(const std::vector<Prim>& prims, const std::function<Json(Doc&, const Prim&, std::size_t)>& write) {
    Doc doc = baseDocument(prims);
    for (std::size_t m = 0; m < prims.size(); ++m) {
        doc.json["meshes"].push_back({{"name", prims[m].name}, {"primitives", {write(doc, prims[m], m)}}});
    }
    return doc;
}

void writeBytes(const fs::path& path, const Bytes& bytes) {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!f) throw std::runtime_error("cannot write " + path.string());
}

void writeGlb(const fs::path& path, Doc doc) {
    Bytes bin = doc.buffers[0];
    bin.resize((bin.size() + 3) & ~std::size_t(3), 0);
    doc.json["buffers"][0] = {{"byteLength", doc.buffers[0].size()}};
    std::string json = doc.json.dump();
    json.append((4 - json.size() % 4) % 4, ' ');
    Bytes out = {'g', 'l', 'T', 'F'};
    putU32(out, 2);
    putU32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    putU32(out, static_cast<std::uint32_t>(json.size()));
    putU32(out, 0x4E4F534Au);  // JSON
    out.insert(out.end(), json.begin(), json.end());
    putU32(out, static_cast<std::uint32_t>(bin.size()));
    putU32(out, 0x004E4942u);  // BIN
    out.insert(out.end(), bin.begin(), bin.end());
    writeBytes(path, out);
}

void writeGltf(const fs::path& path, Doc doc, const std::map<int, std::string>& files) {
    for (const auto& [b, file] : files) {
        const auto i = static_cast<std::size_t>(b);
        doc.json["buffers"][i]["uri"] = file;
        doc.json["buffers"][i]["byteLength"] = doc.buffers[i].size();
        writeBytes(path.parent_path() / file, doc.buffers[i]);
    }
    std::ofstream out(path);
    out << doc.json.dump(1) << "\n";
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

namespace {

void writeValidFiles(const fs::path& dir) {
    const std::vector<Prim> prims = cornell();
    const std::vector<Prim> moved = shifted(prims);
    const auto plain = [](Doc& d, const Prim& p, std::size_t) { return plainPrimitive(d, p, 0); };
    writeGlb(dir / "cornell.glb", scene(prims, plain));
    writeGlb(dir / "cornell-shifted.glb", scene(moved, plain));

    // Draco: every primitive compressed; with `withFallback` its accessors
    // also hold the shifted geometry and the extension is only used.
    auto draco = [&](const DracoOptions& o, bool withFallback) {
        Doc doc = scene(prims, [&](Doc& d, const Prim& p, std::size_t m) {
            return dracoPrimitive(d, p, o, withFallback ? &moved[m] : nullptr);
        });
        addExtension(doc.json, "KHR_draco_mesh_compression", !withFallback);
        return doc;
    };
    writeGlb(dir / "cornell-draco.glb", draco({}, false));
    writeGlb(dir / "cornell-draco-edgebreaker.glb", draco({false, 0}, false));
    writeGlb(dir / "cornell-draco-quantized.glb", draco({true, 14}, false));
    writeGlb(dir / "cornell-draco-fallback.glb", draco({}, true));
    // POSITION and NORMAL in the stream; TEXCOORD_0/1 and TANGENT plain.
    writeGlb(dir / "cornell-draco-mixed.glb", draco({true, 0, {"POSITION", "NORMAL"}}, false));

    // A TRIANGLE_STRIP of 6 vertices plain (indices 0-5), then in a Draco
    // stream whose two triangles (0,1,2) (3,4,5) hold that index sequence.
    {
        Prim strip;
        strip.name = "Strip";
        for (int i = 0; i < 6; ++i) {
            strip.positions.insert(strip.positions.end(), {float(i / 2), float(1 - i % 2), 0.0f});
            strip.normals.insert(strip.normals.end(), {0.0f, 0.0f, 1.0f});
            strip.uv0.insert(strip.uv0.end(), {float(i / 2) / 2, float(i % 2)});
            strip.indices.push_back(static_cast<std::uint32_t>(i));
        }
        // The strip plain (mesh 0), then in a Draco stream (mesh 1), both TRIANGLE_STRIP.
        const auto twins = [&](const fs::path& file) {
            Doc doc = scene({strip, strip}, [](Doc& d, const Prim& p, std::size_t m) {
                Json prim = m == 0 ? plainPrimitive(d, p, 0) : dracoPrimitive(d, p, {}, nullptr);
                prim["mode"] = 5;
                return prim;
            });
            addExtension(doc.json, "KHR_draco_mesh_compression", true);
            writeGlb(file, doc);
        };
        twins(dir / "draco-strip.glb");
        // The same strip with a float COLOR_0 per vertex.
        for (int i = 0; i < 6; ++i) strip.colors.insert(strip.colors.end(), {0.125f * i, 1.0f - 0.125f * i, 0.5f, 0.25f});
        twins(dir / "draco-colors.glb");
    }

    // Two twins of a box skinned by two joints (joint 1 turned about z):
    // mesh 0 plain, mesh 1 with JOINTS_0 and WEIGHTS_0 in its Draco stream.
    {
        Prim bar = box("Bar", {0.0f, 0.5f, 0.0f}, {0.2f, 0.5f, 0.2f}, 0);
        for (std::size_t i = 0; i < bar.vertices(); ++i) {
            const float w = std::clamp(bar.positions[3 * i + 1], 0.0f, 1.0f);  // y, 0 to 1
            bar.joints.insert(bar.joints.end(), {0, 1, 0, 0});
            bar.weights.insert(bar.weights.end(), {1.0f - w, w, 0.0f, 0.0f});
        }
        Doc doc = scene({bar, bar}, [](Doc& d, const Prim& p, std::size_t m) {
            return m == 0 ? plainPrimitive(d, p, 0) : dracoPrimitive(d, p, {}, nullptr);
        });
        Json& nodes = doc.json["nodes"];
        nodes.push_back({{"name", "Joint0"}});
        nodes.push_back({{"name", "Joint1"}, {"translation", {0.0, 0.5, 0.0}}, {"rotation", {0.0, 0.0, 0.3826834, 0.9238795}}});
        const std::size_t joint0 = nodes.size() - 2, joint1 = nodes.size() - 1;
        doc.json["scenes"][0]["nodes"].push_back(joint0);
        doc.json["scenes"][0]["nodes"].push_back(joint1);
        // tinygltf 2.7 requires inverseBindMatrices: two identities.
        std::vector<float> identities(32, 0.0f);
        for (int k = 0; k < 4; ++k) identities[static_cast<std::size_t>(5 * k)] = identities[static_cast<std::size_t>(16 + 5 * k)] = 1.0f;
        const int bindView = doc.addPlainView(0, identities.data(), identities.size() * sizeof(float));
        const int bind = doc.addAccessor({{"bufferView", bindView}, {"componentType", kFloat}, {"count", 2}, {"type", "MAT4"}});
        doc.json["skins"] = {{{"joints", {joint0, joint1}}, {"inverseBindMatrices", bind}}};
        nodes[0]["skin"] = 0;
        nodes[1]["skin"] = 0;
        addExtension(doc.json, "KHR_draco_mesh_compression", true);
        writeGlb(dir / "draco-skin.glb", doc);
    }

    // meshopt: compressed data in buffer 0, the views' own buffer 1.
    auto meshopt = [&](const std::function<MeshoptOptions(std::size_t)>& options, bool withFallback) {
        Doc doc = baseDocument(prims);
        doc.addBuffer();
        for (std::size_t m = 0; m < prims.size(); ++m) {
            const Json prim = meshoptPrimitive(doc, prims[m], 1, options(m), withFallback ? &moved[m] : nullptr);
            doc.json["meshes"].push_back({{"name", prims[m].name}, {"primitives", {prim}}});
        }
        addExtension(doc.json, "EXT_meshopt_compression", !withFallback);
        return doc;
    };
    const auto triangles = [](std::size_t) { return MeshoptOptions{}; };
    const Json tag = {{"EXT_meshopt_compression", {{"fallback", true}}}};
    {
        // .gltf with a tagged fallback buffer without uri.
        Doc doc = meshopt(triangles, false);
        doc.json["buffers"][1] = {{"byteLength", doc.buffers[1].size()}, {"extensions", tag}};
        writeGltf(dir / "cornell-meshopt.gltf", doc, {{0, "cornell-meshopt.bin"}});
    }
    {
        // .gltf with a tagged fallback buffer holding the shifted geometry.
        Doc doc = meshopt(triangles, true);
        doc.json["buffers"][1]["extensions"] = tag;
        writeGltf(dir / "cornell-meshopt-fallback.gltf", doc,
                  {{0, "cornell-meshopt-fallback.bin"}, {1, "cornell-meshopt-fallback-data.bin"}});
    }
    {
        // GLB: the compressed data in the BIN chunk, an untagged placeholder
        // buffer 1 without uri; indices alternate between INDICES of u32
        // and TRIANGLES of u16.
        Doc doc = meshopt([](std::size_t m) { return m % 2 ? MeshoptOptions{} : MeshoptOptions{"INDICES", 4}; },
                          false);
        doc.json["buffers"][1] = {{"byteLength", doc.buffers[1].size()}};
        writeGlb(dir / "cornell-meshopt.glb", doc);
    }
}

}  // namespace

}  // namespace makecompressed

int main(int argc, char** argv) {
    using namespace makecompressed;
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_compressed DIR\n");
        return 2;
    }
    try {
        const fs::path dir = argv[1];
        fs::create_directories(dir / "broken");
        meshopt_encodeVertexVersion(0);  // 0xa0: EXT_meshopt_compression's vertex codec
        meshopt_encodeIndexVersion(1);   // 0xe1 (the spec, Appendix A)
        writeValidFiles(dir);
        writeFilterFile(dir);
        writeBrokenFiles(dir);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_compressed: %s\n", e.what());
        return 1;
    }
    return 0;
}
