// Cross-check of the cone methods against an exact oracle: the lateral quadric, its axial slab and
// the cap disks decided in exact rationals (GMP), the reference t from a 256-bit MPFR square root
// (exact_cone_root, crosscheck/exact.cpp). Cones are cylinders, pointed and truncated cones in
// random orientations, open or capped, all in float so both precisions trace the same shape.
#include "crosscheck/checks.h"
#include "crosscheck/driver.h"
#include "crosscheck/exact.h"
#include "crosscheck/ray_sets.h"
#include "intersect/cone/methods.h"

#include <array>
#include <cmath>
#include <string>
#include <tbb/parallel_for.h>
#include <utility>
#include <vector>

namespace rtlab::xcheck {

namespace {

/// One test: a cone and a ray, both in float.
struct ConeCase {
    Cone<float> cone;
    Ray<float> ray;
};

/// A named ray set with its exact answers.
struct ConeSet {
    std::string name;
    std::vector<ConeCase> cases;
    std::vector<Truth> oracle;
};

/// The set names, in table order.
const std::vector<std::string>& set_names() {
    static const std::vector<std::string> names{"random", "axis",   "along_axis", "grazing",
                                                "rim",    "inside", "thin",       "far_small"};
    return names;
}

/// Log-uniform in [a, b].
float log_uni(Rng& rng, float a, float b) {
    return a * std::pow(b / a, rng.uni(0, 1));
}

/// Unit vector perpendicular to unit n (any).
Vec3f perpendicular(Rng& rng, const Vec3f& n) {
    for (;;) {
        const Vec3f v = cross(n, rng.dir());
        if (length_squared(v) > 1e-4f) {
            return normalize(v);
        }
    }
}

/// Base and apex radii for cone i: cylinders, pointed cones (either end) and truncated cones.
void radii(Rng& rng, std::size_t i, float r, Cone<float>& c) {
    c.base_radius = r;
    switch (i % 4) {
    case 0:
        c.apex_radius = r;
        break;
    case 1:
        c.apex_radius = 0;
        break;
    case 2:
        c.apex_radius = r * rng.uni(0.1f, 2.0f);
        break;
    default:
        c.base_radius = 0;
        c.apex_radius = r;
        break;
    }
}

/// A cone: base in [-10, 10]^3, height log-uniform in [0.2, 10], radius log-uniform in [0.1, 5];
/// every other cone's axis along a coordinate axis (as the SPD's are), caps random.
Cone<float> random_cone(Rng& rng, std::size_t i) {
    Cone<float> c;
    c.base = {rng.uni(-10, 10), rng.uni(-10, 10), rng.uni(-10, 10)};
    Vec3f axis = normalize(rng.dir());
    if ((i / 4) % 2 == 0) {
        axis = {0, 0, 0};
        axis[rng.below(3)] = rng.coin(0.5f) ? 1.0f : -1.0f;
    }
    c.apex = c.base + axis * log_uni(rng, 0.2f, 10);
    radii(rng, i, log_uni(rng, 0.1f, 5), c);
    c.caps = static_cast<ConeCaps>(rng.below(4));
    return c;
}

/// Radius of cone c at fraction f of its height.
float radius_at(const Cone<float>& c, float f) {
    return c.base_radius + (c.apex_radius - c.base_radius) * f;
}

/// A point on the lateral surface at fraction f of the height, radial direction `radial`.
Vec3f side_point(const Cone<float>& c, float f, const Vec3f& radial, float scale = 1) {
    return c.base + (c.apex - c.base) * f + radial * (radius_at(c, f) * scale);
}

/// The "grazing" set: in the tangent plane at a side point moved radially by a factor 1 + delta,
/// |delta| log-uniform in [1e-7, 1e-2], either sign: near-tangent rays, tangent to the quadric.
Rayf grazing_ray(
    Rng& rng, const Cone<float>& c, const Vec3f& axis, const Vec3f& radial, std::size_t i) {
    const float f = rng.uni(0.05f, 0.95f);
    const float delta = (i % 2 ? 1.0f : -1.0f) * std::pow(10.0f, rng.uni(-7, -2));
    const Vec3f touch = side_point(c, f, radial, 1 + delta);
    const Vec3f along = cross(axis, radial);  // the tangent plane holds `along` and the
                                              // generator direction
    const Vec3f gen = normalize(c.apex - c.base + radial * (c.apex_radius - c.base_radius));
    const Vec3f dir = normalize(along * rng.uni(0.2f, 1) + gen * rng.uni(-0.5f, 0.5f));
    return {touch - dir * rng.uni(1, 20), dir};
}

/// The "far" set: a cone made anew, small and far (distance / radius log-uniform in [10, 1e4]),
/// and a ray aimed within 1.2 radii of it.
Rayf small_far_ray(Rng& rng, std::size_t i, Cone<float>& c) {
    const float r = std::pow(10.0f, rng.uni(-3, 0));
    const Vec3f dir = rng.dir();
    const float dist = r * std::pow(10.0f, rng.uni(1, 4));
    const Vec3f org{rng.uni(-1, 1), rng.uni(-1, 1), rng.uni(-1, 1)};
    const Vec3f aim = org + normalize(dir) * dist;
    const Vec3f ax = normalize(rng.dir());
    const float h = r * rng.uni(0.5f, 4);
    c.base = aim - ax * (h * rng.uni(0, 1)) + perpendicular(rng, ax) * (r * rng.uni(0, 1.2f));
    c.apex = c.base + ax * h;
    radii(rng, i, r, c);
    return {org, dir};
}

/// One case of set `name`.
ConeCase make_case(Rng& rng, const std::string& name, std::size_t i) {
    ConeCase k;
    k.cone = random_cone(rng, i);
    Cone<float>& c = k.cone;
    const Vec3f axis = normalize(c.apex - c.base);
    const Vec3f far_org{rng.uni(-20, 20), rng.uni(-20, 20), rng.uni(-20, 20)};
    const Vec3f radial = perpendicular(rng, axis);
    if (name == "random") {
        const Vec3f target = side_point(c, rng.uni(-0.2f, 1.2f), radial, rng.uni(0, 1.3f));
        k.ray = {far_org, (target - far_org) * rng.uni(0.05f, 0.5f)};
        if (i % 2 == 1) {
            k.ray.tmax = rng.uni(0, 40);
        }
    } else if (name == "axis") {
        // Along a coordinate axis (two zero components, signed zeros and denormals), aimed within
        // 1.2 radii of a point on the axis.
        const std::size_t a = rng.below(3);
        Vec3f dir{zero_like(rng), zero_like(rng), zero_like(rng)};
        dir[a] = rng.coin(0.5f) ? 1.0f : -1.5f;
        const float r = std::max(c.base_radius, c.apex_radius);
        Vec3f org = c.base + (c.apex - c.base) * rng.uni(-0.1f, 1.1f) +
                    Vec3f{rng.uni(-1.2f, 1.2f), rng.uni(-1.2f, 1.2f), rng.uni(-1.2f, 1.2f)} * r;
        org[a] -= dir[a] * rng.uni(15, 30);
        k.ray = {org, dir};
    } else if (name == "along_axis") {
        // Parallel to the cone's own axis, inside or just outside the end disks (open ends, caps).
        const float r = std::max(c.base_radius, c.apex_radius);
        const Vec3f org = c.base - axis * rng.uni(1, 10) + radial * (r * rng.uni(0, 1.1f));
        k.ray = {org, (rng.coin(0.5f) ? axis : -axis) * rng.uni(0.5f, 2)};
        if (dot(k.ray.dir, axis) < 0) {
            k.ray.org = k.ray.org + axis * (length(c.apex - c.base) + rng.uni(2, 20));
        }
    } else if (name == "grazing") {
        k.ray = grazing_ray(rng, c, axis, radial, i);
    } else if (name == "rim") {
        // Aimed at a point of an end circle moved by +-1e-6 relative (open edge or cap edge);
        // never at the tip of a pointed cone (a single point, not an edge).
        float f = rng.coin(0.5f) ? 0.0f : 1.0f;
        if (radius_at(c, f) == 0) {
            f = 1 - f;
        }
        const float scale = 1 + tiny(rng);
        const Vec3f target = side_point(c, f, radial, scale) + axis * (tiny(rng) * 1.0f);
        k.ray = {far_org, target - far_org};
    } else if (name == "inside") {
        // From inside the solid cone (half way to the axis), any direction; secondary-ray
        // windows half the time.
        const float f = rng.uni(0.1f, 0.9f);
        k.ray = {side_point(c, f, radial, rng.uni(0, 0.5f)), rng.dir()};
        if (i % 2 == 1) {
            k.ray.tmin = 1e-4f;
        }
    } else if (name == "thin") {
        // Needles: radius / height log-uniform in [1e-5, 1e-2], aimed within 1.2 radii.
        const float h = length(c.apex - c.base);
        radii(rng, i, h * log_uni(rng, 1e-5f, 1e-2f), c);
        const Vec3f target = side_point(c, rng.uni(0, 1), radial, rng.uni(0, 1.2f));
        k.ray = {far_org, target - far_org};
    } else {
        k.ray = small_far_ray(rng, i, c);
    }
    return k;
}

/// The exact answer for one case.
Truth oracle(const ConeCase& k) {
    const Cone<double> c{Vec3d(k.cone.base), static_cast<double>(k.cone.base_radius),
                         Vec3d(k.cone.apex), static_cast<double>(k.cone.apex_radius), k.cone.caps};
    const ExactRoot r = exact_cone_root(c, static_cast<Rayd>(k.ray));
    return {r.hit, r.t};
}

/// The ray sets; `n` rays in all, split evenly.
std::vector<ConeSet> make_sets(std::size_t n, std::uint64_t seed) {
    const std::vector<std::string>& names = set_names();
    std::vector<ConeSet> sets;
    for (std::size_t s = 0; s < names.size(); ++s) {
        ConeSet set;
        set.name = names[s];
        const std::size_t count = n / names.size() + (s < n % names.size() ? 1 : 0);
        Rng rng(seed * 0x9E3779B97F4A7C15ull + 0xC0DE + s);
        for (std::size_t i = 0; i < count; ++i) {
            set.cases.push_back(make_case(rng, set.name, i));
        }
        set.oracle.resize(set.cases.size());
        tbb::parallel_for(std::size_t(0), set.cases.size(),
                          [&](std::size_t i) { set.oracle[i] = oracle(set.cases[i]); });
        sets.push_back(std::move(set));
    }
    return sets;
}

/// Visits the cone methods of precision T (see run_wanted).
constexpr auto for_each_cone = [](auto tag, const auto& f) {
    for_each_cone_method<typename decltype(tag)::type>(f);
};

/// The case's cone in precision T, for the driver.
constexpr auto convert = []<class T>(const ConeCase& k, std::type_identity<T>) {
    return to_scalar<T>(k.cone);
};

}  // namespace

std::vector<std::string> cone_methods() {
    return method_names(for_each_cone);
}

std::vector<Row> check_cones(const Options& opt) {
    const std::vector<std::string> wanted = select_methods(cone_methods(), opt.methods, "cone");
    const std::vector<ConeSet> sets = make_sets(opt.rays, opt.seed);
    std::vector<Row> rows;
    run_wanted(wanted, opt, for_each_cone, [&]<class M>() {
        run_case_sets<M>("cone", std::string(M::name), sets, convert, opt.by_set, rows);
    });
    return rows;
}

BenchCases<Cone<float>> cone_bench_cases(std::size_t n, std::uint64_t seed) {
    // The check's sets, n rays each; the bench keeps random, rim (as edge), grazing, far_small.
    const std::vector<ConeSet> sets = make_sets(set_names().size() * n, seed);
    BenchCases<Cone<float>> out;
    const std::array<std::pair<const char*, BenchSet>, 4> kept{{{"random", bench_random},
                                                                {"rim", bench_edge},
                                                                {"grazing", bench_grazing},
                                                                {"far_small", bench_far}}};
    add_kept_sets(
        sets, kept, [](const auto& c) { return c.cone; }, out);
    return out;
}

}  // namespace rtlab::xcheck
