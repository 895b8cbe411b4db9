// The certified-hit test's oracle (see exact_triangle_oracle.h): CGAL's exact line/triangle
// intersection, the exact t of the point along the ray, and that t rounded to the nearest float by
// exact comparisons against the midpoints between neighbouring floats.
#include "crosscheck/exact_triangle_oracle.h"

#include "crosscheck/exact_ray.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <bit>
#include <cmath>
#include <optional>

namespace rtlab::xcheck {

namespace {

using K = ExactRay::K;
constexpr float inf = std::numeric_limits<float>::infinity();

K::Point_3 exact_point(const Vec3f& v) {
    return K::Point_3(static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z));
}

/// The exact t of the single point where the ray meets the closed triangle within its window;
/// none for a miss, a zero-area triangle or a line lying in the triangle's plane.
std::optional<K::FT> exact_t(const ExactRay& er, const Rayf& ray, const Trianglef& tri) {
    const K::Point_3 q0 = exact_point(tri.p0), q1 = exact_point(tri.p1), q2 = exact_point(tri.p2);
    if (CGAL::collinear(q0, q1, q2) || ray.tmin == inf || ray.tmax == -inf) {
        return std::nullopt;
    }
    if (CGAL::coplanar(q0, q1, q2, er.p1) && CGAL::coplanar(q0, q1, q2, er.p2)) {
        return std::nullopt;  // the line lies in the plane (CGAL gives a point at a lone vertex)
    }
    const auto res = CGAL::intersection(K::Line_3(er.p1, er.p2), K::Triangle_3(q0, q1, q2));
    if (!res) {
        return std::nullopt;
    }
    const K::Point_3* p = boost::get<K::Point_3>(&*res);
    if (p == nullptr) {
        return std::nullopt;  // a segment: the line lies in the plane
    }
    const K::Vector_3 d = er.p2 - er.p1;  // dir, exactly
    K::FT t = ((*p - er.p1) * d) / (d * d);
    if ((!std::isinf(ray.tmin) && t < K::FT(static_cast<double>(ray.tmin))) ||
        (!std::isinf(ray.tmax) && t > K::FT(static_cast<double>(ray.tmax)))) {
        return std::nullopt;
    }
    return t;
}

/// The value of a float for the midpoints; the neighbour past the largest float is 2^128.
double value(float x) {
    return std::isinf(x) ? std::copysign(0x1.0p128, static_cast<double>(x))
                         : static_cast<double>(x);
}

/// True when the finite f is the float nearest to t (ties to even), decided exactly against the
/// midpoints to its two neighbours.
bool is_nearest(float f, const K::FT& t) {
    const K::FT mid_lo = (K::FT(value(f)) + K::FT(value(std::nextafter(f, -inf)))) / 2;
    const K::FT mid_hi = (K::FT(value(f)) + K::FT(value(std::nextafter(f, inf)))) / 2;
    const bool even = (std::bit_cast<std::uint32_t>(f) & 1u) == 0;
    return (t > mid_lo || (t == mid_lo && even)) && (t < mid_hi || (t == mid_hi && even));
}

/// The float nearest to t, ties to even, +-inf past the midpoint between the largest float and
/// 2^128. Starts from the double approximation of t (within a float or two once t is exact) and
/// steps one float at a time towards t until the exact midpoint test holds.
float nearest_float(const K::FT& t) {
    t.exact();  // tightens the interval approximation that to_double reads
    const double approx = CGAL::to_double(t);
    float f = std::isfinite(static_cast<float>(approx))
                  ? static_cast<float>(approx)
                  : std::copysign(std::numeric_limits<float>::max(), static_cast<float>(approx));
    while (std::isfinite(f) && !is_nearest(f, t)) {
        f = std::nextafter(f, t < K::FT(static_cast<double>(f)) ? -inf : inf);
    }
    return f;
}

}  // namespace

ExactTriangleHits exact_triangle_hits(std::span<const Trianglef> tris, const Rayf& ray) {
    const ExactRay er(ray);
    ExactTriangleHits out;
    out.pairs.resize(tris.size());
    std::optional<K::FT> best;
    for (std::uint32_t id = 0; id < tris.size(); ++id) {
        const std::optional<K::FT> t = exact_t(er, ray, tris[id]);
        if (!t) {
            continue;
        }
        out.pairs[id] = {true, nearest_float(*t)};
        if (!best || *t < *best) {  // strict: an exact tie keeps the lower id
            best = t;
            out.closest = id;
        }
    }
    return out;
}

}  // namespace rtlab::xcheck
