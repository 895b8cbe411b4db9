#pragma once
// The cross-check's seeded shapes, ray sets and exact answers, for the benchmarks (bench/): per
// primitive kind, the rays of four distributions (random, edge-aimed, grazing, far) drawn with
// the same generators and judged by the same oracles as `rtlab crosscheck`, computed once.
// A kind without edges (sphere, implicit surfaces) has no edge rays. Each function is defined in
// the kind's <kind>_check.cpp, beside its oracle.

#include "crosscheck/driver.h"
#include "intersect/bounds.h"
#include "intersect/box/obb.h"
#include "intersect/cone/cone.h"
#include "intersect/implicit/tangle_cube.h"
#include "intersect/implicit/torus.h"
#include "intersect/polygon/polygon.h"
#include "intersect/sphere/sphere.h"
#include "intersect/triangle/exact_hit.h"
#include "intersect/triangle/methods.h"
#include "intersect/triangle/triangle.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtlab::xcheck {

/// The benchmark ray distributions; Sample::set is an index into this array.
inline constexpr std::array<std::string_view, 4> bench_set_names{"random", "edge", "grazing",
                                                                 "far"};

/// Index of each distribution in bench_set_names.
enum BenchSet : std::uint8_t { bench_random, bench_edge, bench_grazing, bench_far };

/// One kind's benchmark cases: sample i tests shapes[samples[i].shape] (or, when closest_of_all,
/// every shape for the closest hit, as the triangle check traces a closed mesh) and truth[i] is
/// the exact answer for that test. Samples are grouped by set, in bench_set_names order.
template <class Shape>
struct BenchCases {
    std::vector<Shape> shapes;    ///< float shapes
    std::vector<Sample> samples;  ///< rays with their shape and set index
    std::vector<Truth> truth;     ///< exact answer per sample
    bool closest_of_all = false;  ///< true: each ray is tested against all shapes
};

/// The float shape in precision T (float -> double is exact), for the methods of either precision.
template <class T>
Triangle<T> to_scalar(const Triangle<float>& t) {
    return {Vec3<T>(t.p0), Vec3<T>(t.p1), Vec3<T>(t.p2)};
}
template <class T>
Polygon<T> to_scalar(const Polygon<float>& p) {
    Polygon<T> out;
    for (const Vec3f& v : p.vertices) {
        out.vertices.emplace_back(v);
    }
    return out;
}
template <class T>
Bounds3<T> to_scalar(const Bounds3f& b) {
    return {Vec3<T>(b.lo), Vec3<T>(b.hi)};
}
template <class T>
Obb<T> to_scalar(const Obb<float>& b) {
    return {Vec3<T>(b.center),
            {Vec3<T>(b.axis[0]), Vec3<T>(b.axis[1]), Vec3<T>(b.axis[2])},
            Vec3<T>(b.half)};
}
template <class T>
Sphere<T> to_scalar(const Sphere<float>& s) {
    return {Vec3<T>(s.center), static_cast<T>(s.radius)};
}
template <class T>
Torus<T> to_scalar(const Torus<float>& s) {
    return {Vec3<T>(s.center), static_cast<T>(s.major), static_cast<T>(s.minor)};
}
template <class T>
TangleCube<T> to_scalar(const TangleCube<float>& s) {
    return {Vec3<T>(s.center), static_cast<T>(s.scale)};
}
template <class T>
Cone<T> to_scalar(const Cone<float>& c) {
    return {Vec3<T>(c.base), static_cast<T>(c.base_radius), Vec3<T>(c.apex),
            static_cast<T>(c.apex_radius), c.caps};
}

/// Appends to out the cases of the check's sets that the bench keeps, in kept's order (set name,
/// bench set): each case's float shape shape_of(case) with one sample of its ray in that bench
/// set, and the set's exact answer for it. Each Set has `name`, `cases` (with `ray`) and
/// `oracle` (with `hit` and `t`).
template <class Shape, class Set, std::size_t N, class ShapeOf>
void add_kept_sets(const std::vector<Set>& sets,
                   const std::array<std::pair<const char*, BenchSet>, N>& kept,
                   const ShapeOf& shape_of,
                   BenchCases<Shape>& out) {
    for (const auto& [name, bench_set] : kept) {
        for (const Set& set : sets) {
            if (set.name != name) {
                continue;
            }
            for (std::size_t i = 0; i < set.cases.size(); ++i) {
                Sample smp;
                smp.ray = set.cases[i].ray;
                smp.shape = static_cast<std::uint32_t>(out.shapes.size());
                smp.set = bench_set;
                out.shapes.push_back(shape_of(set.cases[i]));
                out.samples.push_back(smp);
                out.truth.push_back(Truth{set.oracle[i].hit, set.oracle[i].t});
            }
        }
    }
}

/// A "far" ray made from a near one: the origin moved back along the ray by 1e3 to 1e4 direction
/// lengths (then rounded to float, so the oracle judges the moved ray), full window [0, inf).
inline Rayf push_far(Rng& rng, Rayf r) {
    r.org = r.org - r.dir * rng.uni(1e3f, 1e4f);
    r.tmin = 0.0f;
    r.tmax = std::numeric_limits<float>::infinity();
    return r;
}

/// Triangles of the closed perturbed sphere mesh of the triangle check (closest_of_all); sets
/// random (outside, some miss), edge, grazing, far; n rays per set.
BenchCases<Triangle<float>> triangle_bench_cases(std::size_t n, std::uint64_t seed);

/// Visits the triangle methods of precision T (for_each(std::type_identity<T>{}, visitor), as
/// run_wanted wants), and in float also the certified test of exact mode, "exact"
/// (intersect/triangle/exact_hit.h): the methods the cross-check and its benchmarks measure.
inline constexpr auto for_each_checked_triangle = [](auto tag, const auto& f) {
    using T = typename decltype(tag)::type;
    for_each_triangle_method<T>(f);
    if constexpr (std::is_same_v<T, float>) {
        f.template operator()<CertifiedTriangle>();
    }
};
/// The polygon check's polygons; sets random, edge, grazing, far; n rays per set.
BenchCases<Polygon<float>> polygon_bench_cases(std::size_t n, std::uint64_t seed);
/// The AABB check's boxes; sets random, edge, grazing, far; n rays per set.
BenchCases<Bounds3f> aabb_bench_cases(std::size_t n, std::uint64_t seed);
/// The OBB check's boxes; sets random, edge, grazing, far; n rays per set.
BenchCases<Obb<float>> obb_bench_cases(std::size_t n, std::uint64_t seed);
/// The sphere check's cases (one sphere per ray); sets random, grazing, far (far_small); n each.
BenchCases<Sphere<float>> sphere_bench_cases(std::size_t n, std::uint64_t seed);
/// The implicit check's tori (one per ray); sets random, grazing, far; n rays per set. The truth
/// is the check's exact Sturm/MPFR root (relative error < 2^-110 before rounding to double).
BenchCases<Torus<float>> torus_bench_cases(std::size_t n, std::uint64_t seed);
/// As torus_bench_cases, for tangle cubes.
BenchCases<TangleCube<float>> tangle_bench_cases(std::size_t n, std::uint64_t seed);
/// The cone check's cases (one cone per ray); sets random, edge (the check's rim set), grazing,
/// far (far_small); n rays each. The truth is exact_cone_root.
BenchCases<Cone<float>> cone_bench_cases(std::size_t n, std::uint64_t seed);

}  // namespace rtlab::xcheck
