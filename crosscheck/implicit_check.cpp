// Implicit-surface methods against an exact oracle: the ray polynomial f(o + t d) with exact
// rational coefficients (GMP; the float inputs are exact rationals, the tangle constant is 59/5),
// the exact number of distinct roots in [tmin, tmax] by a Sturm sequence over Q, the smallest
// root isolated by Sturm bisection and refined by 256-bit MPFR bisection to < 2^-110 relative.
#include "crosscheck/checks.h"
#include "crosscheck/driver.h"
#include "crosscheck/exact.h"
#include "crosscheck/ray_sets.h"
#include "intersect/implicit/methods.h"

#include <cmath>
#include <gmpxx.h>
#include <mpfr.h>
#include <optional>
#include <random>
#include <stdexcept>
#include <tbb/parallel_for.h>
#include <type_traits>

namespace rtlab::xcheck {

namespace {

/// The exact answer: hit in [tmin, tmax] and the smallest root there (rounded to double).
using ImplicitOracle = ExactRoot;

using Q = mpq_class;

/// A polynomial over Q, ascending coefficients.
using QPoly = std::vector<Q>;

Q exact(float x) {
    return Q(static_cast<double>(x));
}

/// Exact ray polynomial of a torus (the expansion of Torus::along over Q).
QPoly exact_along(const Torus<float>& s, const Vec3f& o, const Vec3f& d) {
    return exact_torus_along({Vec3d(s.center), s.major, s.minor}, Vec3d(o), Vec3d(d));
}

/// Exact ray polynomial of a tangle cube (constant 11.8 = 59/5 exactly).
QPoly exact_along(const TangleCube<float>& s, const Vec3f& o, const Vec3f& d) {
    QPoly p(5, Q(0));
    p[0] = Q(59, 5);
    const Q scale = exact(s.scale);
    for (std::size_t k = 0; k < 3; ++k) {
        const Q a = (exact(o[k]) - exact(s.center[k])) / scale;
        const Q b = exact(d[k]) / scale;
        const Q a2 = a * a, b2 = b * b;
        p[0] += a2 * a2 - 5 * a2;
        p[1] += 4 * a2 * a * b - 10 * a * b;
        p[2] += 6 * a2 * b2 - 5 * b2;
        p[3] += 4 * a * b2 * b;
        p[4] += b2 * b2;
    }
    return p;
}

/// One test: a surface and a ray, in float so float and double runs trace the same input.
template <template <class> class S>
struct ImplicitCase {
    S<float> surface;
    Ray<float> ray;
};

template <template <class> class S>
struct ImplicitSet {
    std::string name;
    std::vector<ImplicitCase<S>> cases;
    std::vector<ImplicitOracle> oracle;
};

/// A random unit vector.
Vec3f random_unit(std::mt19937_64& rng) {
    const auto [v, l2] = ball_shell_point(rng);
    return v / std::sqrt(l2);
}

Torus<float> random_surface(std::mt19937_64& rng, const Torus<float>*) {
    const float major = uni(rng, 0.5f, 2);
    return {
        {uni(rng, -5, 5), uni(rng, -5, 5), uni(rng, -5, 5)}, major, major * uni(rng, 0.1f, 0.5f)};
}

TangleCube<float> random_surface(std::mt19937_64& rng, const TangleCube<float>*) {
    return {{uni(rng, -5, 5), uni(rng, -5, 5), uni(rng, -5, 5)},
            std::ldexp(1.0f, static_cast<int>(rng() % 3) - 1)};
}

/// A ray from outside the box to a uniform point in it.
Ray<float> ray_through_box(std::mt19937_64& rng, const Bounds3f& box) {
    const Vec3f target =
        box.lo + box.diagonal() * Vec3f{uni(rng, 0, 1), uni(rng, 0, 1), uni(rng, 0, 1)};
    const Vec3f org = box.center() + random_unit(rng) * (1.5f * length(box.diagonal()));
    return {org, target - org};
}

/// Ray sets for surface kind S: random through the box, grazing (tangent to the surface at a
/// point found in double, offset along the normal by |delta| in [1e-7, 1e-2] box sizes), and
/// axis-aligned (half of them along z, the torus axis; one in 8 exactly on the centre line).
template <template <class> class S>
std::vector<ImplicitSet<S>> make_sets(std::size_t n, std::uint64_t seed) {
    const std::vector<std::string> names{"random", "grazing", "axis"};
    std::vector<ImplicitSet<S>> sets;
    for (std::size_t si = 0; si < names.size(); ++si) {
        ImplicitSet<S> set;
        set.name = names[si];
        const std::size_t count = n / names.size() + (si < n % names.size() ? 1 : 0);
        std::mt19937_64 rng(seed * 0xD1B54A32D192ED03ull + si + 17 * S<float>::name.size());
        for (std::size_t i = 0; i < count; ++i) {
            ImplicitCase<S> c;
            c.surface = random_surface(rng, static_cast<const S<float>*>(nullptr));
            const Bounds3f box = c.surface.bounds();
            const float size = length(box.diagonal());
            if (set.name == "random") {
                c.ray = ray_through_box(rng, box);
            } else if (set.name == "grazing") {
                using M = ImplicitClosedForm<S, double>;
                S<double> exact_surface;
                if constexpr (std::is_same_v<S<float>, Torus<float>>) {
                    exact_surface = {Vec3d(c.surface.center), c.surface.major, c.surface.minor};
                } else {
                    exact_surface = {Vec3d(c.surface.center), c.surface.scale};
                }
                const auto prepared = M::prepare(exact_surface);
                std::optional<PrimHit<double>> hit;
                Ray<double> probe;
                while (!hit) {
                    probe = static_cast<Ray<double>>(ray_through_box(rng, box));
                    hit = M::intersect(prepared, probe);
                }
                const Vec3d point = probe.at(hit->t);
                const Vec3d normal = normalize(exact_surface.gradient(point));
                const Vec3d tangent = normalize(cross(normal, Vec3d(random_unit(rng))));
                const double delta =
                    (i % 2 ? 1.0 : -1.0) * std::pow(10.0, static_cast<double>(uni(rng, -7, -2)));
                const Vec3d through = point + normal * (delta * static_cast<double>(size));
                c.ray = {Vec3f(through - tangent * static_cast<double>(size)), Vec3f(tangent)};
            } else {
                const std::size_t axis = rng() % 2 ? 2 : rng() % 2;
                Vec3f org = c.surface.center;
                if (i % 8 != 0) {
                    org = box.center() + box.diagonal() * Vec3f{uni(rng, -0.55f, 0.55f),
                                                                uni(rng, -0.55f, 0.55f),
                                                                uni(rng, -0.55f, 0.55f)};
                }
                Vec3f dir{0, 0, 0};
                dir[axis] = rng() % 2 ? 1.0f : -0.75f;
                org[axis] = c.surface.center[axis] - dir[axis] * size;
                c.ray = {org, dir};
            }
            set.cases.push_back(c);
        }
        set.oracle.resize(set.cases.size());
        tbb::parallel_for(std::size_t(0), set.cases.size(), [&](std::size_t i) {
            const ImplicitCase<S>& c = set.cases[i];
            set.oracle[i] = exact_first_root(exact_along(c.surface, c.ray.org, c.ray.dir),
                                             c.ray.tmin, c.ray.tmax);
        });
        sets.push_back(std::move(set));
    }
    return sets;
}

/// Visits the methods of surface kind S in precision T (see run_wanted).
template <template <class> class S>
constexpr auto for_each_method =
    [](auto tag, const auto& f) { for_each_implicit_method<S, typename decltype(tag)::type>(f); };

/// Runs the wanted methods of surface kind S (names "<surface>/<method>").
template <template <class> class S>
void run_surface(const Options& opt,
                 const std::vector<std::string>& wanted,
                 std::vector<Row>& rows) {
    const std::string prefix = std::string(S<float>::name) + "/";
    bool any = false;
    for (const std::string& w : wanted) {
        any = any || w.rfind(prefix, 0) == 0;
    }
    if (!any) {
        return;
    }
    const std::vector<ImplicitSet<S>> sets = make_sets<S>(opt.rays, opt.seed);
    const auto convert = []<class T>(const ImplicitCase<S>& c, std::type_identity<T>) {
        return to_scalar<T>(c.surface);
    };
    run_wanted(
        wanted, opt, for_each_method<S>,
        [&]<class M>() {
            run_case_sets<M>("implicit", prefix + std::string(M::name), sets, convert, opt.by_set,
                             rows);
        },
        prefix);
}

}  // namespace

std::vector<std::string> implicit_methods() {
    std::vector<std::string> names = method_names(for_each_method<Torus>, "torus/");
    const std::vector<std::string> tangle = method_names(for_each_method<TangleCube>, "tangle/");
    names.insert(names.end(), tangle.begin(), tangle.end());
    return names;
}

std::vector<Row> check_implicits(const Options& opt) {
    const std::vector<std::string> wanted =
        select_methods(implicit_methods(), opt.methods, "implicit");
    std::vector<Row> rows;
    run_surface<Torus>(opt, wanted, rows);
    run_surface<TangleCube>(opt, wanted, rows);
    return rows;
}

namespace {

/// The check's random and grazing sets of surface kind S (n rays each), then far rays: from
/// 1e2 to 1e3 box diagonals away to a uniform point of the box.
template <template <class> class S>
BenchCases<S<float>> implicit_bench_cases(std::size_t n, std::uint64_t seed) {
    const std::vector<ImplicitSet<S>> sets = make_sets<S>(3 * n, seed);
    BenchCases<S<float>> out;
    const auto add = [&](const ImplicitCase<S>& c, const ImplicitOracle& o, BenchSet set) {
        Sample smp;
        smp.ray = c.ray;
        smp.shape = static_cast<std::uint32_t>(out.shapes.size());
        smp.set = set;
        out.shapes.push_back(c.surface);
        out.samples.push_back(smp);
        out.truth.push_back({o.hit, o.t});
    };
    for (const ImplicitSet<S>& set : sets) {
        const BenchSet bs = set.name == "random" ? bench_random : bench_grazing;
        if (set.name == "random" || set.name == "grazing") {
            for (std::size_t i = 0; i < set.cases.size(); ++i) {
                add(set.cases[i], set.oracle[i], bs);
            }
        }
    }
    std::mt19937_64 rng(seed * 0xD1B54A32D192ED03ull + 1001 + 17 * S<float>::name.size());
    std::vector<ImplicitCase<S>> far(n);
    for (ImplicitCase<S>& c : far) {
        c.surface = random_surface(rng, static_cast<const S<float>*>(nullptr));
        const Bounds3f box = c.surface.bounds();
        const Vec3f target =
            box.lo + box.diagonal() * Vec3f{uni(rng, 0, 1), uni(rng, 0, 1), uni(rng, 0, 1)};
        const Vec3f org = box.center() + random_unit(rng) * (length(box.diagonal()) *
                                                             std::pow(10.0f, uni(rng, 2, 3)));
        c.ray = {org, target - org};
    }
    std::vector<ImplicitOracle> oracle(far.size());
    tbb::parallel_for(std::size_t(0), far.size(), [&](std::size_t i) {
        oracle[i] = exact_first_root(exact_along(far[i].surface, far[i].ray.org, far[i].ray.dir),
                                     far[i].ray.tmin, far[i].ray.tmax);
    });
    for (std::size_t i = 0; i < far.size(); ++i) {
        add(far[i], oracle[i], bench_far);
    }
    return out;
}

}  // namespace

BenchCases<Torus<float>> torus_bench_cases(std::size_t n, std::uint64_t seed) {
    return implicit_bench_cases<Torus>(n, seed);
}

BenchCases<TangleCube<float>> tangle_bench_cases(std::size_t n, std::uint64_t seed) {
    return implicit_bench_cases<TangleCube>(n, seed);
}

}  // namespace rtlab::xcheck
