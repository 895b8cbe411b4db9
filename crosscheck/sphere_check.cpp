// Sphere methods against an exact oracle: hit/miss from CGAL Epeck (squared distance of the exact
// window segment or ray to the centre against r^2, and "both ends strictly inside"), reference t
// from the exact rational quadratic (GMP) with a 256-bit MPFR square root.
#include "crosscheck/checks.h"
#include "crosscheck/driver.h"
#include "crosscheck/exact.h"
#include "crosscheck/ray_sets.h"
#include "intersect/sphere/methods.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <cmath>
#include <gmpxx.h>
#include <random>
#include <stdexcept>
#include <tbb/parallel_for.h>

namespace rtlab::xcheck {

namespace {

using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

/// One test: a sphere and a ray, both in float so float and double runs trace the same input.
struct SphereCase {
    Sphere<float> sphere;
    Ray<float> ray;
};

/// The exact answer: hit in [tmin, tmax] and the nearest such t (rounded to double).
struct SphereOracle {
    bool hit = false;
    double t = 0;
};

/// A named ray set with its oracle answers.
struct SphereSet {
    std::string name;
    std::vector<SphereCase> cases;
    std::vector<SphereOracle> oracle;
};

mpq_class exact(float x) {
    return mpq_class(static_cast<double>(x));
}

/// Exact hit/miss by CGAL: the window is the segment [o + tmin d, o + tmax d] (a ray when tmax is
/// infinite); it meets the sphere surface iff its distance to the centre is <= r and not both of
/// its ends lie strictly inside (a ray's far end is always outside).
bool cgal_hit(const SphereCase& c) {
    using P = Epeck::Point_3;
    using V = Epeck::Vector_3;
    const P o(c.ray.org.x, c.ray.org.y, c.ray.org.z);
    const V d(c.ray.dir.x, c.ray.dir.y, c.ray.dir.z);
    const P ctr(c.sphere.center.x, c.sphere.center.y, c.sphere.center.z);
    const Epeck::FT r2 = Epeck::FT(c.sphere.radius) * Epeck::FT(c.sphere.radius);
    const P a = o + d * Epeck::FT(c.ray.tmin);
    if (std::isinf(c.ray.tmax)) {
        // A ray leaves every sphere, so only its distance to the centre matters.
        return CGAL::squared_distance(Epeck::Ray_3(a, d), ctr) <= r2;
    }
    const P b = o + d * Epeck::FT(c.ray.tmax);
    const bool near = CGAL::squared_distance(Epeck::Segment_3(a, b), ctr) <= r2;
    const bool both_inside =
        CGAL::squared_distance(a, ctr) < r2 && CGAL::squared_distance(b, ctr) < r2;
    return near && !both_inside;
}

/// The oracle for one case. g(t) = a t^2 + 2 b t + c is |o + t d - centre|^2 - r^2 in exact
/// rationals; the nearest root in the window follows from the exact signs of g at tmin and tmax
/// and the vertex position, and is evaluated with MPFR. Hit/miss itself comes from CGAL.
SphereOracle oracle(const SphereCase& sc) {
    const Vec3f& o = sc.ray.org;
    const Vec3f& d = sc.ray.dir;
    const Vec3f& ctr = sc.sphere.center;
    mpq_class a = 0, b = 0, c = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const mpq_class f = exact(o[k]) - exact(ctr[k]);
        a += exact(d[k]) * exact(d[k]);
        b += f * exact(d[k]);
        c += f * f;
    }
    c -= exact(sc.sphere.radius) * exact(sc.sphere.radius);
    SphereOracle out;
    out.hit = cgal_hit(sc);
    if (!out.hit) {
        return out;
    }
    const mpq_class disc = b * b - a * c;
    const mpq_class tmin = exact(sc.ray.tmin);
    const mpq_class g_min = (a * tmin + 2 * b) * tmin + c;
    if (g_min == 0) {
        out.t = static_cast<double>(sc.ray.tmin);
    } else if (g_min < 0) {
        out.t = mpfr_root(a, b, disc, +1);  // inside at tmin: the leaving root
    } else {
        out.t = mpfr_root(a, b, disc, -1);  // outside, and CGAL says hit: the entering root
    }
    return out;
}

/// Random direction with float components (not normalised: length in [0.5, 2]).
Vec3f random_dir(std::mt19937_64& rng) {
    const auto [v, l2] = ball_shell_point(rng);
    return v * (uni(rng, 0.5f, 2.0f) / std::sqrt(l2));
}

/// A sphere with centre in [-10, 10]^3 and radius log-uniform in [0.1, 5].
Sphere<float> random_sphere(std::mt19937_64& rng) {
    return {{uni(rng, -10, 10), uni(rng, -10, 10), uni(rng, -10, 10)},
            0.1f * std::pow(50.0f, uni(rng, 0, 1))};
}

/// The ray sets; `n` rays in all, split evenly.
std::vector<SphereSet> make_sets(std::size_t n, std::uint64_t seed) {
    const std::vector<std::string> names{"random",  "centre", "grazing",  "inside",
                                         "surface", "axis",   "far_small"};
    std::vector<SphereSet> sets;
    for (std::size_t s = 0; s < names.size(); ++s) {
        SphereSet set;
        set.name = names[s];
        const std::size_t count = n / names.size() + (s < n % names.size() ? 1 : 0);
        std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + s);
        for (std::size_t i = 0; i < count; ++i) {
            SphereCase c;
            c.sphere = random_sphere(rng);
            const Vec3f ctr = c.sphere.center;
            const float r = c.sphere.radius;
            const Vec3f far_org{uni(rng, -20, 20), uni(rng, -20, 20), uni(rng, -20, 20)};
            if (set.name == "random") {
                c.ray = {far_org, random_dir(rng)};
                if (i % 2 == 1) {
                    c.ray.tmax = uni(rng, 0, 40);  // finite windows too
                }
            } else if (set.name == "centre") {
                c.ray = {far_org, ctr - far_org};
            } else if (set.name == "grazing") {
                // Through a point at distance r (1 + delta) from the centre, perpendicular to
                // the offset; |delta| log-uniform in [1e-7, 1e-2], either sign.
                const Vec3f dir = random_dir(rng);
                const Vec3f w = normalize(cross(dir, random_dir(rng)));
                const float delta = (i % 2 ? 1.0f : -1.0f) * std::pow(10.0f, uni(rng, -7, -2));
                const Vec3f touch = ctr + w * (r * (1 + delta));
                c.ray = {touch - dir * uni(rng, 1, 20), dir};
            } else if (set.name == "inside") {
                c.ray = {ctr + random_dir(rng) * (0.45f * r), random_dir(rng)};
            } else if (set.name == "surface") {
                // Exactly on the surface: integer centre, radius 5 * 2^k, origin centre + a
                // signed, permuted (3, 4, 0) * 2^k. Window from a small positive tmin, as a
                // secondary ray would use; the oracle then wants the far root or a miss.
                const float scale = std::ldexp(1.0f, static_cast<int>(rng() % 6) - 3);
                c.sphere.center = {std::round(ctr.x), std::round(ctr.y), std::round(ctr.z)};
                c.sphere.radius = 5 * scale;
                Vec3f off{3 * scale, 4 * scale, 0};
                const std::size_t rot = rng() % 3;
                off = {off[rot], off[(rot + 1) % 3], off[(rot + 2) % 3]};
                off = {rng() % 2 ? off.x : -off.x, rng() % 2 ? off.y : -off.y, off.z};
                c.ray = {c.sphere.center + off, random_dir(rng)};
                c.ray.tmin = 1e-4f * c.sphere.radius / length(c.ray.dir);
            } else if (set.name == "axis") {
                const std::size_t axis = rng() % 3;
                Vec3f dir{0, 0, 0};
                dir[axis] = rng() % 2 ? 1.0f : -1.5f;
                Vec3f org =
                    ctr +
                    Vec3f{uni(rng, -1.2f, 1.2f), uni(rng, -1.2f, 1.2f), uni(rng, -1.2f, 1.2f)} * r;
                org[axis] = ctr[axis] - dir[axis] * uni(rng, 2, 10) * r;
                c.ray = {org, dir};
            } else {
                // Small and far: D / r log-uniform in [10, 1e4], aimed within 1.2 r of the
                // centre.
                const float rad = std::pow(10.0f, uni(rng, -3, 0));
                const Vec3f dir = random_dir(rng);
                const float dist = rad * std::pow(10.0f, uni(rng, 1, 4));
                const Vec3f org{uni(rng, -1, 1), uni(rng, -1, 1), uni(rng, -1, 1)};
                const Vec3f aim = org + normalize(dir) * dist;
                c.sphere = {aim + normalize(random_dir(rng)) * (uni(rng, 0, 1.2f) * rad), rad};
                c.ray = {org, dir};
            }
            set.cases.push_back(c);
        }
        set.oracle.resize(set.cases.size());
        tbb::parallel_for(std::size_t(0), set.cases.size(),
                          [&](std::size_t i) { set.oracle[i] = oracle(set.cases[i]); });
        sets.push_back(std::move(set));
    }
    return sets;
}

