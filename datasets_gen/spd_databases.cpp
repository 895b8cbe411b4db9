// SPD databases (Haines et al., SPD 3.14, public domain): balls.c, jacks.c, lattice.c, shells.c,
// tetra.c, rebuilt from their rules through the SPD library rules of spd_lib.h.
#include "datasets_gen/spd_databases.h"

#include "datasets_gen/spd_lib.h"
#include "datasets_gen/sphere_flake.h"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace rtlab::gen::spd {

namespace {

constexpr double pi = std::numbers::pi;
const Vec3d sky_blue{0.078, 0.361, 0.753};  // "UNC sky blue", the usual SPD background

std::uint64_t ipow(std::uint64_t b, int e) {
    std::uint64_t r = 1;
    for (int i = 0; i < e; ++i) {
        r *= b;
    }
    return r;
}

// ---- balls: the sphere flake, depth-first (a sphere, then each child's whole sub-flake).

void balls_recurse(Writer& w, int depth, const Vec3d& center, double radius, const Vec3d& dir) {
    w.sphere(center, radius);
    if (depth == 0) {
        return;
    }
    const double scale = radius * (1.0 + 1.0 / 3.0);
    for (int k = 0; k < 9; ++k) {
        const Vec3d c = flake_rotate(dir, flake_child_offset(k)) * scale + center;
        balls_recurse(w, depth - 1, c, radius * (1.0 / 3.0), (c - center) / scale);
    }
}

nff::Document balls(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({2.1, 1.3, 1.7}, {0, 0, 0}, {0, 0, 1}, 45, 0.01, 512, 512);
    w.light({4, 3, 2});
    w.light({1, -4, 4});
    w.light({-3, 1, 5});
    w.color({1, 0.75, 0.33}, 0.8, 0, 0, 0, 1);
    w.polygon({{12, 12, -0.5}, {-12, 12, -0.5}, {-12, -12, -0.5}, {12, -12, -0.5}});
    w.color({1, 0.9, 0.7}, 0.5, 0.5, 37, 0, 1);
    balls_recurse(w, sf, {0, 0, 0}, 0.5, {0, 0, 1});
    return w.take();
}

nff::Counts balls_counts(int sf) {
    return {flake_sphere_count(sf), 0, 1, 0, 3};
}

// ---- jacks: three crossed cylinders with spheres on their ends; a half-size copy in each octant,
// recursively; everything turned -20 degrees about Y, then -30 about X.

void jack(Writer& w) {
    w.push();
    w.apply(scale({0.75, 0.75, 0.75}));
    w.cone({-1, 0, 0}, 0.1, {1, 0, 0}, 0.1);
    w.cone({0, -1, 0}, 0.1, {0, 1, 0}, 0.1);
    w.cone({0, 0, -1}, 0.1, {0, 0, 1}, 0.1);
    for (const Vec3d& c : {Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}, Vec3d{-1, 0, 0},
                           Vec3d{0, -1, 0}, Vec3d{0, 0, -1}}) {
        w.sphere(c, 0.2);
    }
    w.pop();
}

void jacks_recurse(Writer& w, int depth, int max_depth) {
    jack(w);
    if (depth >= max_depth) {
        return;
    }
    for (const double i : {-0.5, 0.5}) {
        for (const double j : {-0.5, 0.5}) {
            for (const double k : {-0.5, 0.5}) {
                w.push();
                w.apply(translate({i, j, k}));
                w.apply(scale({0.5, 0.5, 0.5}));
                jacks_recurse(w, depth + 1, max_depth);
                w.pop();
            }
        }
    }
}

nff::Document jacks(int sf) {
    Writer w;
    w.background({0.2, 0.05, 0.2});
    w.view({0, 0, -8}, {0, 0, 0}, {0, 1, 0}, 25, 0.001, 256, 256);
    w.light({-10, 3, -20});
    w.push();
    w.apply(rotate(0, -30 * pi / 180.0));
    w.apply(rotate(1, -20 * pi / 180.0));
    w.color({0.737, 0.561, 0.561}, 0.7, 0.7, 20, 0, 1);
    jacks_recurse(w, 1, sf);
    w.pop();
    return w.take();
}

nff::Counts jacks_counts(int sf) {
    const std::uint64_t n = (ipow(8, sf) - 1) / 7;  // jacks over all levels
    return {6 * n, 3 * n, 0, 0, 1};
}

// ---- lattice: (SF+1)^3 shiny spheres on a unit cube lattice joined by matte cylinders.

