// Far and small: a sphere of radius r, or a triangle of size s, at distance D from the ray origin
// with D/r from 1e3 to 1e8 per decade, and an Earth-sized sphere (r = 6.4e6 m) under a camera 1 to
// 100 m above it. Shapes and rays are generated in double and rounded to the precision under
// test; the reference is exact for the rounded input (rational quadratic + 256-bit MPFR square
// root for spheres, Cramer's rule over Q for triangles; crosscheck/exact.h).
#include "crosscheck/exact.h"
#include "intersect/sphere/methods.h"
#include "intersect/triangle/methods.h"
#include "stability/cases.h"
#include "stability/exact_judge.h"

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::stab {

namespace {

/// Sphere at distance D (log-uniform in [1, 1e3]) of radius D / ratio from an origin in
/// [-1, 1]^3; the ray aims within 1.2 r of the centre (about 30% miss, some graze).
template <class T>
SphereSamples far_spheres(double ratio, std::size_t n, std::uint64_t seed, std::uint64_t stream) {
    Sampler rng(seed, stream);
    SphereSamples s;
    for (std::size_t i = 0; i < n; ++i) {
        const double dist = std::pow(10.0, rng.uniform(0, 3));
        const double r = dist / ratio;
        const Vec3d org{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        const Vec3d u = rng.unit();
        const Vec3d w = normalize(cross(u, rng.unit()));
        const Vec3d center = org + u * dist + w * (1.2 * r * std::sqrt(rng.uniform(0, 1)));
        s.spheres.push_back({round_to<T>(center), static_cast<double>(static_cast<T>(r))});
        s.rays.push_back({round_to<T>(org), round_to<T>(u * rng.uniform(0.5, 2.0))});
    }
    add_sphere_truth(s);
    return s;
}

/// Earth (r = 6.4e6, centre (0, 0, -6.4e6)) under a camera at (x, y, h), |x|, |y| <= 1 km, h
/// log-uniform in [1, 100] m. down: up to 80 degrees from the nadir; grazing: below the horizon
/// by 0.5 to 1.5 times the dip angle sqrt(2h/R) of the tangent, so about half hit.
template <class T>
SphereSamples earth(bool grazing, std::size_t n, std::uint64_t seed, std::uint64_t stream) {
    constexpr double radius = 6.4e6;
    Sampler rng(seed, stream);
    SphereSamples s;
    for (std::size_t i = 0; i < n; ++i) {
        const double h = std::pow(10.0, rng.uniform(0, 2));
        const Vec3d org{rng.uniform(-1e3, 1e3), rng.uniform(-1e3, 1e3), h};
        const double phi = rng.uniform(0, 2 * std::numbers::pi);
        double below;  // angle below the horizontal
        if (grazing) {
            below = std::sqrt(2 * h / radius) * rng.uniform(0.5, 1.5);
        } else {
            below = std::numbers::pi / 2 - rng.uniform(0, 80) * std::numbers::pi / 180;
        }
        const Vec3d dir{std::cos(below) * std::cos(phi), std::cos(below) * std::sin(phi),
                        -std::sin(below)};
        s.spheres.push_back({Vec3d{0, 0, -radius}, radius});
        s.rays.push_back({round_to<T>(org), round_to<T>(dir)});
    }
    add_sphere_truth(s);
    return s;
}

/// The known cause of a sphere method's errors on a sub-case, for the report.
std::string note_for(const std::string& case_name, std::string_view method) {
    if (case_name == "far_small/earth") {
        return "error from rounding f = o - c at |f| = 6.4e6 (ulp 9.3e-10 m in double, 0.5 m in "
               "float) against heights from 1 m; c = |f|^2 - r^2 cancels likewise";
    }
    if (method == "stable") {
        return "discriminant from the centre's distance to the line: error ~eps D/r";
    }
    return "b^2 - ac cancels: relative error of the discriminant ~eps (D/r)^2";
}

/// Every sphere method in T on the samples, one row each.
template <class T>
void sphere_rows(const SphereSamples& s,
                 const std::string& case_name,
                 const std::string& label,
                 std::vector<Row>& rows) {
    std::vector<Ray<T>> rays;
    for (const Rayd& r : s.rays) {
        rays.push_back(static_cast<Ray<T>>(r));
    }
    for_each_sphere_method<T>([&]<class M>() {
        const MethodTally t = judge<M>(rays, s.truth, [&](std::size_t i) {
            return Sphere<T>{Vec3<T>(s.spheres[i].center), static_cast<T>(s.spheres[i].radius)};
        });
        rows.push_back(tally_row(case_name, std::string(M::name) + " " + label, precision_of<T>(),
                                 t, note_for(case_name, M::name)));
    });
}

/// Triangle of size D / ratio (vertices at that distance from its centre) at distance D
/// (log-uniform in [1, 1e3]); rays from [-1, 1]^3 aim within 1.2 sizes of its centre.
template <class T>
void far_triangle_rows(double ratio,
                       const std::string& label,
                       std::size_t n,
                       std::uint64_t seed,
                       std::uint64_t stream,
                       std::vector<Row>& rows) {
    Sampler rng(seed, stream);
    std::vector<Triangled> tris;
    std::vector<Rayd> rays_d;
    for (std::size_t i = 0; i < n; ++i) {
        const double dist = std::pow(10.0, rng.uniform(0, 3));
        const double size = dist / ratio;
        const Vec3d org{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        const Vec3d u = rng.unit();
        const Vec3d center = org + u * dist;
        tris.push_back({round_to<T>(center + rng.unit() * size),
                        round_to<T>(center + rng.unit() * size),
                        round_to<T>(center + rng.unit() * size)});
        const Vec3d aim = center + rng.ball(1.2 * size);
        rays_d.push_back({round_to<T>(org), round_to<T>(aim - org)});
    }
    const std::vector<ExactTruth> truth = exact_truths(
        n, [&](std::size_t i) { return xcheck::exact_triangle_hit(tris[i], rays_d[i]); });
    const std::vector<Ray<T>> rays = rays_in<T>(rays_d);
    for_each_triangle_method<T>([&]<class M>() {
        const MethodTally t = judge<M>(rays, truth, [&](std::size_t i) {
            return Triangle<T>{Vec3<T>(tris[i].p0), Vec3<T>(tris[i].p1), Vec3<T>(tris[i].p2)};
        });
        rows.push_back(tally_row("far_small/triangle", std::string(M::name) + " " + label,
                                 precision_of<T>(), t,
                                 IntersectionMethod<M> ? "" : "hit/miss only"));
    });
}

template <class T>
void run_precision(const Options& opt, std::vector<Row>& rows) {
    const std::uint64_t base = std::is_same_v<T, float> ? 100 : 200;
    for (int k = 3; k <= 8; ++k) {
        const double ratio = std::pow(10.0, k);
        const std::string label = "D/r=1e" + std::to_string(k);
        sphere_rows<T>(far_spheres<T>(ratio, opt.rays, opt.seed, base + static_cast<unsigned>(k)),
                       "far_small/sphere", label, rows);
    }
    for (int k = 3; k <= 8; ++k) {
        far_triangle_rows<T>(std::pow(10.0, k), "D/s=1e" + std::to_string(k), opt.rays, opt.seed,
                             base + 20 + static_cast<unsigned>(k), rows);
    }
    sphere_rows<T>(earth<T>(false, opt.rays, opt.seed, base + 40), "far_small/earth",
                   "down h=1..100m", rows);
    sphere_rows<T>(earth<T>(true, opt.rays, opt.seed, base + 41), "far_small/earth",
                   "grazing h=1..100m", rows);
}

}  // namespace

std::vector<Row> run_far_small(const Options& opt) {
    std::vector<Row> rows;
    run_precision<float>(opt, rows);
    run_precision<double>(opt, rows);
    return rows;
}

}  // namespace rtlab::stab
