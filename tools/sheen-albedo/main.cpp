// Writes the directional albedo table of KHR_materials_sheen's lobe, run at
// build time: sheen-albedo OUT.h. The lobe is the extension's (Charlie
// distribution, Estevez & Kulla 2017, alpha = sheenRoughness^2, with their
// visibility fit), sheen colour 1:
//
//   E(mu, r) = integral over wi of D(h) / ((1 + L(mu) + L(wi.z)) 4 mu) dwi
//            = integral over h of D(h) (wo.h) / ((1 + L(mu) + L(wi.z)) mu) dh,
//
// wi the mirror of wo = (sqrt(1 - mu^2), 0, mu) about h, counted where
// wo.h > 0 and wi.z > 0. Nodes: mu_i = max((i / (M - 1))^3, kMuMin),
// r_j = (s0 + (1 - s0) j / (R - 1))^2, s0 = sqrt(kSheenRoughnessMin); the
// shader interpolates bilinearly in (mu^(1/3), sqrt(r)) (lib/sheen.glsl).
// Quadrature: midpoint rule in phi (half circle, doubled: the integrand is
// even in phi) and in x with theta_h = pi/2 (1 - (1 - x)^3), which crowds
// the nodes near the horizon, where D peaks for small roughness.
//
// The output is a header for GLSL (the node constants) and C++ (they and
// the table, which packing puts at the start of the texture words:
// pack/textures.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace {

constexpr int kMu = 32, kRoughness = 32;
constexpr double kSheenRoughnessMin = 0.01;
constexpr double kMuMin = 1.0e-4;
constexpr int kTheta = 512, kPhi = 256;
constexpr double kPi = std::numbers::pi;

// The extension's visibility fit (its l(x, alpha_g) and lambda_sheen).
double fitL(double x, double alpha) {
    const double t = (1.0 - alpha) * (1.0 - alpha);
    const double a = 21.5473 + (25.3245 - 21.5473) * t;
    const double b = 3.82987 + (3.32435 - 3.82987) * t;
    const double c = 0.19823 + (0.16801 - 0.19823) * t;
    const double d = -1.97760 + (-1.27393 + 1.97760) * t;
    const double e = -4.32054 + (-4.85967 + 4.32054) * t;
    return a / (1.0 + b * std::pow(x, c)) + d * x + e;
}

double lambda(double cosTheta, double alpha) {
    return cosTheta < 0.5 ? std::exp(fitL(cosTheta, alpha))
                          : std::exp(2.0 * fitL(0.5, alpha) - fitL(1.0 - cosTheta, alpha));
}

double albedo(double mu, double alpha) {
    const double sinO = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    const double lo = lambda(mu, alpha);
    const double norm = (2.0 + 1.0 / alpha) / (2.0 * kPi);
    double sum = 0.0;
    for (int i = 0; i < kTheta; ++i) {
        const double x = (i + 0.5) / kTheta, y = 1.0 - x;
        const double theta = 0.5 * kPi * (1.0 - y * y * y);
        const double dTheta = 1.5 * kPi * y * y / kTheta;
        const double ch = std::cos(theta), sh = std::sin(theta);
        const double d = norm * std::pow(sh, 1.0 / alpha);  // sin^(1/alpha) = (sin^2)^(1/(2 alpha))
        if (d == 0.0) continue;
        for (int k = 0; k < kPhi; ++k) {
            const double phi = (k + 0.5) / kPhi * kPi;
            const double hx = sh * std::cos(phi), hz = ch;
            const double woh = sinO * hx + mu * hz;
            if (woh <= 0.0) continue;
            const double wiz = 2.0 * woh * hz - mu;
            if (wiz <= 0.0) continue;
            sum += d * woh / ((1.0 + lo + lambda(wiz, alpha)) * mu) * sh * dTheta;
        }
    }
    return sum * 2.0 * kPi / kPhi;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: sheen-albedo OUT.h\n");
        return 2;
    }
    const std::string tmp = std::string(argv[1]) + ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "w");
    if (!f) {
        std::perror(tmp.c_str());
        return 2;
    }
    std::fprintf(f,
                 "// Written by tools/sheen-albedo at build time: the directional albedo E(mu, r)\n"
                 "// of KHR_materials_sheen's lobe (tools/sheen-albedo/main.cpp says how).\n"
                 "#ifndef STRATA_SHEEN_ALBEDO_H\n#define STRATA_SHEEN_ALBEDO_H\n"
                 "#ifdef __cplusplus\n#define STRATA_SHEEN_CONST(type, name, value) inline constexpr type name = value\n"
                 "#else\n#define STRATA_SHEEN_CONST(type, name, value) const type name = value\n#endif\n"
                 "STRATA_SHEEN_CONST(int, kSheenAlbedoMuCount, %d);\n"
                 "STRATA_SHEEN_CONST(int, kSheenAlbedoRoughnessCount, %d);\n"
                 "STRATA_SHEEN_CONST(float, kSheenRoughnessMin, %.9g);\n"
                 "STRATA_SHEEN_CONST(float, kSheenAlbedoMuMin, %.9g);\n"
                 "STRATA_SHEEN_CONST(int, kSheenAlbedoEntries, %d);\n"
                 "#ifdef __cplusplus\n"
                 "// Row j (roughness node j), column i (mu node i).\n"
                 "inline constexpr float kSheenAlbedo[%d] = {\n",
                 kMu, kRoughness, kSheenRoughnessMin, kMuMin, kMu * kRoughness, kMu * kRoughness);
    const double s0 = std::sqrt(kSheenRoughnessMin);
    for (int j = 0; j < kRoughness; ++j) {
        const double s = s0 + (1.0 - s0) * j / (kRoughness - 1);
        const double alpha = s * s * s * s;  // r = s^2, alpha = r^2
        for (int i = 0; i < kMu; ++i) {
            const double t = double(i) / (kMu - 1);
            const double mu = std::max(t * t * t, kMuMin);
            const bool last = i == kMu - 1 && j == kRoughness - 1;
            const double e = albedo(mu, alpha);
            std::fprintf(f, "%.7g%s", e < 1.0e-12 ? 0.0 : e, last ? "\n" : (i == kMu - 1 ? ",\n" : ", "));
        }
    }
    std::fprintf(f, "};\n#endif\n#undef STRATA_SHEEN_CONST\n#endif\n");
    if (std::fclose(f) != 0 || std::rename(tmp.c_str(), argv[1]) != 0) {
        std::perror(argv[1]);
        return 2;
    }
    return 0;
}
