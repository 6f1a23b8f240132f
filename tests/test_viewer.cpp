// `strata view` (host/view/, the window module host/window/): run for real
// under Xvfb (xvfb-run, a new X server per test, gone when strata exits)
// with lavapipe and the validation layers; the camera control's math on
// the host; and its errors before any window.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "cli_util.h"
#include "test_util.h"
#include "image/aov.h"
#include "image/image_io.h"
#include "view/camera_control.h"
#include "view/viewer.h"

using namespace strata;
using namespace strata::test;

namespace {

std::string fileBytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> filesIn(const std::filesystem::path& dir) {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

// `strata view ARGS` in `dir` under a fresh X server.
Run view(const TempDir& dir, const std::string& args) {
    return runShell("cd " + dir.path.string() + " && xvfb-run -a -s '-screen 0 800x600x24' " + std::string(STRATA_EXE) +
                    " view " + args);
}

const std::string kCornell = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";

// view() that must exit 0 with no validation message.
Run viewOk(const TempDir& dir, const std::string& args) {
    const Run v = view(dir, args);
    INFO(v.output);
    REQUIRE(v.status == 0);
    CHECK(v.output.find("validation") == std::string::npos);
    return v;
}

}  // namespace

TEST_SUITE_BEGIN("render");

TEST_CASE("view: the window's image after 16 spp is the PNG that render writes with the same size, spp and view, bit for bit") {
    TempDir dir;
    const Run v = viewOk(dir, kCornell + " --width 96 --height 64 --exit-after-spp 16 --screenshot shown.png");
    CAPTURE(v.output);
    const Run r = run("render " + kCornell + " --width 96 --height 64 --spp 16 -o " +
                      (dir.path / "rendered.png").string() + " --quiet");
    REQUIRE(r.status == 0);
    const std::string shown = fileBytes(dir.path / "shown.png"), rendered = fileBytes(dir.path / "rendered.png");
    REQUIRE(!shown.empty());
    CHECK(shown == rendered);
    // Another view is another image: the comparison can fail.
    const Run moved = view(dir, kCornell + " --width 96 --height 64 --exit-after-spp 16 --screenshot moved.png "
                                           "--look-from 0,1,4 --look-at 0,1,0");
    REQUIRE(moved.status == 0);
    CHECK(fileBytes(dir.path / "moved.png") != rendered);
}

TEST_CASE("view: the albedo view restarts with the AOV sums and shows render --aov's albedo layer") {
    TempDir dir;
    const Run v = viewOk(dir, kCornell + " --width 64 --height 48 --exit-after-spp 8 --screenshot albedo.png "
                                         "--script '1 view albedo'");
    CAPTURE(v.output);
    const std::string exr = (dir.path / "aov.exr").string();
    REQUIRE(run("render " + kCornell + " --width 64 --height 48 --spp 8 --aov -o " + exr + " --quiet").status == 0);
    const AovImages aov = readAovImages(exr);
    writeImages({(dir.path / "rendered-albedo.png").string()}, aov.width, aov.height, aov.albedo);
    const std::string shown = fileBytes(dir.path / "albedo.png");
    REQUIRE(!shown.empty());
    CHECK(shown == fileBytes(dir.path / "rendered-albedo.png"));
    writeImages({(dir.path / "rendered-color.png").string()}, aov.width, aov.height, aov.color);
    CHECK(shown != fileBytes(dir.path / "rendered-color.png"));
}

TEST_CASE("view: the printed render command renders the view the window shows after an orbit") {
    TempDir dir;
    const Run v = viewOk(dir, kCornell + " --width 80 --height 60 --exit-after-spp 8 --screenshot shown.png "
                                         "--script '1 orbit 8 3; 1 print'");
    CAPTURE(v.output);
    const std::size_t at = v.output.find("strata render ");
    REQUIRE(at != std::string::npos);
    const std::string line = v.output.substr(at, v.output.find('\n', at) - at);
    CHECK(line.find("--look-from ") != std::string::npos);
    CHECK(line.find(" --spp 8") != std::string::npos);
    CHECK(line.find("--script") == std::string::npos);
    const Run r = runShell("cd " + dir.path.string() + " && " + std::string(STRATA_EXE) +
                           line.substr(std::string("strata").size()) + " -o rendered.png --quiet");
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    const Image a = readImage((dir.path / "shown.png").string()), b = readImage((dir.path / "rendered.png").string());
    REQUIRE(a.pixels.size() == b.pixels.size());
    // The same view to the printed digits: the camera's vectors are made
    // again from --look-from, --look-at and --up, so a few edge pixels may
    // move; against the view before the orbit, most pixels differ.
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) same += std::abs(a.pixels[i] - b.pixels[i]) <= 1.5f / 255.0f;
    CHECK(double(same) / double(a.pixels.size()) > 0.99);
    const Run before = run("render " + kCornell + " --width 80 --height 60 --spp 8 -o " +
                           (dir.path / "before.png").string() + " --quiet");
    REQUIRE(before.status == 0);
    const Image c = readImage((dir.path / "before.png").string());
    std::size_t unmoved = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) unmoved += std::abs(a.pixels[i] - c.pixels[i]) <= 1.5f / 255.0f;
    CHECK(double(unmoved) / double(a.pixels.size()) < 0.8);
}

