#pragma once
// The three implicit-surface methods, templated on the surface and the scalar. All clip to the
// surface's box first (implicit.h). Costs below are per ray after the clip (~6 divisions).
//   closed_form: Ferrari/Cardano roots of the quartic (closed_form.h); ~3 sqrt, 1 cbrt/acos.
//   newton: 16 uniform steps over the window, first sign change refined by Newton + bisection.
//   laguerre: all roots by Laguerre with deflation (laguerre.h), smallest real one in the window.

#include "intersect/implicit/closed_form.h"
#include "intersect/implicit/implicit.h"
#include "intersect/implicit/laguerre.h"
#include "intersect/implicit/newton.h"
#include "intersect/implicit/tangle_cube.h"
#include "intersect/implicit/torus.h"
#include "intersect/method.h"

#include <optional>
#include <string_view>
#include <tuple>
#include <utility>

namespace rtlab {

/// Members common to the three methods (the family's types, prepare_implicit, implicit_box and
/// ImplicitRay as per-ray set-up; normal, and intersect by Derived::first_root, the method's
/// first root in [0, 1] of the ray polynomial).
template <template <class> class Surface, class T, class Derived>
struct ImplicitMethodBase : FamilyRayMethod<Derived,
                                            T,
                                            Surface<T>,
                                            PreparedImplicit<Surface<T>>,
                                            prepare_implicit<Surface<T>>,
                                            implicit_box<Surface<T>>,
                                            ImplicitRay<T>> {
    using MethodDefaults<Derived>::intersect;
    /// Unit normal (normalised gradient) at the hit point of ray at hit.t.
    static Vec3<T> normal(const PreparedImplicit<Surface<T>>& p,
                          const Ray<T>& ray,
                          const PrimHit<T>& hit) {
        return implicit_normal(p, ray.at(hit.t));
    }
    /// Nearest t in [tmin, tmax] inside the box; u = v = 0.
    static std::optional<PrimHit<T>> intersect(const PreparedImplicit<Surface<T>>& p,
                                               const Ray<T>& ray,
                                               const ImplicitRay<T>& rd) {
        return implicit_intersect(p, ray, rd,
                                  [](const auto& poly) { return Derived::first_root(poly); });
    }
};

/// Closed form: all real roots of the ray quartic on the unit window (solve_closed_form_unit:
/// negligible leading terms dropped), the first in the window. Exact double roots (tangency) are
/// kept by the small discriminant slack of solve_quadratic/solve_cubic.
template <template <class> class Surface, class T>
struct ImplicitClosedForm : ImplicitMethodBase<Surface, T, ImplicitClosedForm<Surface, T>> {
    static constexpr std::string_view name = "closed_form";

    /// The smallest real root of poly in [0, 1].
    template <std::size_t N>
    static std::optional<T> first_root(const Polynomial<T, N>& poly) {
        const RealRoots<T, 4> r = solve_closed_form_unit(poly);
        T u;
        return r.first_in(T(0), T(1), u) ? std::optional<T>(u) : std::nullopt;
    }
};

/// Newton: the window [0, 1] is cut into `steps` equal intervals; the first with a sign change
/// is refined by newton_bisect. An interval without a sign change whose derivative changes sign
/// is split at the extremum (found by newton_bisect on p'), so two roots closer than a step are
/// still found; a tangent (double) root is found only if p is exactly 0 at the extremum.
template <template <class> class Surface, class T>
struct ImplicitNewton : ImplicitMethodBase<Surface, T, ImplicitNewton<Surface, T>> {
    static constexpr std::string_view name = "newton";
    static constexpr int steps = 16;

    /// First root of poly in [0, 1] by marching and bracketed Newton of at most max_iter steps
    /// per refinement (the default converges; the benchmarks cap it to measure the error).
    template <std::size_t N>
    static std::optional<T> first_root(const Polynomial<T, N>& poly, int max_iter = 100) {
        const auto dpoly = poly.derivative();
        const auto fdf = [&](T u) {
            T v, d;
            poly.eval(u, v, d);
            return std::pair<T, T>{v, d};
        };
        const auto dfdf = [&](T u) {
            T v, d;
            dpoly.eval(u, v, d);
            return std::pair<T, T>{v, d};
        };
        T ua = T(0), va = poly(ua), da = dpoly(ua);
        if (va == T(0)) {
            return ua;
        }
        for (int i = 1; i <= steps; ++i) {
            const T ub = static_cast<T>(i) / static_cast<T>(steps);
            const T vb = poly(ub), db = dpoly(ub);
            if ((va < T(0)) != (vb < T(0)) || vb == T(0)) {
                return newton_bisect(fdf, ua, ub, max_iter);
            }
            if ((da < T(0)) != (db < T(0))) {
                // An extremum inside: if p there reaches the other sign, a root pair straddles it.
                if (const std::optional<T> uc = newton_bisect(dfdf, ua, ub, max_iter)) {
                    const T vc = poly(*uc);
                    if (vc == T(0)) {
                        return uc;
                    }
                    if ((vc < T(0)) != (va < T(0))) {
                        return newton_bisect(fdf, ua, *uc, max_iter);
                    }
                }
            }
            ua = ub;
            va = vb;
            da = db;
        }
        return std::nullopt;
    }
};

/// Laguerre: all complex roots with deflation, the smallest real one in the window.
template <template <class> class Surface, class T>
struct ImplicitLaguerre : ImplicitMethodBase<Surface, T, ImplicitLaguerre<Surface, T>> {
    static constexpr std::string_view name = "laguerre";

    /// The smallest real root of poly in [0, 1].
    template <std::size_t N>
    static std::optional<T> first_root(const Polynomial<T, N>& poly) {
        const auto r = laguerre_real_roots(poly);
        T u;
        return r.first_in(T(0), T(1), u) ? std::optional<T>(u) : std::nullopt;
    }
};

/// Every implicit-surface method on Surface in scalar T as a type list; the first is the
/// tracer's default.
template <template <class> class Surface, class T>
using ImplicitMethods = std::
    tuple<ImplicitClosedForm<Surface, T>, ImplicitNewton<Surface, T>, ImplicitLaguerre<Surface, T>>;

static_assert(names_unique<ImplicitMethods<Torus, float>>());
static_assert(ImplicitSurface<Torus<float>>);
static_assert(ImplicitSurface<TangleCube<double>>);
static_assert(IntersectionMethod<ImplicitClosedForm<Torus, float>>);
static_assert(IntersectionMethod<ImplicitNewton<TangleCube, double>>);
static_assert(IntersectionMethod<ImplicitLaguerre<Torus, double>>);
static_assert(HasRayData<ImplicitNewton<Torus, float>>);

/// Calls f.template operator()<M>() for every implicit method M on Surface in scalar T, in list
/// order.
template <template <class> class Surface, class T, class F>
void for_each_implicit_method(F&& f) {
    for_each_type<ImplicitMethods<Surface, T>>(f);
}

}  // namespace rtlab
