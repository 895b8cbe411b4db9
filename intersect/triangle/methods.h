#pragma once
// The compile-time list of triangle intersection methods, so tests, cross-checks and benchmarks
// can iterate them generically: for_each_triangle_method<float>([]<class M>() { ... }).

#include "intersect/method.h"
#include "intersect/triangle/badouel.h"
#include "intersect/triangle/moller_trumbore.h"
#include "intersect/triangle/segura_feito.h"
#include "intersect/triangle/watertight.h"

#include <tuple>

namespace rtlab {

/// Every triangle method in scalar T, as a type list (Segura–Feito is occlusion-only).
template <class T>
using TriangleMethods = std::tuple<MollerTrumbore<T>, Badouel<T>, SeguraFeito<T>, Watertight<T>>;

/// The triangle methods in scalar T that report t, u, v (satisfy IntersectionMethod).
template <class T>
using TriangleIntersectors = IntersectorsOf<TriangleMethods<T>>;

static_assert(names_unique<TriangleMethods<float>>());

/// Call f.template operator()<M>() for every triangle method M in scalar T, in list order.
template <class T, class F>
void for_each_triangle_method(F&& f) {
    for_each_type<TriangleMethods<T>>(f);
}

/// Call f.template operator()<M>() for every triangle method in scalar T that reports t, u, v.
template <class T, class F>
void for_each_triangle_intersector(F&& f) {
    for_each_type<TriangleIntersectors<T>>(f);
}

}  // namespace rtlab
