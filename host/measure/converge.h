// `strata converge`: error against a reference as a function of spp and of
// device time, over several seeds, with the fitted convergence slopes and
// bias floor. Each seed is rendered once; the image at every listed spp is a
// checkpoint of that one progressive render (the samples of spp k are a
// prefix of those of spp n > k).
#pragma once
#include "scene/scene.h"
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "denoise/denoise.h"
#include "render/renderer.h"
#include "scene/environment.h"
#include "scene/view.h"

namespace strata {

struct ConvergeCommand {
    std::string scene;
    std::string reference;              // EXR; its size sets the render size
    std::vector<std::uint32_t> spp;     // ascending; default 1, 2, 4, ..., 256
    std::uint32_t seeds = 4;
    std::string report;                 // .csv or .json
    std::string plot;                   // .png, optional
    RenderSettings settings;            // width/height come from the reference; settings.sampler
    EnvironmentOptions env;             // --env / --env-color, --env-intensity, --env-rotate
    bool allSamplers = false;           // --sampler all: every sampler that suits the spp list
    ViewOptions view;                   // --camera, --look-from, --look-at, --up, --fov
    std::string variant;                // --variant (KHR_materials_variants)
    std::string restrictPaths;          // --restrict-paths DIR (as given)
    Instancing instancing = Instancing::Auto;  // --instancing
    std::uint32_t textureMaxSize = 0;   // --texture-max-size (0: every texture whole)
    int device = -1;
    bool validation = false;
    bool quiet = false;
    bool denoise = false;               // --denoise [fast]: each image denoised as well, measured apart
    DenoiseMethod method = DenoiseMethod::Nfor;
};

struct ConvergeLevel {
    std::uint32_t spp = 0;
    double seconds = 0.0;               // mean device seconds over seeds
    double relMse = 0.0, relMseStd = 0.0;   // mean and standard deviation over seeds
    double relMseTrimmed = 0.0;
    double rmse = 0.0;
    double efficiency = 0.0;            // 1 / (relMse * seconds)
};

struct ConvergeReport {
    std::vector<ConvergeLevel> levels;
    double slopeSpp = 0.0;              // d log relMSE / d log spp
    double slopeTime = 0.0;             // d log relMSE / d log seconds
    double biasFloor = 0.0;             // b^2 of relMSE(N) = b^2 + c / N
    double varianceConstant = 0.0;      // c
    double referenceFloor = 0.0;        // mean refVar / (ref^2 + eps): the floor the reference's own noise adds
    std::uint32_t seeds = 0;
    double eps = 1e-2;
    std::string sampler;                // the sampler's name, "+nfor" or "+fast" when denoised
    nlohmann::json toJson() const;
};

// Renders and measures; it writes nothing. One report, or with cmd.denoise
// two: the images as rendered, then denoised (the seconds then include the
// denoiser's device time).
std::vector<ConvergeReport> measureConvergence(const ConvergeCommand& cmd);

// `cmd` as the command line parsed and checked it (cli/checks.h): what
// the flags alone decide is not checked again.
int runConverge(const ConvergeCommand& cmd);

}  // namespace strata
