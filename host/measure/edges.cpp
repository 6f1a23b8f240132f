#include "measure/edges.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <utility>

#include "../../shaders/shared/types.h"
#include "image/image_io.h"
#include "measure/plot.h"
#include "measure/sample_dump.h"
#include "render/sampler_kind.h"
#include "util/error.h"
#include "util/files.h"
#include "vk/check.h"

namespace strata {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// One edge direction with its offsets and the exact coverage at each,
// shared by every pixel and sampler.
struct EdgeGeometry {
    double angleDeg = 0.0;
    double nx = 0.0, ny = 1.0;  // unit normal (-sin theta, cos theta)
    std::vector<double> offset, exact;
};

EdgeGeometry makeGeometry(double angleDeg, std::uint32_t offsets) {
    EdgeGeometry g;
    g.angleDeg = angleDeg;
    g.nx = -std::sin(angleDeg * kDegree);
    g.ny = std::cos(angleDeg * kDegree);
    const double h = edgeOffsetHalfWidth(angleDeg);
    for (std::uint32_t k = 0; k < offsets; ++k) {
        const double c = offsets == 1 ? 0.0 : -h + 2.0 * h * k / (offsets - 1);
        g.offset.push_back(c);
        g.exact.push_back(edgeCoverage(angleDeg, c));
    }
    return g;
}

// A sample on the edge line is outside (the half-plane is open). Projections
// that are equal in exact arithmetic (a row of the regular grid at 45
// degrees, where sin and cos differ in the last bit) differ by ~1e-16 after
// rounding; comparing against offset - kTie keeps such a line of samples on
// one side when an offset falls on it, so it enters at one offset, as it does
// geometrically.
constexpr double kTie = 1e-9;

// estimate[k] = #{i : dot(p_i - centre, n) < offset[k]} / spp, from the
// sorted projections (offsets ascend, so one pass). Returns the number of
// distinct estimates.
std::uint32_t estimateCoverage(const EdgeGeometry& g, const std::vector<glm::vec2>& samples,
                               std::vector<double>& projection, std::vector<double>& estimate) {
    projection.resize(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i)
        projection[i] = (samples[i].x - 0.5) * g.nx + (samples[i].y - 0.5) * g.ny;
    std::sort(projection.begin(), projection.end());
    estimate.resize(g.offset.size());
    const double n = static_cast<double>(samples.size());
    std::size_t inside = 0;
    std::uint32_t shades = 0;
    std::size_t last = ~std::size_t{0};
    for (std::size_t k = 0; k < g.offset.size(); ++k) {
        while (inside < projection.size() && projection[inside] < g.offset[k] - kTie) ++inside;
        estimate[k] = n > 0.0 ? static_cast<double>(inside) / n : 0.0;
        if (inside != last) ++shades, last = inside;
    }
    return shades;
}

// Regular and rotated place sample k at the centre of grid cell k in every
// pixel (gridPoint in shaders/lib/sampler.glsl: jitter 0.5, no pixel or seed
// term), so one pixel stands for all.
bool samePatternInEveryPixel(std::uint32_t kind) {
    return kind == gpu::kSamplerRegular || kind == gpu::kSamplerRotated;
}

// The requested samplers (all when none is named) that suit the spp; notes
// for the others in `skipped`. Throws when none suits.
std::vector<const SamplerInfo*> selectSamplers(const EdgeSettings& s, std::vector<std::string>& skipped) {
    if (s.spp == 0) throw Error("strata: error: edges needs --spp of at least 1");
    if (s.offsets < 2) throw Error("strata: error: edges needs at least 2 edge offsets");
    if (s.blockSide == 0 || s.blockSide > s.imageSide)
        throw Error("strata: error: edges needs a pixel block inside the image");
    std::vector<std::uint32_t> kinds = s.samplers;
    if (kinds.empty())
        for (const auto& info : samplers()) kinds.push_back(info.kind);
    std::vector<const SamplerInfo*> suited;
    for (std::uint32_t kind : kinds) {
        const SamplerInfo& info = samplerByKind(kind);
        try {
            checkSamplerSettings(info, s.spp, static_cast<int>(s.imageSide), static_cast<int>(s.imageSide));
            suited.push_back(&info);
        } catch (const Error& e) {
            std::string why = e.what();
            const std::string prefix = "strata: error: ";
            if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
            skipped.push_back(std::string(info.name) + ": skipped: " + why);
        }
    }
    if (suited.empty()) {
        std::string notes;
        for (const auto& n : skipped) notes += (notes.empty() ? "" : "; ") + n;
        throw Error("strata: error: no requested sampler suits --spp " + std::to_string(s.spp) + " (" + notes + ")");
    }
    return suited;
}

std::string formatShades(double shades, std::uint32_t lo, std::uint32_t hi) {
    char buf[64];
    if (lo == hi) std::snprintf(buf, sizeof buf, "%u", lo);
    else std::snprintf(buf, sizeof buf, "%.1f", shades);
    return buf;
}

std::string formatAngle(double deg) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", deg);
    std::string s = buf;
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

// Pooled over angles with equal weight (every angle has the same number of
// offsets and pixels): sqrt(mean of rmse^2).
struct Pooled {
    double rmse = 0.0, rmseIndependent = 0.0, maxAbsError = 0.0;
};

Pooled pool(const EdgeReport& r, const std::string& sampler) {
    Pooled p;
    double n = 0.0;
    for (const auto& row : r.rows) {
        if (row.sampler != sampler) continue;
        p.rmse += row.rmse * row.rmse;
        p.rmseIndependent += row.rmseIndependent * row.rmseIndependent;
        p.maxAbsError = std::max(p.maxAbsError, row.maxAbsError);
        n += 1.0;
    }
    if (n > 0) p.rmse = std::sqrt(p.rmse / n), p.rmseIndependent = std::sqrt(p.rmseIndependent / n);
    return p;
}

std::vector<std::string> measuredSamplers(const EdgeReport& r) {
    std::vector<std::string> names;
    for (const auto& row : r.rows)
        if (std::find(names.begin(), names.end(), row.sampler) == names.end()) names.push_back(row.sampler);
    return names;
}

std::array<float, 3> samplerColour(const std::string& name) {
    // Okabe-Ito colours, fixed per sampler so a chart of one sampler matches the chart of all.
    if (name == "independent") return {0.90f, 0.62f, 0.0f};
    if (name == "regular") return {0.84f, 0.37f, 0.0f};
    if (name == "rotated") return {0.0f, 0.45f, 0.70f};
    if (name == "stratified") return {0.80f, 0.47f, 0.65f};
    if (name == "sobol") return {0.0f, 0.62f, 0.45f};
    return {0.34f, 0.71f, 0.91f};
}

// Per angle (0 and the rotated grid's), the estimate of pixel (0, 0) against
// the exact coverage: over the whole range, and zoomed to exact coverage in
// [0.375, 0.625] where steps of 1/spp are visible.
void plotEdges(const std::string& path, const EdgeReport& r) {
    std::vector<Panel> panels;
    for (double angle : {0.0, rotatedGridAngle(r.spp)})
        for (const auto& [lo, hi] : {std::pair{0.0, 1.0}, std::pair{0.375, 0.625}}) {
            Panel panel;
            panel.title = "edge at " + formatAngle(angle) + " deg" + (lo > 0.0 ? " (zoom)" : "") + ", pixel (0,0), " +
                          std::to_string(r.spp) + " spp";
            panel.xLabel = "exact coverage";
            panel.yLabel = "estimate";
            panel.logX = panel.logY = false;
            panel.series.push_back({"exact", {lo, hi}, {lo, hi}, {0.5f, 0.5f, 0.5f}, true, false});
            // An unlabelled single point draws nothing; it raises the top of the
            // y axis so the legend (drawn top right) sits above the curves.
            panel.series.push_back({"", {lo}, {hi + 0.6 * (hi - lo)}, {1.0f, 1.0f, 1.0f}, false, false});
            for (const auto& [sampler, c] : r.curves) {
                if (std::abs(c.angleDeg - angle) > 1e-9) continue;
                Series s{sampler + " (" + std::to_string(c.shades) + " shades)", {}, {}, samplerColour(sampler)};
                s.markers = false;
                for (std::size_t k = 0; k < c.exact.size(); ++k)
                    if (c.exact[k] >= lo && c.exact[k] <= hi) s.x.push_back(c.exact[k]), s.y.push_back(c.estimate[k]);
                panel.series.push_back(std::move(s));
            }
            if (panel.series.size() > 2) panels.push_back(std::move(panel));
        }
    writeChart(path, panels, 560, 520);
}

}  // namespace

