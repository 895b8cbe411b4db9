#pragma once
// Woop, Benthin & Wald 2013, "Watertight ray/triangle intersection" (JCGT): ray-space shear,
// edge functions with the double fallback for exact float zeros, scaled t-range test, two-sided.
// Epsilon: none, zero edge functions are inclusive. Cost: 6 madd shear, 3 edge fns, 1 division
// per test; 3 divisions per ray in precompute (the shear constants).

#include "intersect/hit.h"
#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/triangle/triangle.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

namespace rtlab {

/// The ray-dependent part of the watertight test: axis permutation and shear constants.
template <class T>
struct WatertightRay {
    std::uint8_t kx, ky, kz;  ///< kz: dominant direction axis; kx, ky keep the winding
    T sx, sy, sz;             ///< shear dir[kx] / dir[kz], dir[ky] / dir[kz], scale 1 / dir[kz]

    /// Precompute for one ray (direction must be non-zero).
    static WatertightRay make(const Ray<T>& ray) {
        WatertightRay r{};
        const std::size_t kz = max_abs_axis(ray.dir);
        std::size_t kx = (kz + 1) % 3;
        std::size_t ky = (kx + 1) % 3;
        if (ray.dir[kz] < T(0)) {
            std::swap(kx, ky);  // keep the winding so the sign of det is meaningful
        }
        r.kx = static_cast<std::uint8_t>(kx);
        r.ky = static_cast<std::uint8_t>(ky);
        r.kz = static_cast<std::uint8_t>(kz);
        r.sx = ray.dir[kx] / ray.dir[kz];
        r.sy = ray.dir[ky] / ray.dir[kz];
        r.sz = T(1) / ray.dir[kz];
        return r;
    }
};

/// Watertight ray/triangle test (Woop, Benthin & Wald 2013), templated on the scalar type. Edges
/// shared by two triangles are decided consistently (a float edge function is exact in sign once
/// its zeros are redone in double); double has no wider fallback, a zero only adds hits.
template <class T>
struct Watertight : VertexTriangleMethod<T>, MethodDefaults<Watertight<T>> {
    using MethodDefaults<Watertight<T>>::intersect;
    using typename VertexTriangleMethod<T>::Prepared;

    /// The per-ray set-up: axis permutation and shear.
    using RayData = WatertightRay<T>;

    static constexpr std::string_view name = "watertight";

    /// The axis permutation and shear of ray (once per ray, shared by every triangle).
    static RayData precompute(const Ray<T>& ray) { return WatertightRay<T>::make(ray); }

    /// Hit with t in [ray.tmin, ray.tmax] and barycentrics u (p1), v (p2), or nullopt.
    static std::optional<PrimHit<T>> intersect(const Prepared& p,
                                               const Ray<T>& ray,
                                               const WatertightRay<T>& r) {
        // Vertices relative to the origin, sheared so the ray runs along +z.
        const Vec3<T> a = p.p0 - ray.org;
        const Vec3<T> b = p.p1 - ray.org;
        const Vec3<T> c = p.p2 - ray.org;
        const T ax = a[r.kx] - r.sx * a[r.kz];
        const T ay = a[r.ky] - r.sy * a[r.kz];
        const T bx = b[r.kx] - r.sx * b[r.kz];
        const T by = b[r.ky] - r.sy * b[r.kz];
        const T cx = c[r.kx] - r.sx * c[r.kz];
        const T cy = c[r.ky] - r.sy * c[r.kz];
        // Depths along the ray, scaled so that t = (U az + V bz + W cz) / det.
        const T az = r.sz * a[r.kz];
        const T bz = r.sz * b[r.kz];
        const T cz = r.sz * c[r.kz];

        // Edge functions: U weighs p0, V weighs p1, W weighs p2.
        const T u = cx * by - cy * bx;
        const T v = ax * cy - ay * cx;
        const T w = bx * ay - by * ax;
        if constexpr (std::is_same_v<T, float>) {
            // An exact 0 in float may be rounding: recompute in double, where the product of two
            // floats is exact, so each sign is the sign of the exact 2D determinant. The rest of
            // the test then stays in double so that no tiny value underflows back to 0.
            if (u == 0.0f || v == 0.0f || w == 0.0f) {
                const auto d = [](float x) { return static_cast<double>(x); };
                return finish<double>(d(cx) * d(by) - d(cy) * d(bx), d(ax) * d(cy) - d(ay) * d(cx),
                                      d(bx) * d(ay) - d(by) * d(ax), d(az), d(bz), d(cz), ray);
            }
        }
        return finish<T>(u, v, w, az, bz, cz, ray);
    }

private:
    /// Sign test, scaled window test and division, in the scalar E of the edge functions.
    template <class E>
    static std::optional<PrimHit<T>> finish(E u, E v, E w, E az, E bz, E cz, const Ray<T>& ray) {
        if ((u < E(0) || v < E(0) || w < E(0)) && (u > E(0) || v > E(0) || w > E(0))) {
            return std::nullopt;  // the ray passes outside one edge
        }
        const E det = u + v + w;
        if (det == E(0)) {
            return std::nullopt;  // ray parallel to the plane, or degenerate triangle
        }
        // Scaled hit distance, tested against the window before dividing.
        const E t_scaled = u * az + v * bz + w * cz;
        const E abs_det = std::abs(det);
        const E t_signed = det < E(0) ? -t_scaled : t_scaled;
        const E tmin = static_cast<E>(ray.tmin);
        const E tmax = static_cast<E>(ray.tmax);
        if (!(t_signed >= tmin * abs_det && t_signed <= tmax * abs_det)) {
            return std::nullopt;
        }
        const E inv_det = E(1) / det;
        const T t = static_cast<T>(t_scaled * inv_det);
        // Rounding in the division can step just outside the window; the window is a contract.
        if (!in_window(t, ray)) {
            return std::nullopt;
        }
        return PrimHit<T>{t, static_cast<T>(v * inv_det), static_cast<T>(w * inv_det)};
    }
};

static_assert(IntersectionMethod<Watertight<float>>);
static_assert(IntersectionMethod<Watertight<double>>);
static_assert(HasRayData<Watertight<float>>);

}  // namespace rtlab
