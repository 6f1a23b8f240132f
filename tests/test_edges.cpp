// Edge coverage (measure/edges.h): the exact coverage geometry, the shades a
// grid gives as an edge slides across the pixel (the sampling lecture: a
// regular 8x8 grid gives 9 of the 65 possible at 0 degrees, the grid rotated
// by atan(1/8) gives 65 there and fails at its own angle), and the RMSE of
// the GLSL samplers against independent samples.
#include <doctest/doctest.h>

#include "cli_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "../shaders/shared/types.h"
#include "measure/edges.h"
#include "measure/sample_dump.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

constexpr std::uint32_t kSpp = 64, kGrid = 8;

// Projection of grid sample (col, row) on the normal (-b, a) of an edge along
// the integer direction (a, b), scaled to an integer: samples share a shade
// step exactly when these are equal, so the distinct values + 1 are the
// shades as the edge slides continuously across the pixel.
std::uint32_t latticeShades(bool rotated, int a, int b) {
    std::set<long> projections;
    const int n = static_cast<int>(kGrid), n2 = n * n;
    for (int k = 0; k < n2; ++k) {
        const int i = k % n, j = k / n;
        // shaders/lib/sampler.glsl gridPoint: regular puts sample k at cell
        // (i, j) of the n x n grid; rotated at column (i n - j) mod n^2, row
        // (i + j n) mod n^2 of the n^2 x n^2 subgrid; both at the cell centre.
        const int col = rotated ? (i * n + n2 - j) % n2 : i;
        const int row = rotated ? (i + j * n) % n2 : j;
        projections.insert(-static_cast<long>(b) * col + static_cast<long>(a) * row);
    }
    return static_cast<std::uint32_t>(projections.size()) + 1;
}

double pooledRmse(const EdgeReport& r, const std::string& sampler) {
    double mse = 0.0;
    for (double a : r.anglesDeg) mse += std::pow(r.row(sampler, a)->rmse, 2) / r.anglesDeg.size();
    return std::sqrt(mse);
}

}  // namespace

TEST_CASE("edge coverage is the exact area of the half-plane in the pixel" * doctest::test_suite("unit")) {
    // theta = 0: the region below y = 0.5 + c.
    for (double c : {-0.5, -0.3, 0.0, 0.123, 0.5}) CHECK(edgeCoverage(0.0, c) == doctest::Approx(0.5 + c));
    // theta = 45: h = sqrt(2)/2; the uncovered corner at distance t = h - c
    // from the line is a right triangle with legs t sqrt(2), area t^2.
    const double h = std::sqrt(0.5);
    CHECK(edgeOffsetHalfWidth(45.0) == doctest::Approx(h));
    for (double t : {0.05, 0.2, 0.5}) CHECK(edgeCoverage(45.0, h - t) == doctest::Approx(1.0 - t * t));
    CHECK(edgeCoverage(45.0, 0.0) == doctest::Approx(0.5));
    // Coverage runs from 0 to 1 over [-h, h]; the complement is the mirror offset.
    for (double angle : {2.0, 7.125, 26.565, 60.0, 135.0}) {
        const double hw = edgeOffsetHalfWidth(angle);
        CHECK(edgeCoverage(angle, -hw) == doctest::Approx(0.0).epsilon(1e-12));
        CHECK(edgeCoverage(angle, hw) == doctest::Approx(1.0));
        CHECK(edgeCoverage(angle, 0.17) + edgeCoverage(angle, -0.17) == doctest::Approx(1.0));
    }
    // Against a 2000 x 2000 midpoint grid (error well below 1e-3).
    const double angle = 30.0, c = 0.21, t = angle * std::numbers::pi / 180.0;
    long inside = 0;
    for (int y = 0; y < 2000; ++y)
        for (int x = 0; x < 2000; ++x)
            inside += ((x + 0.5) / 2000 - 0.5) * -std::sin(t) + ((y + 0.5) / 2000 - 0.5) * std::cos(t) < c;
    CHECK(std::abs(edgeCoverage(angle, c) - inside / 4e6) < 1e-3);
    CHECK(rotatedGridAngle(64) == doctest::Approx(7.1250163));
}

