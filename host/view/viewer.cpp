#include "view/viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <sstream>

#include "denoise/command.h"
#include "denoise/denoise.h"
#include "image/aov.h"
#include "image/image_io.h"
#include "render/sampler_kind.h"
#include "util/error.h"
#include "util/module.h"
#include "view/api.h"
#include "view/camera_control.h"
#include "vk/check.h"
#include "vk/context.h"

namespace strata {
namespace {

using Clock = std::chrono::steady_clock;

// The viewer's dispatches cover at most 128 x 128 pixels, so that a sample
// slower than a frame splits into runs of tiles (RenderTuning::splitSamples).
constexpr std::uint32_t kViewTile = 128;
constexpr double kRefreshSeconds = 0.2;

const view::Api& windowModule() {
    static std::string error;
    static const auto* api = static_cast<const view::Api*>(loadModuleApi(
        {"STRATA_VIEW_MODULE", STRATA_VIEW_MODULE, "libstrata_view.so", "strata_view_api", view::kApiVersion,
         "strata was built without its window module (GLFW and Dear ImGui: libglfw3-dev, libimgui-dev)",
         "window module"},
        error));
    if (!api) throw Error("strata: error: strata view cannot open windows: " + error);
    return *api;
}

std::string vecText(glm::vec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g", double(v.x), double(v.y), double(v.z));
    return buf;
}

// The render command of the current view: view's words (`args`) but its
// own flags and those the view sets (the camera, the size, the depth, the
// spp it stops at), then those from the view.
std::string renderCommandLine(const ViewCommand& cmd, const CameraControl& control, const RenderSettings& s) {
    static const std::vector<std::string> dropped = {"--exit-after-spp", "--screenshot", "--script", "--look-from",
                                                     "--look-at",        "--up",         "--fov",    "--camera",
                                                     "--width",          "--height",     "--max-depth", "--spp"};
    std::string line = "strata render";
    for (std::size_t i = 0; i < cmd.args.size(); ++i) {
        const std::string& a = cmd.args[i];
        const std::string name = a.substr(0, a.find('='));
        if (std::find(dropped.begin(), dropped.end(), name) != dropped.end()) {
            if (name == a) ++i;  // and its value, when it is the next word
            continue;
        }
        line += " " + a;
    }
    const Camera& c = control.camera();
    char fov[32];
    std::snprintf(fov, sizeof fov, "%.9g", double(c.yfov) * 180.0 / 3.14159265358979323846);
    line += " --look-from " + vecText(c.position) + " --look-at " + vecText(control.target()) + " --up " +
            vecText(c.up) + " --fov " + fov + " --width " + std::to_string(s.width) + " --height " +
            std::to_string(s.height) + " --max-depth " + std::to_string(s.maxDepth) + " --spp " +
            std::to_string(s.spp);
    return line;
}

// The image the window shows, linear RGB before exposure, from the film
// (and, for the denoised view, the device's denoiser).
std::vector<float> viewImage(const vk::Context& ctx, const Film& film, int view) {
    if (view == view::kViewColor || !film.aov) return film.mean();
    const AovImages aov = aovImages(film);
    const std::size_t n = film.pixels();
    std::vector<float> out(n * 3);
    switch (view) {
        case view::kViewAlbedo: return aov.albedo;
        case view::kViewNormal:
            for (std::size_t i = 0; i < n * 3; ++i) out[i] = 0.5f * aov.normal[i] + 0.5f;
            return out;
        case view::kViewDepth: {
            float far = 0.0f;
            for (float d : aov.depth) far = std::max(far, std::isfinite(d) ? d : 0.0f);
            for (std::size_t i = 0; i < n; ++i)
                out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = far > 0.0f ? aov.depth[i] / far : 0.0f;
            return out;
        }
        default: return denoise(ctx, denoiseInput(aov), DenoiseMethod::Fast).rgb;
    }
}

int viewByName(const std::string& name) {
    for (int v = 0; v < view::kViewCount; ++v)
        if (name == view::kViewNames[v]) return v;
    return -1;
}

class Viewer {
public:
    Viewer(const ViewCommand& cmd, const view::Api& api) : cmd_(cmd), api_(api) {}
    ~Viewer() {
        if (cmd_.stats && frames_.size() > 1) {
            std::vector<double> gaps;
            for (std::size_t i = 1; i < frames_.size(); ++i)
                gaps.push_back(std::chrono::duration<double, std::milli>(frames_[i] - frames_[i - 1]).count());
            std::sort(gaps.begin(), gaps.end());
            std::fprintf(stderr, "strata view: %zu frames, %.0f ms between frames (median), %.0f ms at most\n",
                         frames_.size(), gaps[gaps.size() / 2], gaps.back());
        }
        if (window_) {
            api_.detach(window_);
            if (ctx_) ctx_->destroySurface();
            api_.close(window_);
        }
    }
    int run();

private:
    void restart() {
        if (!restart_ && !waitingImage_) changed_ = Clock::now();
        restart_ = true;
    }
    void selectCamera(int k);
    void setView(int v);
    void printCommand() {
        std::printf("%s\n", renderCommandLine(cmd_, *control_, settings_).c_str());
        std::fflush(stdout);
    }
    void nextCamera() {
        if (!cameras_.empty()) selectCamera((panel_.camera + 1) % int(cameras_.size()));
    }
    bool frame(double waitSeconds);  // false: stop the render in progress
    void show(Film film, std::uint32_t spp);
    void redisplay();
    void runScript();
    void saveImages();
    void writeScreenshot(const std::string& path);

