// Implicit surfaces on stiff rays: rays tangent to a torus (exact double roots over the tube's
// top circle and the outer equator), grazing it (shifted off tangency by 1e-12 .. 1e-2 tube radii
// either way), along its axis (and parallel to it), and random rays as the baseline. Closed form,
// Newton and Laguerre (intersect/implicit/methods.h) in float and double against the exact first
// root (Sturm sequence over Q refined in MPFR, crosscheck/exact.h): missed roots, t error, ns/ray.
#include "crosscheck/exact.h"
#include "intersect/implicit/methods.h"
#include "stability/cases.h"
#include "stability/exact_judge.h"

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace rtlab::stab {

namespace {

constexpr std::array<const char*, 6> set_names{"tangent_top",   "tangent_outer", "grazing_top",
                                               "grazing_outer", "axis",          "random"};

/// Torus with integer centre, major 2^k * {1, 1.5} and minor major * {1/4, 1/2} (exact in float),
/// axis z. A ray of set `set` (see set_names); all values rounded to T, stored in double. The
/// tangent sets are exactly tangent (an exact double root); the grazing sets pass 1e-12 .. 1e-2
/// tube radii inside or outside the tangent at any azimuth (rounding decides below ~1e-7 in
/// float).
template <class T>
void make_sample(std::size_t set, Sampler& rng, Torus<double>& tor, Rayd& ray) {
    const auto round = [](const Vec3d& v) { return Vec3d(Vec3<T>(v)); };
    const double major = std::ldexp(rng.index(2) ? 1.5 : 1.0, static_cast<int>(rng.index(5)) - 2);
    const double minor = major * (rng.index(2) ? 0.25 : 0.5);
    const Vec3d c{std::round(rng.uniform(-50, 50)), std::round(rng.uniform(-50, 50)),
                  std::round(rng.uniform(-50, 50))};
    tor = {c, major, minor};
    const double size = major + minor;
    // Tangent sets: azimuth k * 90 degrees with exact unit vectors, so the tangent point and the
    // direction are exact and the ray polynomial has an exact double root. Others: any azimuth.
    const bool exact_azimuth = set == 0 || set == 1;
    const double phi = rng.uniform(0, 2 * std::numbers::pi);
    const std::size_t quarter = rng.index(4);
    constexpr std::array<Vec3d, 4> axes{Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{-1, 0, 0},
                                        Vec3d{0, -1, 0}};
    const Vec3d radial = exact_azimuth ? axes[quarter] : Vec3d{std::cos(phi), std::sin(phi), 0};
    const Vec3d along =
        exact_azimuth ? axes[(quarter + 1) % 4] : Vec3d{-std::sin(phi), std::cos(phi), 0};
    const double sign = rng.index(2) ? 1.0 : -1.0;
    switch (set) {
    case 0:
    case 2: {  // over the top (or bottom) circle of the tube: plane z = +-minor, tangent to rho = R
        const double delta = set == 2 ? sign * std::pow(10.0, rng.uniform(-12, -2)) * minor : 0;
        const double zs = rng.index(2) ? 1.0 : -1.0;
        const Vec3d touch = c + radial * major + Vec3d{0, 0, zs * (minor + delta)};
        const Vec3d dir = along * (rng.index(2) ? 1.0 : -1.0);
        ray = {round(touch - dir * (size * rng.uniform(1, 3))), round(dir)};
        break;
    }
    case 1:
    case 3: {  // in the equator plane, tangent to the outer circle rho = R + r
        const double delta = set == 3 ? sign * std::pow(10.0, rng.uniform(-12, -2)) * minor : 0;
        const Vec3d touch = c + radial * (size + delta);
        const Vec3d dir = along * (rng.index(2) ? 1.0 : -1.0);
        ray = {round(touch - dir * (size * rng.uniform(1, 3))), round(dir)};
        break;
    }
    case 4: {  // parallel to the axis at distance rho (an eighth exactly on the axis)
        const double rho = rng.index(8) == 0 ? 0.0 : rng.uniform(0, 1.1 * size);
        const double dz = rng.index(2) ? 1.0 : -1.0;
        ray = {round(c + radial * rho - Vec3d{0, 0, dz * 2 * size}), Vec3d{0, 0, dz}};
        break;
    }
    default: {  // random: from 2 sizes away towards a point of the box
        const Vec3d aim = c + Vec3d{rng.uniform(-size, size), rng.uniform(-size, size),
                                    rng.uniform(-minor, minor)};
        const Vec3d org = c + rng.unit() * (2 * size);
        ray = {round(org), round(aim - org)};
        break;
    }
    }
}

template <class T>
void run_precision(const Options& opt, std::vector<Row>& rows) {
    const std::size_t per_set = std::max<std::size_t>(1, opt.rays / set_names.size());
    for (std::size_t set = 0; set < set_names.size(); ++set) {
        Sampler rng(opt.seed, (std::is_same_v<T, float> ? 900 : 950) + set);
        std::vector<Torus<double>> tori(per_set);
        std::vector<Rayd> rays_d(per_set);
        for (std::size_t i = 0; i < per_set; ++i) {
            make_sample<T>(set, rng, tori[i], rays_d[i]);
        }
        const std::vector<ExactTruth> truth = exact_truths(per_set, [&](std::size_t i) {
            return xcheck::exact_first_root(
                xcheck::exact_torus_along(tori[i], rays_d[i].org, rays_d[i].dir), rays_d[i].tmin,
                rays_d[i].tmax);
        });
        const std::vector<Ray<T>> rays = rays_in<T>(rays_d);
        const std::size_t exact_hits = exact_hit_count(truth);
        for_each_implicit_method<Torus, T>([&]<class M>() {
            const MethodTally t = judge<M>(rays, truth, [&](std::size_t i) {
                return Torus<T>{Vec3<T>(tori[i].center), static_cast<T>(tori[i].major),
                                static_cast<T>(tori[i].minor)};
            });
            Row r = tally_row(std::string("implicit/") + set_names[set], std::string(M::name),
                              precision_of<T>(), t,
                              "exact hits " + std::to_string(exact_hits) + " of " +
                                  std::to_string(per_set) + " (false misses = missed roots)");
            r.failure_kind = "missed roots + false hits";
            if (set < 2) {
                r.note +=
                    "; exact double root: the rounded ray polynomial splits it into a "
                    "complex pair or two close roots, so rounding decides hit or miss, "
                    "and t is good to ~sqrt(eps) only";
            }
            rows.push_back(r);
        });
    }
}

}  // namespace

std::vector<Row> run_implicit(const Options& opt) {
    std::vector<Row> rows;
    run_precision<float>(opt, rows);
    run_precision<double>(opt, rows);
    return rows;
}

}  // namespace rtlab::stab
