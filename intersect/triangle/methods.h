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
using TriangleIntersectors = std::tuple<MollerTrumbore<T>, Badouel<T>, Watertight<T>>;

namespace detail {
/// Calls f.template operator()<M>() for each M of the tuple type, in order.
template <class F, class... Ms>
void for_each_type(F& f, std::tuple<Ms...>*) {
    (f.template operator()<Ms>(), ...);
}
}  // namespace detail

/// Call f.template operator()<M>() for every triangle method M in scalar T, in list order.
template <class T, class F>
void for_each_triangle_method(F&& f) {
    detail::for_each_type(f, static_cast<TriangleMethods<T>*>(nullptr));
}

/// Call f.template operator()<M>() for every triangle method in scalar T that reports t, u, v.
template <class T, class F>
void for_each_triangle_intersector(F&& f) {
    detail::for_each_type(f, static_cast<TriangleIntersectors<T>*>(nullptr));
}

}  // namespace rtlab