    const ViewCommand& cmd_;
    const view::Api& api_;
    view::Window* window_ = nullptr;
    std::unique_ptr<vk::Context> ctx_;
    RenderSettings settings_;
    std::vector<Camera> cameras_;
    std::unique_ptr<CameraControl> control_, home_;
    view::Panel panel_;
    Film film_;               // the accumulation shown
    std::uint32_t spp_ = 0;   // its spp
    bool haveImage_ = false;
    std::vector<float> linear_;        // viewImage, before exposure
    std::vector<std::uint8_t> rgba_;   // what the window shows
    int shownWidth_ = 0, shownHeight_ = 0;
    bool restart_ = false, quit_ = false;
    bool waitingImage_ = true, firstImage_ = true;  // --stats: the latency of the next image
    Clock::time_point changed_;                     // the window opened, or the last change
    std::size_t scriptStep_ = 0;
    bool waitResize_ = false;
    Clock::time_point started_, lastFrame_, refreshed_;
    double renderSeconds_ = 0.0;
    std::uint64_t samples_ = 0;
    std::string sceneStem_;
    std::string captureTo_;                  // --script's window FILE: the next frame, panel included
    std::vector<Clock::time_point> frames_;  // --stats: when each frame was shown
    glm::vec3 center_{0.0f};
    double radius_ = 1.0;
};

void Viewer::redisplay() {
    const float scale = std::exp2(panel_.exposure);
    rgba_.assign(linear_.size() / 3 * 4, 255);
    static const Srgb8Table encode;
    for (std::size_t i = 0, n = linear_.size() / 3; i < n; ++i)
        for (int c = 0; c < 3; ++c) rgba_[4 * i + c] = encode(linear_[3 * i + c] * scale);
}

void Viewer::show(Film film, std::uint32_t spp) {
    if (waitingImage_ && cmd_.stats) {
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - changed_).count();
        std::fprintf(stderr, "strata view: %s image (%u spp) %.0f ms after %s\n", firstImage_ ? "first" : "new",
                     spp, ms, firstImage_ ? "the window opened" : "the change");
    }
    waitingImage_ = false;
    firstImage_ = false;
    film_ = std::move(film);
    spp_ = spp;
    haveImage_ = true;
    shownWidth_ = film_.width;
    shownHeight_ = film_.height;
    linear_ = viewImage(*ctx_, film_, panel_.view);
    redisplay();
}

void Viewer::writeScreenshot(const std::string& path) {
    std::vector<float> rgb = linear_;
    const float scale = std::exp2(panel_.exposure);
    if (scale != 1.0f)
        for (float& v : rgb) v *= scale;
    writeImages({path}, shownWidth_, shownHeight_, rgb);
}

void Viewer::saveImages() {
    if (!haveImage_) return;
    const std::string stem = sceneStem_ + "-view-" + std::to_string(spp_) + "spp";
    const std::vector<std::string> outputs = {stem + ".exr", stem + ".png"};
    writeFilmImages(outputs, film_, false, {});
    panel_.status = "wrote " + outputs[0] + " and " + outputs[1];
    std::fprintf(stderr, "strata: %s\n", panel_.status.c_str());
}

void Viewer::runScript() {
    while (scriptStep_ < cmd_.script.size() && haveImage_ && !restart_ && !waitResize_) {
        const ViewScriptStep& step = cmd_.script[scriptStep_];
        if (spp_ < step.spp) return;
        ++scriptStep_;
        std::string words = step.action;
        for (const std::string& a : step.args) words += " " + a;
        std::printf("strata view: %u spp at %dx%d: %s\n", spp_, shownWidth_, shownHeight_, words.c_str());
        std::fflush(stdout);
        const auto number = [&](std::size_t k) { return std::stod(step.args.at(k)); };
        if (step.action == "orbit") control_->orbit(number(0), number(1), settings_.height), restart();
        else if (step.action == "pan") control_->pan(number(0), number(1), settings_.height), restart();
        else if (step.action == "zoom") control_->zoom(number(0)), restart();
        else if (step.action == "camera") nextCamera();
        else if (step.action == "screenshot") writeScreenshot(step.args.at(0));
        else if (step.action == "window") captureTo_ = step.args.at(0);
        else if (step.action == "view") setView(viewByName(step.args.at(0)));
        else if (step.action == "print") printCommand();
        else if (step.action == "close") api_.requestClose(window_);
        else if (step.action == "resize") {
            api_.requestSize(window_, int(number(0)), int(number(1)));
            waitResize_ = true;
        }
    }
}

bool Viewer::frame(double waitSeconds) {
    view::Input in;
    api_.poll(window_, waitSeconds, in);
    const auto now = Clock::now();
    if (cmd_.stats) frames_.push_back(now);
    const double dt = std::chrono::duration<double>(now - lastFrame_).count();
    lastFrame_ = now;
    if (in.close) quit_ = true;
    if (in.width > 0 && in.height > 0 && (in.width != settings_.width || in.height != settings_.height)) {
        settings_.width = in.width;
        settings_.height = in.height;
        waitResize_ = false;
        restart();
    }
    if (in.orbitX != 0 || in.orbitY != 0) control_->orbit(in.orbitX, in.orbitY, settings_.height), restart();
    if (in.panX != 0 || in.panY != 0) control_->pan(in.panX, in.panY, settings_.height), restart();
    if (in.zoom != 0) control_->zoom(in.zoom), restart();
    const glm::vec3 fly(in.fly[0], in.fly[1], in.fly[2]);
    if (fly != glm::vec3(0.0f)) control_->fly(fly, std::min(dt, 0.25)), restart();
    if (in.resetView) *control_ = *home_, restart();
    if (in.nextCamera) nextCamera();
    if (in.save) saveImages();
    if (in.printCommand) printCommand();
    runScript();

    // The panel: its edits apply at the next frame.
    const view::Panel before = panel_;
    panel_.spp = spp_;
    panel_.sppCap = settings_.spp;
    panel_.seconds = renderSeconds_;
    panel_.samplesPerSecond = renderSeconds_ > 0 ? double(samples_) / renderSeconds_ : 0.0;
    const std::vector<std::uint8_t> black(std::size_t(std::max(settings_.width, 1)) * std::max(settings_.height, 1) * 4, 0);
    const bool shown = !rgba_.empty();
    std::vector<std::uint8_t> captured;
    int cw = 0, ch = 0;
    const std::string error = api_.present(window_, shown ? rgba_.data() : black.data(),
                                           shown ? shownWidth_ : settings_.width, shown ? shownHeight_ : settings_.height,
                                           panel_, true, captureTo_.empty() ? nullptr : &captured, &cw, &ch);
    if (!error.empty()) throw vk::DeviceError("strata view: " + error);
    if (!captureTo_.empty() && !captured.empty()) {  // the window as shown, panel included
        std::vector<std::uint8_t> rgb(std::size_t(cw) * ch * 3);
        for (std::size_t i = 0; i < std::size_t(cw) * ch; ++i)
            for (int c = 0; c < 3; ++c) rgb[3 * i + c] = captured[4 * i + c];
        writePng8(captureTo_, cw, ch, rgb);
        captureTo_.clear();
    }
    if (panel_.maxDepth != before.maxDepth) settings_.maxDepth = std::uint32_t(panel_.maxDepth), restart();
    if (panel_.view != before.view) setView(panel_.view);
    if (panel_.exposure != before.exposure && haveImage_) redisplay();
    if (panel_.save) saveImages();
    if (panel_.printCommand) printCommand();
    if (panel_.camera != before.camera) selectCamera(panel_.camera);
    return !restart_ && !quit_;
}

void Viewer::setView(int v) {
    panel_.view = v;
    const bool needsAov = v != view::kViewColor;
    if (needsAov && settings_.integrator == IntegratorKind::Wavefront) {
        panel_.view = view::kViewColor;
        panel_.status = "the wavefront integrator keeps no AOVs: --integrator megakernel shows them";
    } else if (needsAov && !settings_.aov) {
        settings_.aov = true, restart();  // the AOV sums from the next accumulation on
    } else if (haveImage_) {
        linear_ = viewImage(*ctx_, film_, panel_.view), redisplay();
    }
}

void Viewer::selectCamera(int k) {
    if (k < 0 || std::size_t(k) >= cameras_.size()) return;
    panel_.camera = k;
    *control_ = CameraControl(cameras_[std::size_t(k)], orbitTarget(cameras_[std::size_t(k)], center_, radius_), radius_);
    restart();
}

int Viewer::run() {
    // Load first: a scene render refuses is one line before any window.
    SceneRequest request = sceneRequest(static_cast<const RenderCommand&>(cmd_));
    request.camera->width = cmd_.settings.width;
    request.camera->height = cmd_.settings.height;
    HostScene host = prepareScene(request);
    sceneStem_ = std::filesystem::path(cmd_.scene).stem().string();
    settings_ = cmd_.settings;

    std::string error = api_.open(settings_.width, settings_.height, "strata view: " + cmd_.scene, &window_);
    if (!error.empty()) throw Error("strata: error: strata view: " + error);
    changed_ = Clock::now();
    vk::ContextOptions options{cmd_.device, cmd_.validation};
    options.instanceExtensions = api_.instanceExtensions(window_);
    options.makeSurface = [&](VkInstance instance) {
        VkSurfaceKHR surface = VK_NULL_HANDLE;
        const std::string why = api_.createSurface(window_, instance, &surface);
        if (!why.empty()) throw Error("strata: error: strata view: " + why);
        return surface;
    };
    ctx_ = std::make_unique<vk::Context>(options);
    if (!cmd_.quiet)
        std::fprintf(stderr, "strata: device %u: %s (%s, %s)\n", ctx_->info.index, ctx_->info.name.c_str(),
                     ctx_->info.type.c_str(), ctx_->info.driver.c_str());
    const bool tree = !host.gpu.lightTree.empty();
    center_ = glm::vec3(host.gpu.sceneCenter);
    radius_ = host.gpu.sceneRadius;
    const DeviceScene dev = uploadPrepared(*ctx_, request, host.gpu);
    error = api_.attach(window_, view::Device{ctx_->instance, ctx_->physical, ctx_->device, ctx_->queueFamily,
                                              ctx_->queue, ctx_->surface});
    if (!error.empty()) throw vk::DeviceError("strata view: " + error);

    cameras_ = host.scene.cameras;
    const Camera start = host.camera;
    const glm::vec3 target = cmd_.view.lookAt ? *cmd_.view.lookAt : orbitTarget(start, center_, radius_);
    control_ = std::make_unique<CameraControl>(start, target, radius_);
    home_ = std::make_unique<CameraControl>(*control_);
    for (const Camera& c : cameras_) panel_.cameras.push_back(c.name.empty() ? "camera" : c.name);
    panel_.camera = std::min(cmd_.view.camera, int(cameras_.size()) - 1);
    panel_.device = ctx_->info.name;
    panel_.sampler = samplerByKind(settings_.sampler).name;
    panel_.lightSampler = tree ? "light tree" : "power (alias table)";
    panel_.integrator = settings_.integrator == IntegratorKind::Wavefront ? "wavefront" : "megakernel";
    panel_.maxDepth = int(settings_.maxDepth);

    RenderTuning tuning = cmd_.tuning;
    tuning.submitSeconds = cmd_.frameSeconds;
    tuning.splitSamples = true;  // a slow sample goes a run of tiles at a time
    tuning.tileSize = kViewTile;
    lastFrame_ = Clock::now();
    frame(0.0);  // the window, black, before the first batch
    while (!quit_) {
        if (restart_) waitingImage_ = true;
        restart_ = false;
        haveImage_ = false;
        started_ = Clock::now();
        renderSeconds_ = 0.0;
        samples_ = 0;
        SampleRun run;
        if (cmd_.exitAfterSpp) run.end = std::min(cmd_.exitAfterSpp, settings_.spp);
        run.onSubmission = [&](std::uint32_t spp, const std::function<Film()>& image) {
            renderSeconds_ = std::chrono::duration<double>(Clock::now() - started_).count();
            samples_ = std::uint64_t(spp) * settings_.width * settings_.height;
            // The image is read back and shown at most every kRefreshSeconds
            // (it costs about a third of a 50 ms submission at 640x360 on
            // lavapipe), and at once after a change or for a script step;
            // the input is read after every submission.
            const auto now = Clock::now();
            const bool due = waitingImage_ || std::chrono::duration<double>(now - refreshed_).count() >= kRefreshSeconds ||
                             (scriptStep_ < cmd_.script.size() && spp >= cmd_.script[scriptStep_].spp);
            if (due) {
                show(image(), spp);
                refreshed_ = now;
            }
            return frame(0.0);
        };
        const RenderResult result = render(*ctx_, dev, control_->camera(), settings_, tuning, {}, run);
        if (restart_ || quit_) continue;
        // The accumulation ended (--spp, or --exit-after-spp): the image stays.
        show(result.film, result.spp);
        if (cmd_.exitAfterSpp && result.spp >= std::min(cmd_.exitAfterSpp, settings_.spp)) {
            frame(0.0);
            break;
        }
        while (!restart_ && !quit_) frame(0.1);
    }
    // --screenshot: the image last shown, however the window ended.
    if (!cmd_.screenshot.empty() && !linear_.empty()) writeScreenshot(cmd_.screenshot);
    return 0;
}

}  // namespace