TEST_CASE("view: a camera change restarts the accumulation with a new image, a resize keeps rendering, and closing the window exits 0 writing nothing unasked") {
    TempDir dir;
    const Run v = viewOk(dir, kCornell + " --width 96 --height 64 --stats --script '4 screenshot a.png; 4 orbit 40 10; "
                                         "2 screenshot b.png; 3 resize 80 48; 2 screenshot c.png; 3 close'");
    CAPTURE(v.output);
    // The steps ran in order, each once the image had its spp (a submission
    // may take several); after the orbit and after the resize the image
    // started again from 1 spp (the counter fell), at the new size.
    const std::vector<std::pair<std::string, std::uint32_t>> steps = {
        {"at 96x64: screenshot a.png", 4},   {"at 96x64: orbit 40 10", 4}, {"new image (1 spp)", 1},
        {"at 96x64: screenshot b.png", 2},   {"at 96x64: resize 80 48", 3}, {"new image (1 spp)", 1},
        {"at 80x48: screenshot c.png", 2},   {"at 80x48: close", 3}};
    std::size_t at = 0;
    for (const auto& [text, spp] : steps) {
        const std::size_t found = v.output.find(text, at);
        CHECK_MESSAGE(found != std::string::npos, text);
        if (found == std::string::npos) continue;
        at = found + 1;
        if (text.rfind("at ", 0) == 0) {  // "strata view: N spp at ..."
            const std::size_t line = v.output.rfind("strata view: ", found);
            REQUIRE(line != std::string::npos);
            CHECK(std::stoul(v.output.substr(line + 13)) >= spp);
        }
    }
    const std::string a = fileBytes(dir.path / "a.png"), b = fileBytes(dir.path / "b.png");
    REQUIRE(!a.empty());
    REQUIRE(!b.empty());
    CHECK(a != b);
    CHECK(std::filesystem::exists(dir.path / "c.png"));
    // Only what the script asked for.
    CHECK(filesIn(dir.path) == std::set<std::string>{"a.png", "b.png", "c.png"});
}

