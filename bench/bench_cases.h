#pragma once
// The cross-check's ray sets and exact answers (crosscheck/ray_sets.h), computed once per process
// and primitive kind on first use, shared by the intersector and root-finder suites; plus the
// conversion of the float shapes to the precision a method runs in (float -> double is exact).

#include "bench/benchmarks.h"
#include "crosscheck/ray_sets.h"

#include <cstddef>
#include <cstdint>

namespace rtlab::bench {

/// Seed of every benchmark case set (the seed `rtlab crosscheck` uses by default).
inline constexpr std::uint64_t case_seed = 1;

/// Rays per distribution: 10000 (rates resolved to 1e-4), 1000 with --quick.
inline std::size_t rays_per_set() {
    return quick_mode() ? 1000 : 10000;
}

/// The cases Make(rays_per_set(), case_seed) builds, computed once (the oracle runs here, in
/// parallel, never inside a timed loop).
template <class Shape, xcheck::BenchCases<Shape> (*Make)(std::size_t, std::uint64_t)>
const xcheck::BenchCases<Shape>& cached_cases() {
    static const xcheck::BenchCases<Shape> cases = Make(rays_per_set(), case_seed);
    return cases;
}

/// The float shape in precision T.
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

}  // namespace rtlab::bench
