#pragma once
// Möller & Trumbore 1997, "Fast, minimum storage ray-triangle intersection": Cramer's rule,
// two-sided, divide before the u/v tests. Epsilon: none (det == 0 misses, edges inclusive, NaN
// fails every test). Cost: 2 cross, 4 dot, 1 division per test; stores the three vertices.

#include "intersect/hit.h"
#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <optional>
#include <string_view>

namespace rtlab {

/// Möller–Trumbore ray/triangle test, templated on the scalar type.
template <class T>
struct MollerTrumbore : VertexTriangleMethod<T>, MethodDefaults<MollerTrumbore<T>> {
    using typename VertexTriangleMethod<T>::Prepared;

    static constexpr std::string_view name = "moller_trumbore";

    /// Hit with t in [ray.tmin, ray.tmax] and barycentrics u (p1), v (p2), or nullopt.
    static std::optional<PrimHit<T>> intersect(const Prepared& p, const Ray<T>& ray) {
        const Vec3<T> e1 = p.p1 - p.p0;
        const Vec3<T> e2 = p.p2 - p.p0;
        const Vec3<T> pvec = cross(ray.dir, e2);
        const T det = dot(e1, pvec);
        if (det == T(0)) {
            return std::nullopt;
        }
        const T inv_det = T(1) / det;
        const Vec3<T> tvec = ray.org - p.p0;
        const T u = dot(tvec, pvec) * inv_det;
        if (!(u >= T(0) && u <= T(1))) {
            return std::nullopt;
        }
        const Vec3<T> qvec = cross(tvec, e1);
        const T v = dot(ray.dir, qvec) * inv_det;
        if (!(v >= T(0) && u + v <= T(1))) {
            return std::nullopt;
        }
        const T t = dot(e2, qvec) * inv_det;
        if (!in_window(t, ray)) {
            return std::nullopt;
        }
        return PrimHit<T>{t, u, v};
    }
};

static_assert(IntersectionMethod<MollerTrumbore<float>>);
static_assert(IntersectionMethod<MollerTrumbore<double>>);

}  // namespace rtlab
