#include "pack/env_tables.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace strata {
namespace {

// f(x, y) of the distribution: luminance of the map texel times sin(theta) at
// the centre of its row.
std::vector<double> texelWeights(const Environment& env) {
    const int w = env.width, h = env.height;
    std::vector<double> f(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        const double sinTheta = std::sin(std::numbers::pi * (y + 0.5) / h);
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const glm::dvec3 c(env.rgb[3 * i], env.rgb[3 * i + 1], env.rgb[3 * i + 2]);
            f[i] = luminance(c) * sinTheta;
        }
    }
    return f;
}

// Density (per unit of the [0,1] domain) and CDF of a piecewise-constant
// function of n cells; uniform when it is zero everywhere.
void piecewiseConstant(const double* f, std::size_t n, float* pdf, float* cdf) {
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) total += f[i];
    double run = 0.0;
    cdf[0] = 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
        const double p = total > 0.0 ? f[i] / total : 1.0 / static_cast<double>(n);
        pdf[i] = static_cast<float>(p * static_cast<double>(n));
        run += p;
        cdf[i + 1] = static_cast<float>(run);
    }
    cdf[n] = 1.0f;
}

}  // namespace

glm::dvec3 envDirection(double u, double v, double rotation) {
    const double theta = std::numbers::pi * v, phi = 2.0 * std::numbers::pi * (u - 0.5);
    const glm::dvec3 m(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
    const double c = std::cos(rotation), s = std::sin(rotation);  // R_y(rotation) m
    return {c * m.x + s * m.z, m.y, -s * m.x + c * m.z};
}

glm::dvec2 envUv(const glm::dvec3& d, double rotation) {
    const double c = std::cos(rotation), s = std::sin(rotation);  // R_y(-rotation) d
    const glm::dvec3 m(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
    const double u = (m.x == 0.0 && m.z == 0.0) ? 0.5 : 0.5 + std::atan2(m.x, -m.z) / (2.0 * std::numbers::pi);
    return {u, std::acos(std::clamp(m.y / glm::length(m), -1.0, 1.0)) / std::numbers::pi};
}

std::vector<float> buildEnvTables(const Environment& env) {
    const std::size_t w = static_cast<std::size_t>(env.width), h = static_cast<std::size_t>(env.height);
    if (w == 0 || h == 0) return {};
    const std::vector<double> f = texelWeights(env);
    std::vector<float> t(2 * h + 1 + h * w + h * (w + 1));
    std::vector<double> rows(h, 0.0);
    for (std::size_t y = 0; y < h; ++y) {
        for (std::size_t x = 0; x < w; ++x) rows[y] += f[y * w + x];
        piecewiseConstant(&f[y * w], w, &t[2 * h + 1 + y * w], &t[2 * h + 1 + h * w + y * (w + 1)]);
    }
    piecewiseConstant(rows.data(), h, &t[0], &t[h]);
    return t;
}

std::vector<glm::vec4> envTexels(const Environment& env) {
    const std::size_t n = static_cast<std::size_t>(env.width) * env.height;
    std::vector<glm::vec4> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = glm::vec4(env.rgb[3 * i], env.rgb[3 * i + 1], env.rgb[3 * i + 2], 0.0f);
    return out;
}

double envMeanLuminance(const Environment& env) {
    const double scale = luminance(glm::dvec3(env.scale));
    if (env.width == 0 || env.height == 0) return scale;
    // Each row spans theta in [y, y + 1] pi / h: its share of the sphere is
    // (cos theta0 - cos theta1) / 2, split evenly over its w texels.
    const int w = env.width, h = env.height;
    double sum = 0.0;
    for (int y = 0; y < h; ++y) {
        const double share = 0.5 * (std::cos(std::numbers::pi * y / h) - std::cos(std::numbers::pi * (y + 1) / h)) / w;
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            sum += share * luminance(glm::dvec3(env.rgb[3 * i], env.rgb[3 * i + 1], env.rgb[3 * i + 2]));
        }
    }
    return scale * sum;
}

}  // namespace strata
