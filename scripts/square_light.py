#!/usr/bin/env python3
"""Closed-form direct lighting of scenes/square-light.gltf, checked numerically.

The scene: a Lambertian plane y = 0 (albedo a) lit by a square emitter of
side 2w at height h, parallel to the plane, centred above the origin, facing
down, one-sided, radiance Le, black (baseColor 0). The irradiance at a point
p = (x, 0, z) of the plane is

    E(p) = pi Le F(p)

with F the form factor from a differential area at p (normal +Y) to the
square. For a parallel rectangle of sides A, B at height h with one corner
straight above the differential area (Howell, "A Catalog of Radiation Heat
Transfer Configuration Factors", 3rd ed., case B-3):

    F = 1/(2 pi) [ X/sqrt(1+X^2) atan(Y/sqrt(1+X^2))
                 + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2)) ],   X = A/h, Y = B/h.

The integrand cos cos' / (pi r^2) is even in both in-plane coordinates, so
the integral over [0, u] x [0, v] is sign(u) sign(v) F(|u|/h, |v|/h), and
any axis-aligned rectangle [x0, x1] x [z0, z1] (relative to p) is the signed
sum of its four corners: G(x1, z1) - G(x0, z1) - G(x1, z0) + G(x0, z0).

The plane's outgoing radiance is L(p) = (a / pi) E(p) = a Le F(p) at every
max depth >= 1: the emitter reflects nothing and emits only downwards, and
the flat plane cannot see itself. At max depth 0 the plane is black.

Run to print F and L at a few points next to two independent numerical
estimates (deterministic output):

    python3 scripts/square_light.py
"""

import math
import random

# scenes/square-light.gltf (scripts/make_scenes.py writes it from these).
HALF_SIDE = 0.5    # w
HEIGHT = 1.0       # h
ALBEDO = 0.5       # a
LE = 1.0           # emitted radiance


def corner_form_factor(u, v, h):
    """Form factor to the rectangle [0, u] x [0, v] at height h, signed by sign(u) sign(v)."""
    if u == 0.0 or v == 0.0:
        return 0.0
    x, y = abs(u) / h, abs(v) / h
    sx, sy = math.sqrt(1.0 + x * x), math.sqrt(1.0 + y * y)
    f = (x / sx * math.atan(y / sx) + y / sy * math.atan(x / sy)) / (2.0 * math.pi)
    return math.copysign(1.0, u) * math.copysign(1.0, v) * f


def form_factor(px, pz, w=HALF_SIDE, h=HEIGHT):
    """Form factor from (px, 0, pz), normal +Y, to the square [-w, w]^2 at y = h."""
    x0, x1, z0, z1 = -w - px, w - px, -w - pz, w - pz
    g = corner_form_factor
    return g(x1, z1, h) - g(x0, z1, h) - g(x1, z0, h) + g(x0, z0, h)


def radiance(px, pz):
    """Outgoing radiance of the plane at (px, 0, pz), max depth >= 1."""
    return ALBEDO * LE * form_factor(px, pz)


def form_factor_quadrature(px, pz, n, w=HALF_SIDE, h=HEIGHT):
    """Midpoint rule with n x n cells of F = (1/pi) int cos cos' / r^2 dA = (h^2/pi) int dA / r^4."""
    d = 2.0 * w / n
    total = 0.0
    for i in range(n):
        x = -w + (i + 0.5) * d - px
        for j in range(n):
            z = -w + (j + 0.5) * d - pz
            r2 = x * x + z * z + h * h
            total += 1.0 / (r2 * r2)
    return h * h / math.pi * total * d * d


def form_factor_monte_carlo(px, pz, n, seed, w=HALF_SIDE, h=HEIGHT):
    """F is the fraction of cosine-distributed directions from p that hit the
    square (Nusselt analog). Returns (estimate, standard error)."""
    rng = random.Random(seed)
    hits = 0
    for _ in range(n):
        r, phi = math.sqrt(rng.random()), 2.0 * math.pi * rng.random()
        dx, dz = r * math.cos(phi), r * math.sin(phi)
        dy = math.sqrt(max(0.0, 1.0 - r * r))
        if dy <= 0.0:
            continue
        s = h / dy
        hits += abs(px + s * dx) <= w and abs(pz + s * dz) <= w
    f = hits / n
    return f, math.sqrt(f * (1.0 - f) / n)


def main():
    points = [(0.0, 0.0), (0.25, 0.1), (0.5, 0.5), (0.7, -0.3), (2.0, 1.0), (-3.0, 0.2)]
    print("(x, z)          F analytic    F midpoint    difference  "
          "F Monte Carlo (se), 4e6 directions   L = a Le F")
    for px, pz in points:
        f = form_factor(px, pz)
        q = form_factor_quadrature(px, pz, 1000)
        mc, se = form_factor_monte_carlo(px, pz, 4000000, seed=1)
        print(f"({px:5.2f}, {pz:5.2f})  {f:.10f}  {q:.10f}  {f - q:+.1e}  "
              f"{mc:.6f} ({se:.6f}) {(mc - f) / se:+5.2f} se  {radiance(px, pz):.10f}")


if __name__ == "__main__":
    main()