TEST_CASE("edge profile of a CPU 8x8 grid: 9 shades at 0 degrees, 16 at 45" * doctest::test_suite("unit")) {
    std::vector<glm::vec2> grid;
    for (std::uint32_t j = 0; j < kGrid; ++j)
        for (std::uint32_t i = 0; i < kGrid; ++i) grid.emplace_back((i + 0.5f) / kGrid, (j + 0.5f) / kGrid);
    const EdgeProfile flat = edgeProfile(grid, 0.0, 1001);
    CHECK(flat.shades == latticeShades(false, 1, 0));
    CHECK(flat.shades == 9);
    CHECK(flat.estimate.front() == 0.0);
    CHECK(flat.estimate.back() == 1.0);
    // At 45 degrees the 15 diagonals of the grid each enter at one offset,
    // although their projections differ in the last bit (sin and cos of 45
    // degrees do).
    CHECK(edgeProfile(grid, 45.0, 1001).shades == 16);
}

TEST_CASE("GLSL regular and rotated grids: the shades the lecture describes for edges") {
    vk::Context& ctx = test::context();
    // The same pattern in every pixel (measureEdges measures one pixel of each).
    for (std::uint32_t kind : {gpu::kSamplerRegular, gpu::kSamplerRotated}) {
        const auto a = drawPixelSamples(ctx, {kind, kSpp, 3, 0, 0, 256, 256});
        const auto b = drawPixelSamples(ctx, {kind, kSpp, 9, 13, 200, 256, 256});
        for (std::uint32_t i = 0; i < kSpp; ++i) CHECK((a[i].x == b[i].x && a[i].y == b[i].y));
    }
    EdgeSettings s;
    s.samplers = {gpu::kSamplerRegular, gpu::kSamplerRotated};
    s.spp = kSpp;
    const EdgeReport r = measureEdges(ctx, s);
    const double own = rotatedGridAngle(kSpp);

    // The lecture's numbers: 9 shades from 64 regular samples at 0 degrees
    // (the 8 rows enter 8 samples at a time); 65 from the rotated grid.
    CHECK(r.row("regular", 0.0)->shades == 9);
    CHECK(r.row("rotated", 0.0)->shades == 65);
    // At its own angle atan(1/8), direction (8, 1), the rotated grid fails:
    // sample (i, j) projects to j (1 + n^2) + n^2 w on the normal (-1, n),
    // w = 1 where the column wrapped (i = 0, j > 0), so its 64 samples lie on
    // 1 + 2 (n - 1) = 15 lines: 16 shades, steps of 8, 7 and 1 samples.
    CHECK(r.row("rotated", own)->shades == 16);
    CHECK(r.row("rotated", own)->shades < r.row("rotated", 0.0)->shades);
    CHECK(r.row("rotated", own)->maxAbsError > 2.0 * r.row("rotated", 0.0)->maxAbsError);

    // Every angle with a rational slope against the integer lattice: 0 (1, 0),
    // atan(1/8) (8, 1), atan(1/2) (2, 1), 45 (1, 1). Regular: 9, 65, 23, 16;
    // rotated: 65, 16, 59, 61.
    const std::array<std::array<int, 2>, 4> directions = {{{1, 0}, {8, 1}, {2, 1}, {1, 1}}};
    for (const auto& [a, b] : directions) {
        const double angle = std::atan2(b, a) * 180.0 / std::numbers::pi;
        CAPTURE(angle);
        CHECK(r.row("regular", angle)->shades == latticeShades(false, a, b));
        CHECK(r.row("rotated", angle)->shades == latticeShades(true, a, b));
    }
    // A staircase of steps of 1/8 is off by up to half a step, 1/16 (less the
    // offsets' spacing in coverage, 1/1000), with the RMSE of a sawtooth,
    // (1/8) / sqrt(12).
    CHECK(std::abs(r.row("regular", 0.0)->maxAbsError - 1.0 / 16) <= 1e-3);
    CHECK(std::abs(r.row("regular", 0.0)->rmse / (0.125 / std::sqrt(12.0)) - 1.0) < 0.01);
}