TEST_CASE("view: split samples (runs of tiles per submission, the image read between them) give the render's bits") {
    RenderSettings s;
    s.width = 72;
    s.height = 40;
    s.spp = 6;
    SceneRequest request = keptRequest(s);
    request.file = kCornell;
    const HostScene host = prepareScene(request);
    const DeviceScene dev = uploadPrepared(context(), request, host.gpu);
    RenderTuning folds;
    folds.maxBatch = 4;  // a fold inside the run (batches set the float32 sums: the same in both)
    const RenderResult whole = render(context(), dev, host.camera, s, folds);
    RenderTuning split = folds;
    split.splitSamples = true;
    split.tileSize = 16;          // 5 x 3 tiles a sample
    split.submitSeconds = 1e-9;   // a tile per submission
    std::uint32_t calls = 0, partial = 0, last = 0;
    std::size_t counted = 0;
    SampleRun run;
    run.onSubmission = [&](std::uint32_t spp, const std::function<Film()>& image) {
        ++calls;
        partial += spp == last;
        last = spp;
        const Film f = image();
        counted = 0;
        for (std::uint64_t c : f.count) counted += c;
        CHECK(counted >= std::size_t(spp) * f.pixels());  // the sample's tiles so far are in
        return true;
    };
    const RenderResult cut = render(context(), dev, host.camera, s, split, {}, run);
    CHECK(cut.spp == 6);
    CHECK(calls > 20);    // the first sample whole, then a tile at a time
    CHECK(partial > 10);  // images between a sample's tiles
    CHECK(cut.film.count == whole.film.count);
    CHECK(cut.film.sum == whole.film.sum);
    CHECK(cut.film.sumSq == whole.film.sumSq);
    // A stop between tiles: the samples reached, nothing after.
    std::uint32_t stops = 0;
    SampleRun stopped;
    stopped.onSubmission = [&](std::uint32_t, const std::function<Film()>&) { return ++stops < 9; };
    const RenderResult early = render(context(), dev, host.camera, s, split, {}, stopped);
    CHECK(early.spp < 6);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

TEST_CASE("view: a scene that render refuses is one line and exit 2 before any window, and so is no display") {
    TempDir dir;
    const std::string broken = std::string(STRATA_SOURCE_DIR) + "/tests/data/media/broken/scatter-anisotropy-1.gltf";
    const Run r = runShell("cd " + dir.path.string() + " && env -u DISPLAY " + std::string(STRATA_EXE) + " view " + broken);
    CHECK(r.status == 2);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.rfind(broken + ": error: ", 0) == 0);
    const Run none = runShell("cd " + dir.path.string() + " && env -u DISPLAY " + std::string(STRATA_EXE) + " view " +
                              kCornell + " --quiet");
    CAPTURE(none.output);
    CHECK(none.status == 2);
    CHECK(lines(none.output) == 1);
    CHECK(none.output.find("strata: error: strata view: no display") == 0);
    CHECK(filesIn(dir.path).empty());
    // Flags: a script step it does not know, a screenshot that is no PNG.
    const Run step = run("view " + kCornell + " --script '4 spin 3'");
    CHECK(step.status == 2);
    CHECK(step.output == "strata: error: --script: unknown action 'spin'\n");
    const Run exr = run("view " + kCornell + " --screenshot s.exr");
    CHECK(exr.status == 2);
    CHECK(lines(exr.output) == 1);
}

