#pragma once
// The cone intersection methods as a compile-time list, for tests, cross-checks and benchmarks.

#include "intersect/cone/quadric.h"
#include "intersect/cone/stable.h"
#include "intersect/method.h"

#include <tuple>

namespace rtlab {

/// Every cone method in scalar T as a type list; the first is the tracer's default.
template <class T>
using ConeMethods = std::tuple<ConeStable<T>, ConeQuadric<T>>;

static_assert(names_unique<ConeMethods<float>>());
static_assert(IntersectionMethod<ConeQuadric<float>>);
static_assert(IntersectionMethod<ConeStable<float>>);
static_assert(HasRayData<ConeQuadric<double>>);

/// Calls f.template operator()<M>() for every cone method M in scalar T, in list order.
template <class T, class F>
void for_each_cone_method(F&& f) {
    for_each_type<ConeMethods<T>>(f);
}

}  // namespace rtlab
