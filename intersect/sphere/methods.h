#pragma once
// The sphere intersection methods as a compile-time list, for tests, cross-checks and benchmarks.

#include "intersect/method.h"
#include "intersect/sphere/algebraic.h"
#include "intersect/sphere/geometric.h"
#include "intersect/sphere/stable.h"

namespace rtlab {

static_assert(IntersectionMethod<SphereGeometric<float>>);
static_assert(IntersectionMethod<SphereAlgebraic<float>>);
static_assert(IntersectionMethod<SphereStable<double>>);

/// Calls f.template operator()<M>() for every sphere method M in scalar T, in table order.
template <class T, class F>
void for_each_sphere_method(F&& f) {
    f.template operator()<SphereGeometric<T>>();
    f.template operator()<SphereAlgebraic<T>>();
    f.template operator()<SphereStable<T>>();
}

}  // namespace rtlab
