// glTF animations (host/scene/gltf_animation.cpp, glTF 2.0 3.11 and
// appendix C): known answers of LINEAR, STEP and CUBICSPLINE sampling, the
// clamping outside the keys, the node's static TRS under the channels, the
// animation picked by name or index, and one error line for each kind of
// malformed animation. The models are built in memory (Builder).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "gltf_util.h"
#include "scene/gltf_animation.h"
#include "scene/gltf_internal.h"

TEST_SUITE_BEGIN("unit");

namespace {

using namespace strata;
using namespace strata::test;
using gltf::Animation;

const std::string kPath = "anim.gltf";
constexpr double kPi = 3.14159265358979323846;

// A tinygltf::Model made in memory: one buffer, a bufferView per accessor.
struct Builder {
    tinygltf::Model model;

    Builder() {
        model.buffers.emplace_back();
        model.nodes.resize(2);
        model.nodes[0].name = "Box";
        model.nodes[1].matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    }

    // An accessor of `data` (components of type T) as `type` elements.
    template <class T>
    int accessor(const std::vector<T>& data, int type, int componentType, bool normalized = false) {
        std::vector<unsigned char>& bytes = model.buffers[0].data;
        while (bytes.size() % 4 != 0) bytes.push_back(0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = bytes.size();
        view.byteLength = data.size() * sizeof(T);
        bytes.resize(bytes.size() + view.byteLength);
        if (!data.empty()) std::memcpy(bytes.data() + view.byteOffset, data.data(), view.byteLength);
        model.bufferViews.push_back(view);
        tinygltf::Accessor acc;
        acc.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
        acc.componentType = componentType;
        acc.normalized = normalized;
        acc.type = type;
        acc.count = data.size() / (type == TINYGLTF_TYPE_SCALAR ? 1 : type == TINYGLTF_TYPE_VEC3 ? 3 : 4);
        model.accessors.push_back(acc);
        return static_cast<int>(model.accessors.size()) - 1;
    }
    int floats(const std::vector<float>& data, int type) {
        return accessor(data, type, TINYGLTF_COMPONENT_TYPE_FLOAT);
    }

    // A channel of animation `animation` (made when missing) moving `path` of
    // `node` with a new sampler of FLOAT keys; returns the sampler.
    tinygltf::AnimationSampler& channel(std::size_t animation, int node, const std::string& path,
                                        const std::vector<float>& times, const std::vector<float>& values,
                                        const std::string& interpolation = "LINEAR") {
        if (model.animations.size() <= animation) model.animations.resize(animation + 1);
        tinygltf::Animation& a = model.animations[animation];
        tinygltf::AnimationSampler sampler;
        sampler.input = floats(times, TINYGLTF_TYPE_SCALAR);
        sampler.output = floats(values, path == "rotation" ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3);
        sampler.interpolation = interpolation;
        a.samplers.push_back(sampler);
        tinygltf::AnimationChannel c;
        c.sampler = static_cast<int>(a.samplers.size()) - 1;
        c.target_node = node;
        c.target_path = path;
        a.channels.push_back(c);
        return a.samplers.back();
    }

    Animation load(const std::string& select = "") const { return Animation::load(kPath, model, select); }
};

// A rotation about z by `angle` radians, (x, y, z, w).
std::vector<float> aboutZ(double angle) {
    return {0.0f, 0.0f, static_cast<float>(std::sin(angle / 2)), static_cast<float>(std::cos(angle / 2))};
}

std::vector<float> join(std::initializer_list<std::vector<float>> parts) {
    std::vector<float> out;
    for (const std::vector<float>& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

glm::dvec3 translationOf(const glm::dmat4& m) { return glm::dvec3(m[3]); }

// The angle about z of a matrix's x axis.
double angleOf(const glm::dmat4& m) { return std::atan2(m[0][1], m[0][0]); }

void checkMatrix(const glm::dmat4& actual, const glm::dmat4& expected) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) CHECK(actual[c][r] == doctest::Approx(expected[c][r]).epsilon(1e-6));
    }
}

// "Walk": node 0 ("Box", static rotation and scale) translated from (0, 0, 0)
// at t = 1 to (2, 4, 6) at t = 3.
Builder walk() {
    Builder b;
    b.model.nodes[0].rotation = {0.0, 0.0, std::sin(kPi / 4), std::cos(kPi / 4)};
    b.model.nodes[0].scale = {2.0, 2.0, 2.0};
    b.channel(0, 0, "translation", {1.0f, 3.0f}, {0, 0, 0, 2, 4, 6});
    b.model.animations[0].name = "Walk";
    return b;
}

// The message of the error loading `b`'s animation `select` throws; empty
// when it loads.
std::string loadError(const Builder& b, const std::string& select = "") {
    CerrCapture capture;
    try {
        b.load(select);
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST_CASE("animation: LINEAR translation is the midpoint at mid-time, held before the first and after the last key") {
    const Builder b = walk();
    const Animation a = b.load();
    CHECK(a.label == "animation 0 (\"Walk\")");
    CHECK(a.start == 1.0);
    CHECK(a.end == 3.0);
    CHECK(a.animates(0));
    CHECK_FALSE(a.animates(1));
    CHECK_FALSE(a.steps(0));
    CHECK_FALSE(a.curves(0));
    const glm::dvec4 q(0.0, 0.0, std::sin(kPi / 4), std::cos(kPi / 4));
    // The static rotation and scale stay under the animated translation.
    checkMatrix(a.local(b.model, 0, 2.0), gltf::trs({1, 2, 3}, q, glm::dvec3(2.0)));
    checkMatrix(a.local(b.model, 0, 2.5), gltf::trs({1.5, 3, 4.5}, q, glm::dvec3(2.0)));
    checkMatrix(a.local(b.model, 0, -4.0), gltf::trs({0, 0, 0}, q, glm::dvec3(2.0)));
    checkMatrix(a.local(b.model, 0, 9.0), gltf::trs({2, 4, 6}, q, glm::dvec3(2.0)));
    checkMatrix(a.local(b.model, 0, 3.0, true), gltf::trs({2, 4, 6}, q, glm::dvec3(2.0)));
    // A node no channel targets keeps its matrix.
    checkMatrix(a.local(b.model, 1, 2.0), gltf::nodeTransform(kPath, b.model, 1));
}

TEST_CASE("animation: LINEAR rotation slerps on the shorter arc, 0 to 90 degrees about z is 22.5 at a quarter") {
    for (const float sign : {1.0f, -1.0f}) {  // q and -q: the same key rotation
        CAPTURE(sign);
        Builder b;
        std::vector<float> end = aboutZ(kPi / 2);
        for (float& c : end) c *= sign;
        b.channel(0, 0, "rotation", {0.0f, 1.0f}, join({aboutZ(0.0), end}));
        const Animation a = b.load();
        CHECK(angleOf(a.local(b.model, 0, 0.25)) == doctest::Approx(kPi / 8).epsilon(1e-6));
        CHECK(angleOf(a.local(b.model, 0, 0.5)) == doctest::Approx(kPi / 4).epsilon(1e-6));
        CHECK(angleOf(a.local(b.model, 0, 1.0)) == doctest::Approx(kPi / 2).epsilon(1e-6));
    }
    // Nearly parallel keys (normalised lerp): 0.01 degrees apart, half of it at mid-time.
    Builder b;
    const double tiny = 0.01 * kPi / 180;
    b.channel(0, 0, "rotation", {0.0f, 1.0f}, join({aboutZ(0.0), aboutZ(tiny)}));
    CHECK(angleOf(b.load().local(b.model, 0, 0.5)) == doctest::Approx(tiny / 2).epsilon(1e-4));
}

TEST_CASE("animation: STEP holds each key until the next, where the limit from the left is the old value") {
    Builder b;
    b.channel(0, 0, "translation", {0.0f, 1.0f, 2.0f}, {10, 0, 0, 20, 0, 0, 30, 0, 0}, "STEP");
    const Animation a = b.load();
    CHECK(a.steps(0));
    CHECK_FALSE(a.curves(0));
    const auto x = [&](double t, bool leftLimit) { return translationOf(a.local(b.model, 0, t, leftLimit)).x; };
    CHECK(x(-1.0, false) == 10.0);
    CHECK(x(0.0, true) == 10.0);
    CHECK(x(0.5, false) == 10.0);
    CHECK(x(0.999, false) == 10.0);
    CHECK(x(1.0, false) == 20.0);
    CHECK(x(1.0, true) == 10.0);
    CHECK(x(1.5, true) == 20.0);
    CHECK(x(2.0, true) == 20.0);
    CHECK(x(2.0, false) == 30.0);
    CHECK(x(7.0, false) == 30.0);
}

TEST_CASE("animation: CUBICSPLINE is the Hermite spline of appendix C, tangents scaled by the key interval") {
    // Zero tangents: the mean of the two values halfway.
    Builder flat;
    flat.channel(0, 0, "translation", {0.0f, 2.0f}, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 8, -2, 0, 0, 0},
                 "CUBICSPLINE");
    const Animation a = flat.load();
    CHECK(a.curves(0));
    const glm::dvec3 mid = translationOf(a.local(flat.model, 0, 1.0));
    CHECK(mid.x == doctest::Approx(2.0));
    CHECK(mid.y == doctest::Approx(4.0));
    CHECK(mid.z == doctest::Approx(-1.0));
    // p(t) = t^3 from keys at 1, 2, 4 with p'(t) = 3t^2 as both tangents: exact between keys.
    // The first key's in-tangent and the last one's out-tangent are never used: 999.
    Builder cubic;
    std::vector<float> values;
    for (const float t : {1.0f, 2.0f, 4.0f}) {
        const float p = t * t * t, d = 3 * t * t;
        values.insert(values.end(), {t == 1.0f ? 999.0f : d, 0, 0, p, 0, 0, t == 4.0f ? 999.0f : d, 0, 0});
    }
    cubic.channel(0, 0, "translation", {1.0f, 2.0f, 4.0f}, values, "CUBICSPLINE");
    const Animation c = cubic.load();
    for (const double t : {1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 3.75, 4.0}) {
        CAPTURE(t);
        CHECK(translationOf(c.local(cubic.model, 0, t)).x == doctest::Approx(t * t * t));
    }
    CHECK(translationOf(c.local(cubic.model, 0, 0.0)).x == doctest::Approx(1.0));
    CHECK(translationOf(c.local(cubic.model, 0, 5.0)).x == doctest::Approx(64.0));
    // A rotation spline is normalised: 0 and 90 degrees with zero tangents give 45 halfway.
    Builder turn;
    const std::vector<float> zero(4, 0.0f);
    turn.channel(0, 0, "rotation", {0.0f, 1.0f}, join({zero, aboutZ(0.0), zero, zero, aboutZ(kPi / 2), zero}),
                 "CUBICSPLINE");
    CHECK(angleOf(turn.load().local(turn.model, 0, 0.5)) == doctest::Approx(kPi / 4).epsilon(1e-6));
}

TEST_CASE("animation: rotations stored as normalized UNSIGNED_SHORT and BYTE") {
    Builder b;
    b.channel(0, 0, "rotation", {0.0f, 1.0f}, join({aboutZ(0.0), aboutZ(0.0)}));
    tinygltf::AnimationSampler& s = b.model.animations[0].samplers[0];
    // 46341 / 65535 = 0.70712...: 90 degrees about z once normalised.
    s.output = b.accessor(std::vector<std::uint16_t>{0, 0, 0, 65535, 0, 0, 46341, 46341}, TINYGLTF_TYPE_VEC4,
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true);
    CHECK(angleOf(b.load().local(b.model, 0, 1.0)) == doctest::Approx(kPi / 2).epsilon(1e-6));
    s.output = b.accessor(std::vector<std::int8_t>{0, 0, 0, 127, 0, 0, -127, -127}, TINYGLTF_TYPE_VEC4,
                          TINYGLTF_COMPONENT_TYPE_BYTE, true);
    CHECK(angleOf(b.load().local(b.model, 0, 1.0)) == doctest::Approx(kPi / 2).epsilon(1e-6));
    CHECK(angleOf(b.load().local(b.model, 0, 0.5)) == doctest::Approx(kPi / 4).epsilon(1e-6));
}

TEST_CASE("animation: picked by name or index, the first by default, with its own timeline and key times") {
    Builder b = walk();
    b.channel(1, 0, "scale", {0.5f, 1.5f, 2.0f, 4.0f}, {1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4});
    b.model.animations[1].name = "Run";
    CHECK(b.load().label == "animation 0 (\"Walk\")");
    CHECK(b.load("0").label == "animation 0 (\"Walk\")");
    for (const char* select : {"Run", "1"}) {
        const Animation run = b.load(select);
        CHECK(run.label == "animation 1 (\"Run\")");
        CHECK(run.start == 0.5);
        CHECK(run.end == 4.0);
        // Scale animated; the node's static rotation (90 degrees about z) and translation (none) kept.
        const glm::dmat4 m = run.local(b.model, 0, 1.75);
        CHECK(translationOf(m) == glm::dvec3(0.0));
        CHECK(glm::length(glm::dvec3(m[0])) == doctest::Approx(2.5));
        CHECK(angleOf(m) == doctest::Approx(kPi / 2));
        std::vector<double> times;
        run.keyTimes(0, 0.5, 4.0, times);
        CHECK(times == std::vector<double>{1.5, 2.0});
        times.clear();
        run.keyTimes(1, 0.0, 9.0, times);
        CHECK(times.empty());
    }
    // An unknown name lists the first four animations.
    for (std::size_t i = 2; i < 6; ++i) b.channel(i, 0, "scale", {0.0f}, {1, 1, 1});
    CHECK(loadError(b, "Jump").find("(the file has animation 0 (\"Walk\"), animation 1 (\"Run\"), animation 2, "
                                    "animation 3 and 2 more)") != std::string::npos);
}

TEST_CASE("animation: a weights channel is skipped with one warning per animation") {
    Builder b;
    b.channel(0, 0, "weights", {0.0f, 1.0f}, {0, 0, 0, 1, 1, 1});
    b.channel(0, 0, "weights", {0.0f, 1.0f}, {0, 0, 0, 1, 1, 1});
    CerrCapture capture;
    const Animation a = b.load();
    CHECK(a.channels.empty());
    CHECK(a.start == 0.0);
    CHECK(a.end == 0.0);
    CHECK_FALSE(a.animates(0));
    CHECK(capture.text() == kPath + ": warning: animation 0: morph-target weight animation is not rendered; "
                                    "the weights stay static\n");
}

TEST_CASE("animation: each malformed animation is one error line naming the file and the problem") {
    struct Case {
        std::string expected;
        std::function<void(Builder&)> change;
        std::string select;
    };
    const auto sampler = [](Builder& b) -> tinygltf::AnimationSampler& { return b.model.animations[0].samplers[0]; };
    const auto channel = [](Builder& b) -> tinygltf::AnimationChannel& { return b.model.animations[0].channels[0]; };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<Case> cases{
        {"no animations in the file", [](Builder& b) { b.model.animations.clear(); }, ""},
        {"no animation named \"Jump\" (the file has animation 0 (\"Walk\"))", [](Builder&) {}, "Jump"},
        {"animation 7 does not exist (the file has animation 0 (\"Walk\"))", [](Builder&) {}, "7"},
        {"animation 0 (\"Walk\") channel 0: sampler 5 does not exist (1 samplers)",
         [&](Builder& b) { channel(b).sampler = 5; }, ""},
        {"animation 0 (\"Walk\") channel 0 has no target node", [&](Builder& b) { channel(b).target_node = -1; }, ""},
        {"channel 0: target node 9 does not exist (2 nodes)", [&](Builder& b) { channel(b).target_node = 9; }, ""},
        {"channel 0 targets node 1, which has a matrix", [&](Builder& b) { channel(b).target_node = 1; }, ""},
        {"channel 0: target path \"color\" is not translation, rotation, scale or weights",
         [&](Builder& b) { channel(b).target_path = "color"; }, ""},
        {"channel 1: node 0 (\"Box\") translation is animated by an earlier channel too",
         [](Builder& b) { b.channel(0, 0, "translation", {0.0f}, {1, 1, 1}); }, ""},
        {"sampler 0: interpolation \"QUADRATIC\" is not LINEAR, STEP or CUBICSPLINE",
         [&](Builder& b) { sampler(b).interpolation = "QUADRATIC"; }, ""},
        {"animation 0 (\"Walk\") sampler 0 input: accessor 99 does not exist (2 accessors)",
         [&](Builder& b) { sampler(b).input = 99; }, ""},
        {"sampler 0 output: accessor -1 does not exist", [&](Builder& b) { sampler(b).output = -1; }, ""},
        {"(animation 0 (\"Walk\") sampler 0 input) is UNSIGNED_BYTE SCALAR; expected FLOAT SCALAR",
         [&](Builder& b) {
             sampler(b).input = b.accessor(std::vector<std::uint8_t>{1, 3}, TINYGLTF_TYPE_SCALAR,
                                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
         }, ""},
        {"sampler 0 input has no key times",
         [&](Builder& b) { sampler(b).input = b.floats({}, TINYGLTF_TYPE_SCALAR); }, ""},
        {"sampler 0 input: key 2 time 1 is not greater than key 1 time 1; key times must be strictly increasing",
         [&](Builder& b) { sampler(b).input = b.floats({0.0f, 1.0f, 1.0f}, TINYGLTF_TYPE_SCALAR); }, ""},
        {"sampler 0 input: key 1 time nan is not finite",
         [&](Builder& b) { sampler(b).input = b.floats({0.0f, nan}, TINYGLTF_TYPE_SCALAR); }, ""},
        {"sampler 0: output has 2 values for 3 key times; expected 3",
         [&](Builder& b) { sampler(b).input = b.floats({0.0f, 1.0f, 2.0f}, TINYGLTF_TYPE_SCALAR); }, ""},
        {"sampler 0: output has 2 values for 2 key times; expected 6 (in-tangent, value, out-tangent per key)",
         [&](Builder& b) { sampler(b).interpolation = "CUBICSPLINE"; }, ""},
        {"(animation 0 (\"Walk\") sampler 0 output) is FLOAT VEC4; expected FLOAT VEC3",
         [&](Builder& b) { sampler(b).output = b.floats({0, 0, 0, 1, 0, 0, 0, 1}, TINYGLTF_TYPE_VEC4); }, ""},
        {"sampler 0 output) is UNSIGNED_SHORT but not normalized",
         [&](Builder& b) {
             channel(b).target_path = "rotation";
             sampler(b).output = b.accessor(std::vector<std::uint16_t>{0, 0, 0, 1, 0, 0, 0, 1}, TINYGLTF_TYPE_VEC4,
                                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
         }, ""},
        {"sampler 0 output: value 1 is not finite",
         [&](Builder& b) { sampler(b).output = b.floats({0, 0, 0, 1, nan, 1}, TINYGLTF_TYPE_VEC3); }, ""},
        {"sampler 0 output: rotation key 1 has length 0",
         [&](Builder& b) {
             channel(b).target_path = "rotation";
             sampler(b).output = b.floats({0, 0, 0, 1, 0, 0, 0, 0}, TINYGLTF_TYPE_VEC4);
         }, ""},
    };
    CHECK(loadError(walk()).empty());
    for (const Case& c : cases) {
        CAPTURE(c.expected);
        Builder b = walk();
        c.change(b);
        const std::string message = loadError(b, c.select);
        CHECK(isOneLine(message));
        CHECK(message.rfind(kPath + ": error: ", 0) == 0);
        CHECK(message.find(c.expected) != std::string::npos);
        if (message.find(c.expected) == std::string::npos) MESSAGE(message);
    }
}
