#pragma once
// Ray-polygon by ray-plane then the crossing-number (even-odd) point-in-polygon test in the
// projection (Haines 1994, "Point in Polygon Strategies", Graphics Gems IV). No epsilon:
// half-open rule below. Cost: plane step + per edge 2 sub, 2 compares, <= 2 mul.

#include "intersect/polygon/polygon.h"

#include <optional>
#include <string_view>

namespace rtlab {

/// Even-odd rule: the point is inside when a test ray from it along +u crosses the boundary an
/// odd number of times. Half-open rule: a vertex with v == point.v counts as above the test ray,
/// so a test ray through a vertex counts the two edges there once or not at all; a crossing
/// exactly at the point (u == 0) does not count, so a point on an edge shared by two polygons is
/// inside exactly one of them.
template <class T>
struct PolygonCrossing : PolygonMethodBase<PolygonCrossing<T>, T> {
    static constexpr std::string_view name = "crossing_count";

    /// True when the projected point (pu, pv) is inside by the even-odd rule.
    static bool contains(const PreparedPolygon<T>& p, T pu, T pv) {
        const std::size_t n = p.pts.size();
        bool inside = false;
        T au = p.pts[n - 1][0] - pu, av = p.pts[n - 1][1] - pv;
        bool a_above = av >= T(0);
        for (std::size_t i = 0; i < n; ++i) {
            const T bu = p.pts[i][0] - pu, bv = p.pts[i][1] - pv;
            const bool b_above = bv >= T(0);
            if (a_above != b_above) {
                // The edge crosses the line v = 0; count it when the crossing lies at u > 0.
                if (au > T(0) && bu > T(0)) {
                    inside = !inside;
                } else if (au > T(0) || bu > T(0)) {
                    // Crossing u = edge_side / (bv - av); its sign without dividing.
                    const T s = detail::edge_side(au, av, bu, bv);
                    if (b_above ? s > T(0) : s < T(0)) {
                        inside = !inside;
                    }
                }
            }
            au = bu;
            av = bv;
            a_above = b_above;
        }
        return inside;
    }
};

}  // namespace rtlab
