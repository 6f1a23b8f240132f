// Shared by the glTF loader tests (test_gltf.cpp, test_gltf_geometry.cpp):
// test data paths, capturing std::cerr, and checks of loaded triangles.
#pragma once
#include <iostream>
#include <sstream>
#include <string>

#include <doctest/doctest.h>
#include <glm/glm.hpp>

#include "scene/scene.h"
#include "util/error.h"

namespace strata::test {

inline std::string dataPath(const std::string& relative) {
    return std::string(STRATA_SOURCE_DIR) + "/tests/data/" + relative;
}

// Collects what is written to std::cerr while alive.
class CerrCapture {
public:
    CerrCapture() : old_(std::cerr.rdbuf(buffer_.rdbuf())) {}
    ~CerrCapture() { std::cerr.rdbuf(old_); }
    CerrCapture(const CerrCapture&) = delete;
    CerrCapture& operator=(const CerrCapture&) = delete;
    std::string text() const { return buffer_.str(); }

private:
    std::ostringstream buffer_;
    std::streambuf* old_;
};

inline std::string str(const glm::vec3& v) {
    std::ostringstream s;
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}

#define CHECK_VEC(actual, expected)                                                           \
    CHECK_MESSAGE(glm::distance(glm::vec3(actual), glm::vec3(expected)) < 1e-5f, str(actual), \
                  " != ", str(expected))

inline void checkTriangle(const Triangle& t, glm::vec3 v0, glm::vec3 v1, glm::vec3 v2) {
    CHECK_VEC(t.v[0], v0);
    CHECK_VEC(t.v[1], v1);
    CHECK_VEC(t.v[2], v2);
}

inline void checkNormals(const Triangle& t, glm::vec3 n0, glm::vec3 n1, glm::vec3 n2) {
    CHECK_VEC(t.n[0], n0);
    CHECK_VEC(t.n[1], n1);
    CHECK_VEC(t.n[2], n2);
}

inline void checkNormals(const Triangle& t, glm::vec3 n) { checkNormals(t, n, n, n); }

// The counter-clockwise (front) side agrees with every vertex normal.
inline void checkFrontFaceMatchesNormals(const Triangle& t) {
    const glm::vec3 g = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
    for (const glm::vec3& n : t.n) CHECK(glm::dot(g, n) > 0.0f);
}

inline bool isOneLine(const std::string& s) { return s.find('\n') == std::string::npos && !s.empty(); }

// The message of the strata::Error that loading `path` throws; empty when it
// loads. What the loader writes to std::cerr is swallowed.
inline std::string loadError(const std::string& path) {
    CerrCapture capture;
    try {
        loadGltf(path);
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

}  // namespace strata::test