double edgeOffsetHalfWidth(double angleDeg) {
    return 0.5 * (std::abs(std::sin(angleDeg * kDegree)) + std::abs(std::cos(angleDeg * kDegree)));
}

double edgeCoverage(double angleDeg, double offset) {
    const double nx = -std::sin(angleDeg * kDegree), ny = std::cos(angleDeg * kDegree);
    // f(p) < 0 inside; each square edge crossing f = 0 adds the crossing point.
    auto f = [&](glm::dvec2 p) { return (p.x - 0.5) * nx + (p.y - 0.5) * ny - offset; };
    const std::array<glm::dvec2, 4> square = {{{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}};
    std::vector<glm::dvec2> poly;
    for (std::size_t i = 0; i < square.size(); ++i) {
        const glm::dvec2 a = square[i], b = square[(i + 1) % square.size()];
        const double fa = f(a), fb = f(b);
        if (fa < 0.0) poly.push_back(a);
        if ((fa < 0.0) != (fb < 0.0)) poly.push_back(a + (b - a) * (fa / (fa - fb)));
    }
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        twiceArea += a.x * b.y - b.x * a.y;
    }
    return std::clamp(0.5 * twiceArea, 0.0, 1.0);
}

double rotatedGridAngle(std::uint32_t spp) {
    return std::atan(1.0 / std::sqrt(static_cast<double>(spp))) / kDegree;
}

