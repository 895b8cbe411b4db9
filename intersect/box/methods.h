#pragma once
// The AABB and OBB intersection methods as compile-time lists, for tests, cross-checks and
// benchmarks.

#include "intersect/box/aabb.h"
#include "intersect/box/obb.h"
#include "intersect/method.h"

#include <tuple>

namespace rtlab {

/// Every AABB method in scalar T as a type list; the first is the tracer's default.
template <class T>
using AabbMethods = std::tuple<AabbSlabs<T>, AabbSlabsRobust<T>>;

/// Every OBB method in scalar T as a type list; the first is the tracer's default.
template <class T>
using ObbMethods = std::tuple<ObbSlabs<T>>;

static_assert(names_unique<AabbMethods<float>>() && names_unique<ObbMethods<float>>());
static_assert(IntersectionMethod<AabbSlabs<float>>);
static_assert(IntersectionMethod<AabbSlabsRobust<double>>);
static_assert(IntersectionMethod<ObbSlabs<float>>);
static_assert(HasRayData<AabbSlabs<float>> && HasRayData<AabbSlabsRobust<double>>);

/// Calls f.template operator()<M>() for every AABB method M in scalar T, in list order.
template <class T, class F>
void for_each_aabb_method(F&& f) {
    for_each_type<AabbMethods<T>>(f);
}

/// Calls f.template operator()<M>() for every OBB method M in scalar T, in list order.
template <class T, class F>
void for_each_obb_method(F&& f) {
    for_each_type<ObbMethods<T>>(f);
}

}  // namespace rtlab