nff::Document lattice(int sf) {
    Writer w;
    const double n = sf;
    const double inv = 1.0 / n;
    const double r1 = 0.25 / n;
    const double r2 = 0.0625 / n;
    const double delta = (r1 * (1.0 - std::sqrt(0.0625 / 0.25))) * 0.99;
    w.background(sky_blue);
    const double mid = (static_cast<double>(sf >> 1) + 0.5) * inv;
    w.view({mid, 1.0, 1.0 - 1.0 / static_cast<double>(sf << 1)},
           {mid, -1.0, -1.0 - 1.0 / static_cast<double>(sf << 1)}, {0.2, 1.0, 0.0}, 60, 0, 512,
           512);
    for (const Vec3d& l : {Vec3d{2, 0.5, 0.5}, Vec3d{-1, 0.5, 0.5}, Vec3d{0.5, 2, 0.5},
                           Vec3d{0.5, -1, 0.5}, Vec3d{0.5, 0.5, 2}, Vec3d{0.5, 0.5, -1}}) {
        w.light(l);
    }
    for (int x = 0; x <= sf; ++x) {
        const double x0 = x / n;
        for (int y = 0; y <= sf; ++y) {
            const double y0 = y / n;
            for (int z = 0; z <= sf; ++z) {
                const double z0 = z / n;
                w.color({0.9, 0.9, 0.9}, 0.5, 0.5, 37, 0, 0);
                w.sphere({x0, y0, z0}, r1);
                if (x != sf) {
                    w.color({0.9, 0.1, 0.1}, 0.99, 0, 0, 0, 0);
                    w.cone({x0 + delta, y0, z0}, r2, {x0 + inv - delta, y0, z0}, r2);
                }
                if (y != sf) {
                    w.color({0.1, 0.9, 0.1}, 0.99, 0, 0, 0, 0);
                    w.cone({x0, y0 + delta, z0}, r2, {x0, y0 + inv - delta, z0}, r2);
                }
                if (z != sf) {
                    w.color({0.1, 0.1, 0.9}, 0.99, 0, 0, 0, 0);
                    w.cone({x0, y0, z0 + delta}, r2, {x0, y0, z0 + inv - delta}, r2);
                }
            }
        }
    }
    return w.take();
}

nff::Counts lattice_counts(int sf) {
    const auto n = static_cast<std::uint64_t>(sf);
    return {(n + 1) * (n + 1) * (n + 1), 3 * n * (n + 1) * (n + 1), 0, 0, 6};
}

// ---- shells: Pickover's seashell (IEEE CG&A, November 1989): spheres on a logarithmic spiral,
// angle 18 pi i / steps for i in [-2 steps / 3, steps / 3], steps = 180 * 2^SF.

long shells_steps(int sf) {
    return static_cast<long>(180.0 * std::pow(2.0, sf));
}

nff::Document shells(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({-6, -60, 35}, {0, 8, -15}, {0, 0, 1}, 45, 0.5, 512, 512);
    w.light({-100, -100, 100});
    w.color({1, 0.8, 0.4}, 0.8, 0.2, 10, 0, 1);
    const long steps = shells_steps(sf);
    for (long i = -steps * 2 / 3; i <= steps / 3; ++i) {
        const double angle = 3.0 * 6.0 * pi * static_cast<double>(i) / static_cast<double>(steps);
        const double r = std::exp(0.15 * angle);
        w.sphere({r * std::sin(angle), r * std::cos(angle), -2.0 * r}, r);
    }
    return w.take();
}

nff::Counts shells_counts(int sf) {
    const long steps = shells_steps(sf);
    return {static_cast<std::size_t>(steps / 3 - (-steps * 2 / 3) + 1), 0, 0, 0, 1};
}

// ---- tetra: Sierpinski tetrahedron (Glassner 1984; Kay & Kajiya 1986): SF-1 levels of four
// half-size tetrahedra at alternate cube corners; leaves give 4 triangles each.

void tetra_recurse(Writer& w, int depth, const Vec3d& c, double half) {
    std::vector<Vec3d> corners;
    for (int x = -1; x <= 1; x += 2) {
        for (int y = -1; y <= 1; y += 2) {
            for (int z = -1; z <= 1; z += 2) {
                if (x * y * z == 1) {
                    corners.push_back(c + Vec3d{double(x), double(y), double(z)} *
                                              (depth <= 1 ? half : half / 2.0));
                }
            }
        }
    }
    if (depth > 1) {
        for (const Vec3d& sub : corners) {
            tetra_recurse(w, depth - 1, sub, half / 2.0);
        }
        return;
    }
    // Face f uses corners f, f+1, f+2 (mod 4), reversed for odd f: outward winding.
    for (int f = 0; f < 4; ++f) {
        std::array<int, 3> o{f % 4, (f + 1) % 4, (f + 2) % 4};
        if (f % 2 == 1) {
            std::swap(o[0], o[2]);
        }
        w.polygon({corners[static_cast<std::size_t>(o[0])], corners[static_cast<std::size_t>(o[1])],
                   corners[static_cast<std::size_t>(o[2])]});
    }
}

nff::Document tetra(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({1.022846, -3.177154, -2.174512}, {-0.004103, -0.004103, 0.216539},
           {-0.816497, -0.816497, 0.816497}, 45, 1, 512, 512);
    w.light({2, -18, -5});
    w.color({1, 0.2, 0.2}, 1, 0, 0, 0, 0);
    tetra_recurse(w, sf, {0, 0, 0}, 1.0);
    return w.take();
}

nff::Counts tetra_counts(int sf) {
    return {0, 0, ipow(4, sf), 0, 1};
}

}  // namespace

std::span<const Database> databases() {
    static const std::array<Database, 5> table{{
        {"balls", 0, 4, 12, balls, balls_counts},
        {"jacks", 1, 3, 9, jacks, jacks_counts},
        {"lattice", 1, 12, 400, lattice, lattice_counts},
        {"shells", 1, 5, 20, shells, shells_counts},
        {"tetra", 1, 6, 13, tetra, tetra_counts},
    }};
    return table;
}

const Database* find_database(std::string_view name) {
    for (const Database& d : databases()) {
        if (d.name == name) {
            return &d;
        }
    }
    return nullptr;
}

}  // namespace rtlab::gen::spd
