#pragma once
// The polygon intersection methods as a compile-time list, for tests, cross-checks and benchmarks.

#include "intersect/method.h"
#include "intersect/polygon/crossing_count.h"
#include "intersect/polygon/winding_number.h"

#include <tuple>

namespace rtlab {

/// Every polygon method in scalar T as a type list; the first is the tracer's default.
template <class T>
using PolygonMethods = std::tuple<PolygonCrossing<T>, PolygonWinding<T>>;

static_assert(names_unique<PolygonMethods<float>>());
static_assert(IntersectionMethod<PolygonCrossing<float>>);
static_assert(IntersectionMethod<PolygonWinding<double>>);

/// Calls f.template operator()<M>() for every polygon method M in scalar T, in list order.
template <class T, class F>
void for_each_polygon_method(F&& f) {
    for_each_type<PolygonMethods<T>>(f);
}

}  // namespace rtlab