std::vector<double> defaultEdgeAngles(std::uint32_t spp) {
    std::vector<double> a = {0.0, 2.0, rotatedGridAngle(spp), std::atan(0.5) / kDegree, 45.0};
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end(), [](double x, double y) { return std::abs(x - y) < 1e-9; }), a.end());
    return a;
}

EdgeProfile edgeProfile(const std::vector<glm::vec2>& samples, double angleDeg, std::uint32_t offsets) {
    const EdgeGeometry g = makeGeometry(angleDeg, offsets);
    EdgeProfile p;
    p.angleDeg = angleDeg;
    p.offset = g.offset;
    p.exact = g.exact;
    std::vector<double> projection;
    p.shades = estimateCoverage(g, samples, projection, p.estimate);
    return p;
}

const EdgeRow* EdgeReport::row(const std::string& sampler, double angleDeg) const {
    for (const auto& r : rows)
        if (r.sampler == sampler && std::abs(r.angleDeg - angleDeg) < 1e-6) return &r;
    return nullptr;
}

void checkEdgeSettings(const EdgeSettings& s) {
    std::vector<std::string> skipped;
    selectSamplers(s, skipped);
}

EdgeReport measureEdges(const vk::Context& ctx, const EdgeSettings& s) {
    EdgeReport report;
    const std::vector<const SamplerInfo*> suited = selectSamplers(s, report.skipped);
    report.spp = s.spp;
    report.offsets = s.offsets;
    report.blockSide = s.blockSide;
    report.imageSide = s.imageSide;
    report.seed = s.seed;
    report.anglesDeg = s.anglesDeg.empty() ? defaultEdgeAngles(s.spp) : s.anglesDeg;
    std::vector<EdgeGeometry> geometry;
    for (double a : report.anglesDeg) geometry.push_back(makeGeometry(a, s.offsets));

    const double spp = static_cast<double>(s.spp);
    std::vector<double> projection, estimate;
    for (const SamplerInfo* info : suited) {
        const std::uint32_t side = samePatternInEveryPixel(info->kind) ? 1 : s.blockSide;
        const std::size_t angles = geometry.size();
        std::vector<double> mseSum(angles, 0.0), mseSqSum(angles, 0.0), shadesSum(angles, 0.0), maxAbs(angles, 0.0);
        std::vector<std::uint32_t> shadesMin(angles, ~0u), shadesMax(angles, 0u);
        // Whole rows of the block per dispatch (one pipeline each), as many
        // as kMaxPixelSamples allows.
        const std::uint32_t rowsPerDraw = static_cast<std::uint32_t>(
            std::clamp<std::uint64_t>(kMaxPixelSamples / (std::uint64_t(s.spp) * side), 1, side));
        std::vector<glm::vec4> drawn;
        std::vector<glm::vec2> samples;
        for (std::uint32_t py = 0; py < side; ++py)
            for (std::uint32_t px = 0; px < side; ++px) {
                const std::uint32_t firstRow = py - py % rowsPerDraw;
                if (px == 0 && py == firstRow) {
                    PixelSampleRequest req{info->kind, s.spp, s.seed, 0, firstRow, s.imageSide, s.imageSide};
                    req.blockWidth = side;
                    req.blockHeight = std::min(rowsPerDraw, side - firstRow);
                    drawn = drawPixelSamples(ctx, req);
                }
                const std::size_t first = (std::size_t(py - firstRow) * side + px) * s.spp;
                samples.clear();
                for (std::size_t k = first; k < first + s.spp; ++k) samples.emplace_back(drawn[k].x, drawn[k].y);
                for (std::size_t a = 0; a < angles; ++a) {
                    const EdgeGeometry& g = geometry[a];
                    const std::uint32_t shades = estimateCoverage(g, samples, projection, estimate);
                    double sq = 0.0;
                    for (std::size_t k = 0; k < estimate.size(); ++k) {
                        const double e = estimate[k] - g.exact[k];
                        sq += e * e;
                        maxAbs[a] = std::max(maxAbs[a], std::abs(e));
                    }
                    const double mse = sq / static_cast<double>(estimate.size());
                    mseSum[a] += mse;
                    mseSqSum[a] += mse * mse;
                    shadesSum[a] += shades;
                    shadesMin[a] = std::min(shadesMin[a], shades);
                    shadesMax[a] = std::max(shadesMax[a], shades);
                    if (px == 0 && py == 0) {
                        report.curves.push_back({info->name, {g.angleDeg, g.offset, g.exact, estimate, shades}});
                    }
                }
            }
        const double pixels = static_cast<double>(side) * side;
        for (std::size_t a = 0; a < angles; ++a) {
            EdgeRow row;
            row.sampler = info->name;
            row.angleDeg = geometry[a].angleDeg;
            row.pixels = side * side;
            row.shades = shadesSum[a] / pixels;
            row.shadesMin = shadesMin[a];
            row.shadesMax = shadesMax[a];
            const double mse = mseSum[a] / pixels;
            row.rmse = std::sqrt(mse);
            if (pixels > 1) {
                const double var = std::max(0.0, (mseSqSum[a] - pixels * mse * mse) / (pixels - 1.0));
                row.mseStdError = std::sqrt(var / pixels);
            }
            row.maxAbsError = maxAbs[a];
            double pq = 0.0;
            for (double p : geometry[a].exact) pq += p * (1.0 - p);
            row.rmseIndependent = std::sqrt(pq / static_cast<double>(geometry[a].exact.size()) / spp);
            report.rows.push_back(row);
        }
    }
    return report;
}

