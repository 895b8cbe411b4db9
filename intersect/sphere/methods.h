#pragma once
// The sphere intersection methods as a compile-time list, for tests, cross-checks and benchmarks.

#include "intersect/method.h"
#include "intersect/sphere/algebraic.h"
#include "intersect/sphere/geometric.h"
#include "intersect/sphere/stable.h"

#include <tuple>

namespace rtlab {

/// Every sphere method in scalar T as a type list; the first is the tracer's default.
template <class T>
using SphereMethods = std::tuple<SphereStable<T>, SphereGeometric<T>, SphereAlgebraic<T>>;

static_assert(names_unique<SphereMethods<float>>());
static_assert(IntersectionMethod<SphereGeometric<float>>);
static_assert(IntersectionMethod<SphereAlgebraic<float>>);
static_assert(IntersectionMethod<SphereStable<double>>);
static_assert(HasRayData<SphereGeometric<float>>);

/// Calls f.template operator()<M>() for every sphere method M in scalar T, in list order.
template <class T, class F>
void for_each_sphere_method(F&& f) {
    for_each_type<SphereMethods<T>>(f);
}

}  // namespace rtlab
