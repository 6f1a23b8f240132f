// `strata denoise IN.exr -o OUT.exr [-o OUT.png] [--method nfor|fast]`, and
// what it shares with `strata render --denoise`: the denoiser's input from
// the AOV images, and the outputs (the denoised R, G, B; the image as
// rendered in noisy.R/G/B; the AOV layers kept).
#pragma once
#include <string>
#include <vector>

#include "denoise/denoise.h"
#include "image/aov.h"

namespace strata {

struct DenoiseCommand {
    std::string input;                  // an EXR with the AOV layers (render --aov)
    std::vector<std::string> outputs;   // .exr and/or .png
    DenoiseMethod method = DenoiseMethod::Nfor;
    int device = -1;
    bool validation = false;
    bool quiet = false;
};

const char* denoiseMethodName(DenoiseMethod method);

DenoiseInput denoiseInput(const AovImages& aov);

// Writes `denoised` to every path (all or none); EXR files also get
// noisy.R/G/B (aov.color) and the AOV layers.
void writeDenoised(const std::vector<std::string>& paths, const AovImages& aov, const std::vector<float>& denoised);

// Returns the exit status; throws strata::Error for bad input (a file
// without a layer the denoiser needs names it), vk::DeviceError for the device.
// `cmd` as the command line parsed and checked it (cli/checks.h): what
// the flags alone decide is not checked again.
int runDenoise(const DenoiseCommand& cmd);

}  // namespace strata