std::string edgesCsv(const EdgeReport& r) {
    std::string out =
        "sampler,angle_deg,spp,pixels,offsets,shades_mean,shades_min,shades_max,rmse,mse_stderr,max_abs_error,"
        "rmse_independent_expected\n";
    char line[320];
    for (const auto& row : r.rows) {
        std::snprintf(line, sizeof line, "%s,%.6g,%u,%u,%u,%.6g,%u,%u,%.6g,%.6g,%.6g,%.6g\n", row.sampler.c_str(),
                      row.angleDeg, r.spp, row.pixels, r.offsets, row.shades, row.shadesMin, row.shadesMax, row.rmse,
                      row.mseStdError, row.maxAbsError, row.rmseIndependent);
        out += line;
    }
    return out;
}

std::string edgesTable(const EdgeReport& r) {
    std::string out;
    char line[320];
    std::snprintf(line, sizeof line, "%-12s %9s %7s %20s %9s %11s %14s\n", "sampler", "angle", "pixels",
                  "shades mean [min,max]", "rmse", "max |error|", "rmse indep.");
    out += line;
    for (const auto& row : r.rows) {
        char shades[64];
        std::snprintf(shades, sizeof shades, "%.2f [%u,%u]", row.shades, row.shadesMin, row.shadesMax);
        std::snprintf(line, sizeof line, "%-12s %9s %7u %20s %9.5f %11.5f %14.5f\n", row.sampler.c_str(),
                      formatAngle(row.angleDeg).c_str(), row.pixels, shades, row.rmse, row.maxAbsError,
                      row.rmseIndependent);
        out += line;
    }
    return out;
}

