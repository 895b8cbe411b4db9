// Cones and cylinders on stiff rays: grazing rays (in a tangent plane, moved off the surface by
// 1e-12 .. 1e-2 radii either way), rays parallel to the cone's axis near its wall, rays along the
// coordinate axes on axis-aligned cylinders (the SPD's lattice and jacks), thin needles (radius /
// height 1e-6 .. 1e-2) and small far cones (D/r 1e3 .. 1e7), with random rays as the baseline.
// Every cone method (intersect/cone/methods.h) in float and double against the exact answer
// (exact_cone_root: rationals + MPFR, crosscheck/exact.h): false misses and hits, t error, ns/ray.
#include "crosscheck/exact.h"
#include "intersect/cone/methods.h"
#include "stability/cases.h"
#include "stability/exact_judge.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace rtlab::stab {

namespace {

constexpr std::array<const char*, 6> set_names{"grazing", "axis_parallel", "coordinate_axis",
                                               "thin",    "far",           "random"};

/// A unit vector perpendicular to unit n.
Vec3d perpendicular(Sampler& rng, const Vec3d& n) {
    for (;;) {
        const Vec3d v = cross(n, rng.unit());
        if (length_squared(v) > 1e-4) {
            return normalize(v);
        }
    }
}

/// A cone and a ray of set `set` (see set_names), rounded to T and stored in double. Cone i % 3:
/// cylinder, pointed cone, truncated cone; caps on every other one.
template <class T>
void make_sample(std::size_t set, std::size_t i, Sampler& rng, Cone<double>& c, Rayd& ray) {
    const auto round = [](const Vec3d& v) { return Vec3d(Vec3<T>(v)); };
    const auto round_s = [](double x) { return static_cast<double>(static_cast<T>(x)); };
    Vec3d axis = rng.unit();
    if (set == 2) {  // coordinate_axis: axis-aligned cylinders with integer ends
        axis = {0, 0, 0};
        axis[rng.index(3)] = rng.index(2) ? 1.0 : -1.0;
    }
    double r = std::ldexp(1.0, static_cast<int>(rng.index(6)) - 3);
    double h = r * rng.uniform(1, 8);
    if (set == 3) {  // thin: needles
        h = r / std::pow(10.0, rng.uniform(-6, -2));
        r = h * std::pow(10.0, rng.uniform(-6, -2));
    }
    const Vec3d base{std::round(rng.uniform(-50, 50)), std::round(rng.uniform(-50, 50)),
                     std::round(rng.uniform(-50, 50))};
    c.base = base;
    c.apex = round(base + axis * (set == 2 ? std::round(h) + 1 : h));
    c.base_radius = round_s(r);
    c.apex_radius = i % 3 == 0 ? c.base_radius : (i % 3 == 1 ? 0.0 : round_s(r * 0.5));
    c.caps = i % 2 == 0 ? ConeCaps::none : ConeCaps::both;
    const Vec3d e = c.apex - c.base;
    const Vec3d unit_axis = normalize(e);
    const Vec3d radial = perpendicular(rng, unit_axis);
    const double f = rng.uniform(0.05, 0.95);
    const double rf = c.base_radius + (c.apex_radius - c.base_radius) * f;
    const double sign = rng.index(2) ? 1.0 : -1.0;
    const double delta = sign * std::pow(10.0, rng.uniform(-12, -2));
    switch (set) {
    case 0: {  // grazing: in the tangent plane along the generator at f, moved off by delta
        const Vec3d touch = c.base + e * f + radial * (rf * (1 + delta));
        const Vec3d gen = normalize(e + radial * (c.apex_radius - c.base_radius));
        const Vec3d along = cross(unit_axis, radial);
        const Vec3d dir = normalize(along * rng.uniform(0.2, 1) + gen * rng.uniform(-0.5, 0.5));
        ray = {round(touch - dir * (h * rng.uniform(1, 3))), round(dir)};
        break;
    }
    case 1: {  // parallel to the axis at radial distance r_base (1 + delta)
        const double rb = std::max(c.base_radius, c.apex_radius);
        const Vec3d org =
            c.base - unit_axis * (h * rng.uniform(0.5, 2)) + radial * (rb * (1 + delta));
        ray = {round(org), round(unit_axis)};
        break;
    }
    case 2: {  // along a coordinate axis other than the cylinder's, through its wall region
        std::size_t a = 0;
        while (std::abs(unit_axis[a]) > 0.5) {
            a = rng.index(3);
        }
        Vec3d dir{0, 0, 0};
        dir[a] = rng.index(2) ? 1.0 : -1.0;
        Vec3d org = c.base + e * f;
        for (std::size_t k = 0; k < 3; ++k) {
            if (k != a && std::abs(unit_axis[k]) < 0.5) {
                org[k] += rf * rng.uniform(-1.1, 1.1);
            }
        }
        org[a] -= dir[a] * (rf + h * rng.uniform(1, 3));
        ray = {round(org), dir};
        break;
    }
    case 4: {  // far: distance / radius 1e3 .. 1e7, aimed within 1.2 radii of the axis
        const Vec3d aim = c.base + e * f + radial * (rf * rng.uniform(0, 1.2));
        const Vec3d dir = rng.unit();
        const double dist = r * std::pow(10.0, rng.uniform(3, 7));
        ray = {round(aim - dir * dist), round(dir)};
        break;
    }
    default: {  // random and thin: from 2 heights away towards a point near the cone
        const Vec3d aim = c.base + e * rng.uniform(-0.1, 1.1) + radial * (rf * rng.uniform(0, 1.3));
        const Vec3d org = aim + rng.unit() * (2 * (h + r));
        ray = {round(org), round(aim - org)};
        break;
    }
    }
}

template <class T>
void run_precision(const Options& opt, std::vector<Row>& rows) {
    const std::size_t per_set = std::max<std::size_t>(1, opt.rays / set_names.size());
    for (std::size_t set = 0; set < set_names.size(); ++set) {
        Sampler rng(opt.seed, (std::is_same_v<T, float> ? 1200 : 1250) + set);
        std::vector<Cone<double>> cones(per_set);
        std::vector<Rayd> rays_d(per_set);
        for (std::size_t i = 0; i < per_set; ++i) {
            make_sample<T>(set, i, rng, cones[i], rays_d[i]);
        }
        const std::vector<ExactTruth> truth = exact_truths(
            per_set, [&](std::size_t i) { return xcheck::exact_cone_root(cones[i], rays_d[i]); });
        const std::vector<Ray<T>> rays = rays_in<T>(rays_d);
        const std::size_t exact_hits = exact_hit_count(truth);
        for_each_cone_method<T>([&]<class M>() {
            const MethodTally t = judge<M>(rays, truth, [&](std::size_t i) {
                const Cone<double>& c = cones[i];
                return Cone<T>{Vec3<T>(c.base), static_cast<T>(c.base_radius), Vec3<T>(c.apex),
                               static_cast<T>(c.apex_radius), c.caps};
            });
            std::string note =
                "exact hits " + std::to_string(exact_hits) + " of " + std::to_string(per_set);
            if (set < 2 && std::is_same_v<T, float>) {
                note +=
                    "; offsets below ~1e-7 radii are under float's resolution: the rounded ray "
                    "(for axis_parallel, its rounded direction, no longer parallel) decides";
            }
            rows.push_back(tally_row(std::string("cone/") + set_names[set], std::string(M::name),
                                     precision_of<T>(), t, note));
        });
    }
}

}  // namespace

std::vector<Row> run_cone(const Options& opt) {
    std::vector<Row> rows;
    run_precision<float>(opt, rows);
    run_precision<double>(opt, rows);
    return rows;
}

}  // namespace rtlab::stab
