// `strata edges`: how well each pixel sampler estimates the coverage of a
// straight edge crossing a pixel, with samples drawn by the real GLSL
// samplers (measure/sample_dump.h).
//
// A pixel's colour is the integral of the image over the pixel; for an edge
// between two flat colours that integral is the covered fraction of the
// pixel, and a sampler's estimate is the fraction of its samples on the
// covered side. An edge at angle theta (degrees from the x axis) with signed
// offset c covers the half-plane {p : dot(p - (0.5, 0.5), n) < c} of the
// unit pixel, n = (-sin theta, cos theta). Sliding c across the pixel, an
// estimate from spp samples can take at most spp + 1 values ("shades"): a
// regular n x n grid gives only n + 1 at theta = 0, a grid rotated by
// atan(1/n) gives all spp + 1 there and fails at its own angle (the
// sampling lecture, ../shared/lecture-sampling.txt).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vk/context.h"

namespace strata {

// Exact area of the half-plane {p : dot(p - (0.5, 0.5), n) < c} clipped to
// the unit square: the square clipped by the half-plane (one
// Sutherland-Hodgman step), shoelace area.
double edgeCoverage(double angleDeg, double offset);

// The offsets where the edge crosses the pixel are (-h, h) with
// h = (|sin theta| + |cos theta|) / 2: coverage is 0 at -h and 1 at h.
double edgeOffsetHalfWidth(double angleDeg);

// atan(1/sqrt(spp)) in degrees: the rotated n x n grid's angle (7.125 for spp 64).
double rotatedGridAngle(std::uint32_t spp);

// 0, 2, rotatedGridAngle(spp), atan(1/2) = 26.565 and 45 degrees, ascending,
// duplicates dropped.
std::vector<double> defaultEdgeAngles(std::uint32_t spp);

// One pixel against one edge direction: `offsets` values of c evenly spaced
// over [-h, h] (endpoints included), the exact coverage at each and the
// estimate from `samples` (positions in [0,1)^2 inside the pixel; none gives
// estimates of 0).
struct EdgeProfile {
    double angleDeg = 0.0;
    std::vector<double> offset, exact, estimate;
    std::uint32_t shades = 0;  // distinct estimates over the offsets
};
EdgeProfile edgeProfile(const std::vector<glm::vec2>& samples, double angleDeg, std::uint32_t offsets);

struct EdgeSettings {
    std::vector<std::uint32_t> samplers;  // gpu::kSampler*; empty: every sampler
    std::uint32_t spp = 64;
    std::uint32_t seed = 0;
    std::vector<double> anglesDeg;        // empty: defaultEdgeAngles(spp)
    std::uint32_t offsets = 1001;
    // Pixels [0, blockSide)^2 of an imageSide x imageSide image, so per-pixel
    // scrambles and jitters are averaged over.
    std::uint32_t blockSide = 16;
    std::uint32_t imageSide = 256;
};

struct EdgeCurve {
    std::string sampler;
    EdgeProfile profile;
};

// One sampler at one angle, over the offsets and the pixels.
struct EdgeRow {
    std::string sampler;
    double angleDeg = 0.0;
    std::uint32_t pixels = 0;    // 1 for regular and rotated: the same pattern in every pixel
    // Distinct estimates per pixel over the offsets, mean over pixels. Two
    // samples whose projections on n lie within one offset step,
    // 2h / (offsets - 1), can share a shade, so random patterns lose a few.
    double shades = 0.0;
    std::uint32_t shadesMin = 0, shadesMax = 0;
    double rmse = 0.0;           // of estimate - exact over offsets and pixels
    double mseStdError = 0.0;    // standard error of rmse^2 from the spread of per-pixel MSEs (0 for 1 pixel)
    double maxAbsError = 0.0;
    // sqrt(mean over the offsets of p (1 - p) / spp), p the exact coverage:
    // the expected RMSE of spp independent uniform samples at this angle.
    double rmseIndependent = 0.0;
};

struct EdgeReport {
    std::uint32_t spp = 0, offsets = 0, blockSide = 0, imageSide = 0, seed = 0;
    std::vector<double> anglesDeg;
    std::vector<EdgeRow> rows;           // sampler-major, angles ascending
    std::vector<EdgeCurve> curves;       // pixel (0, 0) of each measured sampler at each angle
    std::vector<std::string> skipped;    // "bluenoise: ..." for samplers the spp does not suit
    const EdgeRow* row(const std::string& sampler, double angleDeg) const;
};

// Throws strata::Error for spp 0, no offsets, an empty block, or when no
// requested sampler suits the spp.
EdgeReport measureEdges(const vk::Context& ctx, const EdgeSettings& settings);
// The same refusals without a device (the command line checks them while parsing).
void checkEdgeSettings(const EdgeSettings& settings);

// The table as CSV (one line per row) and as aligned text, and one line per
// sampler stating the result in words.
std::string edgesCsv(const EdgeReport& report);
std::string edgesTable(const EdgeReport& report);
std::vector<std::string> edgesSummary(const EdgeReport& report);

struct EdgesCommand {
    EdgeSettings settings;
    std::string table;  // .csv, optional
    std::string plot;   // .png or .exr, optional
    int device = -1;
    bool validation = false;
};

// Measures, prints the table and the summary, writes the files; an output
// that cannot be written is rejected before any work. The settings and file
// names are as the command line checked them (cli/checks.h).
int runEdges(const EdgesCommand& cmd);

}  // namespace strata
