#pragma once
// Bounds3: an axis-aligned box. The default box is empty (lo = +inf, hi = -inf), so extending it
// by anything gives that thing.

#include "intersect/vec.h"

#include <limits>

namespace rtlab {

/// Axis-aligned bounding box [lo, hi]; empty when any lo > hi.
template <class T>
struct Bounds3 {
    Vec3<T> lo{std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity(),
               std::numeric_limits<T>::infinity()};
    Vec3<T> hi{-std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity(),
               -std::numeric_limits<T>::infinity()};

    constexpr Bounds3() = default;
    constexpr Bounds3(const Vec3<T>& lo_, const Vec3<T>& hi_) : lo(lo_), hi(hi_) {}
    /// The degenerate box around one point.
    constexpr explicit Bounds3(const Vec3<T>& p) : lo(p), hi(p) {}

    /// True when the box contains no point.
    constexpr bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    /// Grow to contain p.
    constexpr Bounds3& extend(const Vec3<T>& p) {
        lo = rtlab::min(lo, p);
        hi = rtlab::max(hi, p);
        return *this;
    }
    /// Grow to contain b.
    constexpr Bounds3& extend(const Bounds3& b) {
        lo = rtlab::min(lo, b.lo);
        hi = rtlab::max(hi, b.hi);
        return *this;
    }
    /// hi - lo (negative components when empty).
    constexpr Vec3<T> diagonal() const { return hi - lo; }
    /// Midpoint of the box.
    constexpr Vec3<T> center() const { return (lo + hi) * T(0.5); }
    /// Surface area; 0 for an empty box.
    constexpr T surface_area() const {
        if (empty()) {
            return T(0);
        }
        const Vec3<T> d = diagonal();
        return T(2) * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
    /// Axis (0, 1, 2) of the longest extent.
    std::size_t largest_axis() const { return max_abs_axis(diagonal()); }
    /// True when p lies inside or on the boundary.
    constexpr bool contains(const Vec3<T>& p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z &&
               p.z <= hi.z;
    }
    /// True when b lies inside or on the boundary of this box.
    constexpr bool contains(const Bounds3& b) const { return contains(b.lo) && contains(b.hi); }
    friend constexpr bool operator==(const Bounds3&, const Bounds3&) = default;
};

using Bounds3f = Bounds3<float>;
using Bounds3d = Bounds3<double>;

/// Union of two boxes.
template <class T>
constexpr Bounds3<T> merge(Bounds3<T> a, const Bounds3<T>& b) {
    return a.extend(b);
}

/// Intersection of two boxes (may be empty).
template <class T>
constexpr Bounds3<T> intersection(const Bounds3<T>& a, const Bounds3<T>& b) {
    return {rtlab::max(a.lo, b.lo), rtlab::min(a.hi, b.hi)};
}

}  // namespace rtlab