std::vector<ViewScriptStep> parseViewScript(const std::string& text) {
    std::vector<ViewScriptStep> steps;
    std::stringstream all(text);
    std::string item;
    while (std::getline(all, item, ';')) {
        std::stringstream words(item);
        ViewScriptStep step;
        std::string spp;
        if (!(words >> spp)) continue;
        if (!(words >> step.action) || spp.find_first_not_of("0123456789") != std::string::npos)
            throw Error("strata: error: --script: '" + item + "' is not 'SPP ACTION [ARGS]'");
        step.spp = std::uint32_t(std::stoul(spp));
        std::string a;
        while (words >> a) step.args.push_back(a);
        const std::size_t need = step.action == "orbit" || step.action == "pan" || step.action == "resize" ? 2
                                 : step.action == "zoom" || step.action == "screenshot" || step.action == "window" ||
                                           step.action == "view"
                                       ? 1
                                 : step.action == "close" || step.action == "camera" || step.action == "print" ? 0
                                                                                                           : 99;
        if (need == 99) throw Error("strata: error: --script: unknown action '" + step.action + "'");
        if (step.args.size() != need)
            throw Error("strata: error: --script: '" + step.action + "' takes " + std::to_string(need) +
                        " argument(s), got " + std::to_string(step.args.size()));
        if (step.action == "view" && viewByName(step.args[0]) < 0)
            throw Error("strata: error: --script: view takes colour, albedo, normal, depth or denoised, got '" +
                        step.args[0] + "'");
        const bool numbers = step.action != "screenshot" && step.action != "window" && step.action != "view";
        for (std::size_t k = 0; k < need && numbers; ++k) {
            char* end = nullptr;
            std::strtod(step.args[k].c_str(), &end);
            if (end == step.args[k].c_str() || *end != '\0')
                throw Error("strata: error: --script: '" + step.args[k] + "' is not a number");
        }
        steps.push_back(step);
    }
    return steps;
}

int runView(const ViewCommand& cmd) {
    if (!cmd.screenshot.empty()) requireImageSupport(cmd.screenshot);
    for (const ViewScriptStep& s : cmd.script)
        if (s.action == "screenshot" || s.action == "window") requireImageSupport(s.args[0]);
    const view::Api& api = windowModule();
    Viewer viewer(cmd, api);
    return viewer.run();
}

}  // namespace strata
