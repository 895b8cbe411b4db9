#pragma once
// The polygon intersection methods as a compile-time list, for tests, cross-checks and benchmarks.

#include "intersect/method.h"
#include "intersect/polygon/crossing_count.h"
#include "intersect/polygon/winding_number.h"

namespace rtlab {

static_assert(IntersectionMethod<PolygonCrossing<float>>);
static_assert(IntersectionMethod<PolygonWinding<double>>);

/// Calls f.template operator()<M>() for every polygon method M in scalar T, in table order.
template <class T, class F>
void for_each_polygon_method(F&& f) {
    f.template operator()<PolygonCrossing<T>>();
    f.template operator()<PolygonWinding<T>>();
}

}  // namespace rtlab
