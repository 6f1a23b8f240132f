// The combinations of flags each command refuses, checked right after its
// flags are parsed (cli/commands.cpp) and before anything is read, loaded or
// opened: every check that needs the flags alone. What needs a file, the
// scene or the device stays with the command that runs (render/command.cpp,
// render/merge.cpp, measure/, denoise/command.cpp). Each throws
// strata::Error: one line, "strata: error: ..." or "FILE: error: ..." for a
// file named by a flag.
#pragma once
#include "cli/commands.h"
#include "cli/flags.h"

namespace strata::cli {

// The shared groups: --look-from/--look-at/--up; --aperture-blades,
// --animation, the lens and shutter with the wavefront integrator; --env
// with --env-color, --env-intensity/--env-rotate without either.
void checkViewFlags(const ViewOptions& view);
void checkLensFlags(const RenderSettings& s);
// --light-sampler, --noise-threshold and --min-spp: the tree and adaptive
// sampling on the megakernel only, the minimum within the cap.
void checkSamplingFlags(const RenderSettings& s, std::uint32_t cap);
void checkEnvFlags(const Parsed& parsed, const EnvironmentOptions& env);

// render and reference, after --frames has set the first frame's shutter
// (the shared groups too).
void checkRenderFlags(const Parsed& parsed, const RenderCommand& cmd);
void checkConvergeFlags(const ConvergeCommand& cmd);
void checkEdgesFlags(const EdgesCommand& cmd);
void checkBenchFlags(const BenchCommand& cmd);
void checkCompareFlags(const CompareArgs& args);
void checkDenoiseFlags(const DenoiseCommand& cmd);
void checkMergeFlags(const MergeCommand& cmd);

}  // namespace strata::cli
