// The environment light of the command line (--env FILE | --env-color R,G,B,
// --env-intensity S, --env-rotate DEG) turned into a checked Environment
// (scene.h states the mapping convention).
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata {

struct RgbImage;  // image/image_io.h

struct EnvironmentOptions {
    std::string file;            // --env: equirectangular .hdr / .exr (anything OpenImageIO reads)
    bool hasColor = false;       // --env-color given
    glm::vec3 color{0.0f};       // constant radiance, components >= 0, not all 0
    float intensity = 1.0f;      // --env-intensity, > 0
    double rotateDegrees = 0.0;  // --env-rotate, about +Y (any finite angle)
    std::string restrictPaths;   // --restrict-paths (canonical): `file` must resolve into it
    bool given() const { return !file.empty() || hasColor; }
};

// Reads and checks the map when there is one: every texel finite and >= 0,
// not all black. Throws strata::Error ("<file>: error: ...") on bad input.
Environment makeEnvironment(const EnvironmentOptions& options);
// The same checks of a map already read (`options.file` names it).
Environment environmentFromImage(const EnvironmentOptions& options, RgbImage image);

// loadGltf with `load` plus the command line's environment: a scene lit only
// by the environment is valid. The scene is checked before the map is read.
Scene loadSceneWithEnvironment(const std::string& path, const EnvironmentOptions& options, LoadOptions load = {});
// The same of the file's bytes, already read (`path` names it).
Scene loadSceneWithEnvironment(const std::string& path, const std::vector<unsigned char>& bytes,
                               const EnvironmentOptions& options, LoadOptions load = {});

}  // namespace strata