std::vector<std::string> edgesSummary(const EdgeReport& r) {
    std::vector<std::string> lines;
    for (const std::string& name : measuredSamplers(r)) {
        std::string s = name + ":";
        bool first = true, perPixel = false;
        for (double angle : r.anglesDeg) {
            const EdgeRow* row = r.row(name, angle);
            if (!row) continue;
            perPixel |= row->pixels > 1;
            s += (first ? " " : ", ") + formatShades(row->shades, row->shadesMin, row->shadesMax) +
                 (first ? " shades at " : " at ") + formatAngle(angle) + " deg";
            if (first) s += " (expected " + std::to_string(r.spp + 1) + ")";
            first = false;
        }
        if (perPixel) s += " (mean over " + std::to_string(r.blockSide * r.blockSide) + " pixels)";
        const Pooled p = pool(r, name);
        char tail[200];
        std::snprintf(tail, sizeof tail, "; RMSE %.4f over all angles, %.2fx that of %u independent samples (%.4f); "
                      "max |error| %.4f", p.rmse, p.rmse / p.rmseIndependent, r.spp, p.rmseIndependent,
                      p.maxAbsError);
        lines.push_back(s + tail);
    }
    return lines;
}

int runEdges(const EdgesCommand& cmd) {
    if (!cmd.table.empty()) checkOutputPath(cmd.table);
    if (!cmd.plot.empty()) checkOutputPath(cmd.plot);
    vk::Context ctx({cmd.device, cmd.validation});
    std::fprintf(stderr, "strata: device %u: %s (%s, %s)\n", ctx.info.index, ctx.info.name.c_str(),
                 ctx.info.type.c_str(), ctx.info.driver.c_str());
    const EdgeReport r = measureEdges(ctx, cmd.settings);
    if (ctx.validation && vk::validationMessageCount() > 0)
        throw vk::DeviceError(std::to_string(vk::validationMessageCount()) +
                              " Vulkan validation message(s) while drawing samples");
    if (!cmd.plot.empty()) plotEdges(cmd.plot, r);
    if (!cmd.table.empty()) writeTextAtomically(cmd.table, edgesCsv(r));
    std::printf("edge coverage, %u spp, %u offsets per angle, pixels [0,%u)^2 of %ux%u, seed %u\n", r.spp,
                r.offsets, r.blockSide, r.imageSide, r.imageSide, r.seed);
    std::fputs(edgesTable(r).c_str(), stdout);
    for (const auto& note : r.skipped) std::printf("%s\n", note.c_str());
    for (const auto& line : edgesSummary(r)) std::printf("%s\n", line.c_str());
    return 0;
}

}  // namespace strata