TEST_CASE("GLSL random samplers: edge RMSE of independent, stratified and Sobol samples") {
    vk::Context& ctx = test::context();
    EdgeSettings s;
    s.spp = kSpp;
    s.samplers = {gpu::kSamplerIndependent};
    s.blockSide = 16;
    const EdgeReport ind = measureEdges(ctx, s);
    s.samplers = {gpu::kSamplerStratified, gpu::kSamplerSobol};
    s.blockSide = 8;
    const EdgeReport low = measureEdges(ctx, s);

    // Independent samples: E[(k/N - p)^2] = p (1 - p) / N. Averaged over the
    // 1001 offsets (at 0 degrees p = k/1000, so mean p(1-p) = 1/2 - 2001/6000).
    double expectedMse = 0.0, mse = 0.0, mseStdError = 0.0;
    for (double angle : ind.anglesDeg) {
        const EdgeProfile exact = edgeProfile({glm::vec2(0.5f)}, angle, 1001);
        double pq = 0.0;
        for (double p : exact.exact) pq += p * (1.0 - p);
        const EdgeRow* row = ind.row("independent", angle);
        CHECK(row->rmseIndependent == doctest::Approx(std::sqrt(pq / 1001 / kSpp)));
        expectedMse += pq / 1001 / kSpp / ind.anglesDeg.size();
        mse += row->rmse * row->rmse / ind.anglesDeg.size();
        // The angles share their samples: their standard errors add at most linearly.
        mseStdError += row->mseStdError / ind.anglesDeg.size();
    }
    CHECK(ind.row("independent", 0.0)->rmseIndependent ==
          doctest::Approx(std::sqrt((0.5 - 2001.0 / 6000.0) / kSpp)));
    INFO("independent MSE " << mse << " expected " << expectedMse << " +- " << mseStdError);
    CHECK(std::abs(mse - expectedMse) < 4.0 * mseStdError);
    CHECK(std::abs(std::sqrt(mse) / std::sqrt(expectedMse) - 1.0) < 0.10);
    CHECK(std::sqrt(mse) < 0.0625);  // p (1 - p) <= 1/4

    // Shades of independent samples at 0 degrees: two adjacent projections
    // (spacing g, density 64 (1 - g)^63) share a shade when no offset (spacing
    // d = 1/1000) falls between them, with probability max(0, 1 - g/d):
    // 65 - 63 E[max(0, 1 - g/d)] shades; the lost shades are about Poisson(2),
    // so the mean over 256 pixels has a standard error <= sqrt(2/256) = 0.09.
    const double d = 1.0 / 1000;
    double merge = 0.0;
    for (int k = 0; k < 10000; ++k) {
        const double g = (k + 0.5) / 10000 * d;
        merge += (1.0 - g / d) * 64.0 * std::pow(1.0 - g, 63) * d / 10000;
    }
    INFO("independent shades at 0 deg " << ind.row("independent", 0.0)->shades << " expected " << 65.0 - 63.0 * merge);
    CHECK(std::abs(ind.row("independent", 0.0)->shades - (65.0 - 63.0 * merge)) < 4.0 * std::sqrt(2.0 / 256));

    // Jittered 8x8: an edge crosses about 8 cells; a cell covered to a adds a
    // Bernoulli of variance a (1 - a) weighted 1/64, mean 1/6 for a uniform in
    // [0, 1]: RMSE near sqrt(8/6)/64 = 0.018.
    const double independent = std::sqrt(mse);
    const double stratified = pooledRmse(low, "stratified"), sobol = pooledRmse(low, "sobol");
    INFO("pooled RMSE independent " << independent << " stratified " << stratified << " sobol " << sobol);
    CHECK(stratified <= 0.022);
    CHECK(stratified < 0.5 * independent);
    CHECK(sobol < 0.5 * independent);
    for (double angle : low.anglesDeg) {
        CAPTURE(angle);
        CHECK(low.row("stratified", angle)->rmse < ind.row("independent", angle)->rmse);
        CHECK(low.row("sobol", angle)->rmse < ind.row("independent", angle)->rmse);
    }
}

TEST_CASE("strata edges: table, plot, summary, and bad input is one line and exit 2") {
    const fs::path dir = fs::temp_directory_path() / ("strata-edges-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string csv = (dir / "edges.csv").string(), png = (dir / "edges.png").string();
    Run r = run("edges --spp 64 --sampler regular -o " + csv + " --plot " + png);
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(r.output.find("regular: 9 shades at 0 deg (expected 65)") != std::string::npos);
    CHECK(fs::file_size(png) > 0);
    std::ifstream f(csv);
    std::string line;
    int lines = 0;
    while (std::getline(f, line)) ++lines;
    CHECK(lines == 6);  // header + 5 angles

    for (const std::string& bad : {std::string("edges --spp 0"), std::string("edges --sampler bogus"),
                                   "edges --spp 64 -o " + (dir / "t.txt").string(),
                                   "edges --spp 64 --plot " + (dir / "p.jpg").string(),
                                   std::string("edges --spp 32 --sampler regular")}) {
        const Run b = run(bad);
        CAPTURE(bad);
        CAPTURE(b.output);
        CHECK(b.status == 2);
        CHECK(std::count(b.output.begin(), b.output.end(), '\n') == 1);
    }
    CHECK(!fs::exists(dir / "t.txt"));
    fs::remove_all(dir);
}

TEST_SUITE_END();
