// `strata render`: load -> BVH -> pack -> upload -> render -> write, the
// one-way flow of docs/architecture.md, with the options of the command line.
#pragma once
#include <string>
#include <vector>

#include "pack/gpu_scene.h"
#include "render/renderer.h"
#include "render/state.h"
#include "scene/scene.h"
#include "scene/environment.h"
#include "scene/view.h"
#include "stages/stages.h"

namespace strata {

// --frames FIRST:LAST[:STEP], --fps, --shutter-angle: an animation rendered
// frame by frame; frame f's shutter opens at f / fps and stays open for
// shutterAngle / 360 of a frame's time.
struct FrameRange {
    bool enabled = false;
    int first = 0, last = 0, step = 1;
    double fps = 24.0;
    double shutterAngle = 0.0;  // degrees in [0, 360]; 0: no motion blur
    double open(int frame) const { return frame / fps; }  // frame's shutter, seconds
    double close(int frame) const { return open(frame) + shutterAngle / 360.0 / fps; }
};

// `pattern` with its run of '#' replaced by the frame number, zero-padded to
// the run's length ("out_####.exr", 7 -> "out_0007.exr").
std::string frameFileName(const std::string& pattern, int frame);

struct RenderCommand {
    std::string scene;
    std::vector<std::string> outputs;   // .exr and/or .png
    std::vector<std::string> states;    // -o FILE.state: the accumulation (render/state.h)
    double checkpointEvery = 0.0;       // --checkpoint-every: rewrite the states this often (seconds)
    std::string resume;                 // --resume FILE.state: continue it
    std::uint32_t shard = 0, shards = 0;  // --shard I/K (shards 0: the whole render)
    bool dryRun = false;                // --dry-run: check the flags, say what would be done, stop
    RenderSettings settings;
    RenderTuning tuning;                // tests lower tuning.limits; the command line never sets it
    EnvironmentOptions env;             // --env / --env-color, --env-intensity, --env-rotate
    ViewOptions view;                   // --camera, --look-from, --look-at, --up, --fov
    std::string variant;                // --variant (KHR_materials_variants)
    std::string restrictPaths;          // --restrict-paths DIR (as given)
    Instancing instancing = Instancing::Auto;  // --instancing
    std::uint32_t textureMaxSize = 0;   // --texture-max-size (0: every texture whole)
    int device = -1;
    bool quiet = false;
    bool stats = false;
    std::string statsJson;
    bool validation = false;
    bool variance = false;              // EXR outputs get variance.R/G/B channels
    bool denoise = false;               // --denoise: R, G, B denoised (settings.aov is set too)
    bool denoiseFast = false;           // '--denoise fast': the a-trous filter, not the regression
    FrameRange frames;                  // --frames: outputs and statsJson hold a run of '#'
};

// What the command asks of the stages (stages/stages.h): its file,
// environment, loader options, view, BVH, reads and limits; with --frames
// the placements kept.
SceneRequest sceneRequest(const RenderCommand& cmd);

// The sample indices the command renders: its shard of [0, spp), or all.
SampleRange renderRange(const RenderCommand& cmd);

// Writes `film` to EXR and PNG `outputs`: the mean, with the AOV layers where
// the film has them, else with variance.R/G/B when `variance`; the EXR header
// gets `attributes`.
void writeFilmImages(const std::vector<std::string>& outputs, const Film& film, bool variance,
                     const std::vector<std::pair<std::string, int>>& attributes);

// Returns the process exit status. Throws strata::Error for bad input and
// vk::DeviceError for device failures; writes no output file on any error.
// `cmd` as the command line parsed and checked it (cli/checks.h): what
// the flags alone decide is not checked again.
int runRender(const RenderCommand& cmd);

}  // namespace strata
