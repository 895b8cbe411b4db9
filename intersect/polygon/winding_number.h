#pragma once
// Ray-polygon by ray-plane then the winding-number point-in-polygon test in the projection
// (Sunday 2001; Hormann & Agathos 2001, "The point in polygon problem for arbitrary polygons"),
// nonzero rule. No epsilon; the same half-open rule as crossing_count. Cost: plane step + per
// edge 2 sub, 2 compares, <= 2 mul.

#include "intersect/polygon/polygon.h"

#include <optional>
#include <string_view>

namespace rtlab {

/// Nonzero rule: the point is inside when the boundary winds around it a nonzero number of times.
/// Upward crossings of the test ray along +u add 1, downward ones subtract 1; vertices with
/// v == point.v count as above, and a crossing at u == 0 does not count (as in crossing_count),
/// so for simple polygons both methods give the same answer.
template <class T>
struct PolygonWinding : PolygonMethodBase<PolygonWinding<T>, T> {
    static constexpr std::string_view name = "winding_number";

    /// Winding number of the projected boundary around (pu, pv).
    static int winding(const PreparedPolygon<T>& p, T pu, T pv) {
        const std::size_t n = p.pts.size();
        int wn = 0;
        T au = p.pts[n - 1][0] - pu, av = p.pts[n - 1][1] - pv;
        for (std::size_t i = 0; i < n; ++i) {
            const T bu = p.pts[i][0] - pu, bv = p.pts[i][1] - pv;
            if (av < T(0)) {
                // Upward crossing: the point must be strictly left of the edge.
                if (bv >= T(0) && detail::edge_side(au, av, bu, bv) > T(0)) {
                    ++wn;
                }
            } else if (bv < T(0) && detail::edge_side(au, av, bu, bv) < T(0)) {
                --wn;  // downward crossing with the point strictly right of the edge
            }
            au = bu;
            av = bv;
        }
        return wn;
    }

    /// True when the projected point (pu, pv) is inside by the nonzero rule.
    static bool contains(const PreparedPolygon<T>& p, T pu, T pv) {
        return winding(p, pu, pv) != 0;
    }
};

}  // namespace rtlab