TEST_CASE("view: the camera control orbits at a constant distance, zooms by 15% a step, pans with the cursor and stops short of the poles") {
    Camera cam;
    cam.position = glm::vec3(0.0f, 0.0f, 5.0f);
    cam.forward = glm::vec3(0.0f, 0.0f, -1.0f);
    cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
    cam.yfov = 0.8f;
    const glm::vec3 target(0.0f);
    CameraControl c(cam, target, 2.0);
    // Half a turn per window height: 100 pixels of 400 turn 45 degrees about +Y.
    c.orbit(100.0, 0.0, 400);
    CHECK(glm::length(c.camera().position - target) == doctest::Approx(5.0f));
    CHECK(c.camera().position.x == doctest::Approx(-5.0f * std::sin(0.785398f)).epsilon(1e-5));
    CHECK(glm::dot(c.camera().forward, glm::normalize(target - c.camera().position)) == doctest::Approx(1.0f));
    // Up to the pole and beyond: the elevation stops at 89 degrees.
    c.orbit(0.0, 10000.0, 400);
    const float elevation = std::asin(c.camera().position.y / glm::length(c.camera().position));
    CHECK(elevation == doctest::Approx(89.0f * 3.14159265f / 180.0f).epsilon(1e-4));
    CHECK(std::abs(glm::dot(c.camera().up, c.camera().forward)) < 1e-5f);
    // Two wheel steps: 0.85^2 of the distance.
    CameraControl z(cam, target, 2.0);
    z.zoom(2.0);
    CHECK(glm::length(z.camera().position - target) == doctest::Approx(5.0f * 0.85f * 0.85f));
    // A drag of 200 of 400 pixels right moves the view half its height at
    // the target's depth to the left.
    CameraControl p(cam, target, 2.0);
    p.pan(200.0, 0.0, 400);
    const float half = 5.0f * std::tan(0.4f);
    CHECK(p.target().x == doctest::Approx(-half));
    CHECK(p.camera().position.x == doctest::Approx(-half));
    CHECK(p.camera().forward.z == doctest::Approx(-1.0f));
    // Any move drops the camera's own motion over a shutter.
    cam.motion.resize(2);
    CameraControl m(cam, target, 2.0);
    CHECK(m.camera().motion.size() == 2);
    m.fly(glm::vec3(0.0f, 0.0f, 1.0f), 0.5);
    CHECK(m.camera().motion.empty());
    CHECK(m.camera().position.z == doctest::Approx(4.5f));  // half the radius a second
}

TEST_CASE("view: the display's sRGB table gives the PNG writer's byte (every 127th float in [0, 1], each step's neighbours, outside)") {
    const Srgb8Table table;
    std::size_t checked = 0, wrong = 0;
    auto check = [&](float x) {
        ++checked;
        wrong += table(x) != srgb8(x);
    };
    for (std::uint32_t bits = 0; bits <= 0x3f800000u; bits += 127) {
        float x;
        std::memcpy(&x, &bits, sizeof x);
        check(x);
    }
    for (int k = 1; k < 256; ++k) {  // 2,000 floats around each step, where a byte changes
        const double e = (k - 0.5) / 255.0;  // the encoded value halfway between two bytes, decoded
        float x = float(e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4));
        for (int i = 0; i < 1000; ++i) x = std::nextafter(x, 0.0f);
        for (int i = 0; i < 2000; ++i, x = std::nextafter(x, 2.0f)) check(x);
    }
    for (float x : {-1.0f, -0.0f, 1.0f, 1.5f, 1e30f, std::numeric_limits<float>::infinity()}) check(x);
    CHECK(table(std::numeric_limits<float>::quiet_NaN()) == 0);
    CHECK(checked > 8800000);
    CHECK(wrong == 0);
}

TEST_CASE("view: --script steps are parsed, and a bad one is refused in one line") {
    const auto steps = parseViewScript("4 orbit 30 -2; 2 screenshot b.png;3 close");
    REQUIRE(steps.size() == 3);
    CHECK(steps[0].spp == 4);
    CHECK(steps[0].action == "orbit");
    CHECK(steps[0].args == std::vector<std::string>{"30", "-2"});
    CHECK(steps[1].args == std::vector<std::string>{"b.png"});
    CHECK(steps[2].args.empty());
    CHECK_THROWS_WITH(parseViewScript("4 orbit 30"), "strata: error: --script: 'orbit' takes 2 argument(s), got 1");
    CHECK_THROWS_WITH(parseViewScript("x orbit 1 2"), "strata: error: --script: 'x orbit 1 2' is not 'SPP ACTION [ARGS]'");
    CHECK_THROWS_WITH(parseViewScript("4 zoom far"), "strata: error: --script: 'far' is not a number");
}

TEST_SUITE_END();
