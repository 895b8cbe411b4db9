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

using detail::ipow;
using detail::pi;
using detail::sky_blue;

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
    return {flake_sphere_count(sf), 0, 1, 0, 3, 4};
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
    return {6 * n, 3 * n, 0, 0, 1, 0};
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
    return {(n + 1) * (n + 1) * (n + 1), 3 * n * (n + 1) * (n + 1), 0, 0, 6, 0};
}

// ---- rings: pyramid of objects of 6 pentagonal rings (cylinders joining the edge midpoints of a
// dodecahedron, a sphere on every joint), layer k holding (k+1)^2 objects, a wall behind.

std::array<Vec3d, 30> dodec_points(double minor_radius) {
    std::array<Vec3d, 30> v;
    const double scale_f = 1.0 / (1.0 + minor_radius);
    for (std::size_t i = 0; i < 5; ++i) {
        const double a = static_cast<double>(i) * 2.0 * pi / 5.0;
        v[i] = {scale_f * std::cos(a), scale_f * std::sin(a), 0.0};
    }
    // The dihedral angle's supplement, about X; then 1/10 + k/5 of a turn about Z.
    const Mat4 xm = rotate(0, 2.0 * std::acos(std::cos(pi / 3.0) / std::sin(pi / 5.0)));
    for (std::size_t p = 1; p < 6; ++p) {
        const Mat4 zm = rotate(2, pi * (2.0 * static_cast<double>(p - 1) + 1.0) / 5.0);
        for (std::size_t i = 0; i < 5; ++i) {
            v[5 * p + i] = transform_point(transform_point(v[i], xm), zm);
        }
    }
    return v;
}

nff::Document rings(int sf) {
    Writer w;
    const double radius = 0.07412;
    const double spread = 1.0 / std::sin(pi / 8.0);
    const double y_diff = spread;  // SPREAD_OUT = 1 <= spread
    const double xz_diff = 1.0;
    w.background(sky_blue);
    const Vec3d from{-1.0, -spread, 0.5};
    w.view(from, {from.x, from.y + 1.0, from.z}, {0, 0, 1}, 45, 1, 512, 512);
    w.light({3.0, -spread, 3.0});
    w.light({-4.0, -spread, 1.0});
    w.light({2.0, -spread, -4.0});
    w.color({1, 1, 1}, 1, 0, 0, 0, 0);
    const double wy = y_diff * (sf + 1);
    const double wxz = 1.01 * (wy - from.y) * std::tan(pi / 8.0);
    w.polygon({{wxz + from.x, wy, wxz + from.z},
               {-wxz + from.x, wy, wxz + from.z},
               {-wxz + from.x, wy, -wxz + from.z},
               {wxz + from.x, wy, -wxz + from.z}});
    const std::array<Vec3d, 6> colors{Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1},
                                      Vec3d{0, 1, 1}, Vec3d{1, 0, 1}, Vec3d{1, 1, 0}};
    const std::array<Vec3d, 30> dodec = dodec_points(radius);
    for (int depth = 0; depth < sf; ++depth) {
        for (int oz = 0; oz <= depth; ++oz) {
            for (int ox = 0; ox <= depth; ++ox) {
                const Vec3d offset{xz_diff * (2 * ox - depth), y_diff * (depth + 1),
                                   xz_diff * (2 * oz - depth)};
                for (std::size_t e = 0; e < 30; ++e) {
                    std::size_t prev = e - 1;
                    if (e % 5 == 0) {
                        prev = e + 4;
                        w.color(colors[e / 5], 0.5, 0.2, 37, 0, 0);
                    }
                    const Vec3d base = dodec[e] + offset;
                    w.cone(base, radius, dodec[prev] + offset, radius);
                    w.sphere(base, radius);
                }
            }
        }
    }
    return w.take();
}

nff::Counts rings_counts(int sf) {
    const auto n = static_cast<std::uint64_t>(sf);
    const std::uint64_t objects = n * (n + 1) * (2 * n + 1) / 6;
    return {30 * objects, 30 * objects, 1, 0, 3, 4};
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
    return {static_cast<std::size_t>(steps / 3 - (-steps * 2 / 3) + 1), 0, 0, 0, 1, 0};
}

// ---- tree: Aono & Kunii's botanical tree (IEEE CG&A, May 1984): a cone per branch with a sphere
// on its tip, two sub-branches per branch: turned by the branching angle about X and the
// divergence about Z, contracted, moved to the tip.

void grow_tree(Writer& w, const Mat4& m, const std::array<Mat4, 2>& rst, double scale, int depth) {
    const Vec3d base = transform_point({0, 0, 0}, m);
    const double base_r = scale * 0.15;
    const Vec3d apex = transform_point({0, 0, 1}, m);
    const double apex_r = base_r * 0.67;
    w.cone(base, base_r, apex, apex_r);
    w.sphere(apex, apex_r);
    if (depth == 0) {
        return;
    }
    for (const Mat4& r : rst) {
        grow_tree(w, r * m, rst, scale * 0.67, depth - 1);
    }
}

nff::Document tree(int sf) {
    Writer w;
    w.background(sky_blue);
    w.view({4.5, 0.4, 2.0}, {0, 0, 1.5}, {0, 0, 1}, 45, 1, 512, 512);
    for (const Vec3d& l :
         {Vec3d{-5, 5, 50}, Vec3d{30, -30, 30}, Vec3d{-40, -30, 20}, Vec3d{10, 30, 40},
          Vec3d{-30, 40, 10}, Vec3d{50, 25, 20}, Vec3d{-10, -60, 30}}) {
        w.light(l);
    }
    w.color({0.2, 0.7, 0.2}, 1, 0, 0, 0, 0);
    w.polygon({{50, 50, 0}, {-50, 50, 0}, {-50, -50, 0}, {50, -50, 0}});
    w.color({0.55, 0.4, 0.2}, 1, 0, 0, 0, 0);
    std::array<Mat4, 2> rst;
    const double branch[2] = {40.0, 25.0};
    const double divergence[2] = {90.0, 140.0 + 90.0};
    const double contraction[2] = {0.65, 0.70};
    for (std::size_t i = 0; i < 2; ++i) {
        Mat4 st = scale({contraction[i], contraction[i], contraction[i]});
        st.m[3][2] = 1.0;
        rst[i] = rotate(0, branch[i] * pi / 180.0) * rotate(2, divergence[i] * pi / 180.0) * st;
    }
    grow_tree(w, identity(), rst, 1.0, sf);
    return w.take();
}

nff::Counts tree_counts(int sf) {
    const std::uint64_t n = ipow(2, sf + 1) - 1;
    return {n, n, 1, 0, 7, 4};
}

}  // namespace

std::span<const Database> databases() {
    static const std::array<Database, 11> table{{
        {"balls", 0, 4, 12, balls, balls_counts},
        {"gears", 1, 4, 40, gears, gears_counts},
        {"jacks", 1, 3, 9, jacks, jacks_counts},
        {"lattice", 1, 12, 400, lattice, lattice_counts},
        {"mount", 1, 6, 12, mount, mount_counts},
        {"rings", 1, 7, 60, rings, rings_counts},
        {"shells", 1, 5, 20, shells, shells_counts},
        {"sombrero", 1, 1, 9, sombrero, sombrero_counts},
        {"teapot", 1, 6, 200, teapot, teapot_counts},
        {"tetra", 1, 6, 13, tetra, tetra_counts},
        {"tree", 1, 11, 22, tree, tree_counts},
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