/// Visits the sphere methods of precision T (see run_wanted).
constexpr auto for_each_sphere = [](auto tag, const auto& f) {
    for_each_sphere_method<typename decltype(tag)::type>(f);
};

/// The case's sphere in precision T, for the driver.
constexpr auto convert = []<class T>(const SphereCase& c, std::type_identity<T>) {
    return to_scalar<T>(c.sphere);
};

}  // namespace

std::vector<std::string> sphere_methods() {
    return method_names(for_each_sphere);
}

std::vector<Row> check_spheres(const Options& opt) {
    const std::vector<std::string> wanted = select_methods(sphere_methods(), opt.methods, "sphere");
    const std::vector<SphereSet> sets = make_sets(opt.rays, opt.seed);
    std::vector<Row> rows;
    run_wanted(wanted, opt, for_each_sphere, [&]<class M>() {
        run_case_sets<M>("sphere", std::string(M::name), sets, convert, opt.by_set, rows);
    });
    return rows;
}

BenchCases<Sphere<float>> sphere_bench_cases(std::size_t n, std::uint64_t seed) {
    // The check's sets, n rays each (7 sets); the bench keeps random, grazing and far_small.
    const std::vector<SphereSet> sets = make_sets(7 * n, seed);
    BenchCases<Sphere<float>> out;
    const std::array<std::pair<const char*, BenchSet>, 3> kept{
        {{"random", bench_random}, {"grazing", bench_grazing}, {"far_small", bench_far}}};
    add_kept_sets(
        sets, kept, [](const auto& c) { return c.sphere; }, out);
    return out;
}

}  // namespace rtlab::xcheck
