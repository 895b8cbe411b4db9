// Implicit-surface methods against an exact oracle: the ray polynomial f(o + t d) with exact
// rational coefficients (GMP; the float inputs are exact rationals, the tangle constant is 59/5),
// the exact number of distinct roots in [tmin, tmax] by a Sturm sequence over Q, the smallest
// root isolated by Sturm bisection and refined by 256-bit MPFR bisection to < 2^-110 relative.
#include "crosscheck/checks.h"
#include "crosscheck/driver.h"
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

using Q = mpq_class;

/// A polynomial over Q, ascending coefficients, no zero leading coefficient (empty = 0).
using QPoly = std::vector<Q>;

void trim(QPoly& p) {
    while (!p.empty() && p.back() == 0) {
        p.pop_back();
    }
}

Q eval(const QPoly& p, const Q& x) {
    Q v = 0;
    for (std::size_t i = p.size(); i-- > 0;) {
        v = v * x + p[i];
    }
    return v;
}

int sign(const Q& x) {
    return sgn(x);
}

/// Remainder of a divided by b (b non-zero).
QPoly remainder(QPoly a, const QPoly& b) {
    while (a.size() >= b.size() && !a.empty()) {
        const Q f = a.back() / b.back();
        const std::size_t shift = a.size() - b.size();
        for (std::size_t i = 0; i < b.size(); ++i) {
            a[i + shift] -= f * b[i];
        }
        a.pop_back();  // the leading term cancels exactly
        trim(a);
    }
    return a;
}

/// The Sturm sequence p, p', -rem(p, p'), ... down to the last non-zero remainder.
std::vector<QPoly> sturm(const QPoly& p) {
    std::vector<QPoly> seq{p};
    QPoly d;
    for (std::size_t i = 1; i < p.size(); ++i) {
        d.push_back(p[i] * static_cast<long>(i));
    }
    trim(d);
    if (d.empty()) {
        return seq;
    }
    seq.push_back(d);
    for (;;) {
        QPoly r = remainder(seq[seq.size() - 2], seq.back());
        if (r.empty()) {
            break;
        }
        for (Q& c : r) {
            c = -c;
        }
        seq.push_back(std::move(r));
    }
    return seq;
}

/// Sign variations of the sequence at x (zeros skipped).
int variations(const std::vector<QPoly>& seq, const Q& x) {
    int count = 0, last = 0;
    for (const QPoly& p : seq) {
        const int s = sign(eval(p, x));
        if (s != 0) {
            count += (last != 0 && s != last) ? 1 : 0;
            last = s;
        }
    }
    return count;
}

/// p(x) in MPFR for the n coefficients c (ascending), at the precision of out.
void eval_mpfr(const mpfr_t* c, std::size_t n, const mpfr_t x, mpfr_t out) {
    mpfr_set(out, c[n - 1], MPFR_RNDN);
    for (std::size_t i = n - 1; i-- > 0;) {
        mpfr_mul(out, out, x, MPFR_RNDN);
        mpfr_add(out, out, c[i], MPFR_RNDN);
    }
}

/// The exact answer: hit in [tmin, tmax] and the smallest root there (rounded to double).
struct ImplicitOracle {
    bool hit = false;
    double t = 0;
};

/// Exact oracle for the polynomial p over the window [tmin, tmax] (tmax may be infinite).
ImplicitOracle solve_exact(QPoly p, float tmin, float tmax) {
    trim(p);
    ImplicitOracle out;
    if (p.size() < 2) {
        return out;  // constant along the ray (a zero polynomial cannot occur for d != 0)
    }
    Q lo(static_cast<double>(tmin));
    if (eval(p, lo) == 0) {
        return {true, static_cast<double>(tmin)};
    }
    Q hi;
    if (std::isinf(tmax)) {
        // Cauchy bound: every root is below 1 + max |c_i / c_n|.
        Q bound = 0;
        for (std::size_t i = 0; i + 1 < p.size(); ++i) {
            bound = std::max<Q>(bound, abs(p[i] / p.back()));
        }
        hi = std::max<Q>(bound + 1, lo + 1);
    } else {
        hi = Q(static_cast<double>(tmax));
    }
    const std::vector<QPoly> seq = sturm(p);
    int v_lo = variations(seq, lo);
    int n = v_lo - variations(seq, hi);  // distinct roots in (lo, hi]
    if (n <= 0) {
        return out;
    }
    out.hit = true;
    // Isolate the smallest root: keep the lower half whenever it holds a root.
    for (int step = 0; step < 400 && n > 1; ++step) {
        const Q mid = (lo + hi) / 2;
        const int v_mid = variations(seq, mid);
        if (v_lo - v_mid >= 1) {
            hi = mid;
            n = v_lo - v_mid;
        } else {
            lo = mid;
            v_lo = v_mid;
        }
    }
    if (eval(p, hi) == 0) {
        out.t = hi.get_d();
        return out;
    }
    if (sign(eval(p, lo)) == sign(eval(p, hi))) {
        // Even multiplicity (exact tangency): no sign change; keep bisecting by Sturm counts.
        for (int step = 0; step < 130; ++step) {
            const Q mid = (lo + hi) / 2;
            const int v_mid = variations(seq, mid);
            if (v_lo - v_mid >= 1) {
                hi = mid;
            } else {
                lo = mid;
                v_lo = v_mid;
            }
        }
        out.t = Q((lo + hi) / 2).get_d();
        return out;
    }
    // Simple (odd-multiplicity) root with a sign change: 256-bit MPFR bisection; coefficients
    // rounded to 256 bits, far below the 110 bits the refinement needs.
    const int s_lo = sign(eval(p, lo));
    if (p.size() > 5) {
        throw std::logic_error("implicit oracle: degree above 4");
    }
    mpfr_t c[5];
    for (std::size_t i = 0; i < p.size(); ++i) {
        mpfr_init2(c[i], 256);
        mpfr_set_q(c[i], p[i].get_mpq_t(), MPFR_RNDN);
    }
    mpfr_t a, b, m, v, w;
    mpfr_inits2(256, a, b, m, v, w, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_q(a, lo.get_mpq_t(), MPFR_RNDN);
    mpfr_set_q(b, hi.get_mpq_t(), MPFR_RNDN);
    for (int step = 0; step < 600; ++step) {
        mpfr_add(m, a, b, MPFR_RNDN);
        mpfr_div_2ui(m, m, 1, MPFR_RNDN);
        mpfr_sub(w, b, a, MPFR_RNDN);
        mpfr_abs(v, m, MPFR_RNDN);
        mpfr_mul_2si(v, v, -110, MPFR_RNDN);
        if (mpfr_cmp(w, v) <= 0) {
            break;
        }
        eval_mpfr(c, p.size(), m, v);
        if (mpfr_sgn(v) == 0) {
            break;
        }
        if (mpfr_sgn(v) == s_lo) {
            mpfr_set(a, m, MPFR_RNDN);
        } else {
            mpfr_set(b, m, MPFR_RNDN);
        }
    }
    out.t = mpfr_get_d(m, MPFR_RNDN);
    mpfr_clears(a, b, m, v, w, static_cast<mpfr_ptr>(nullptr));
    for (std::size_t i = 0; i < p.size(); ++i) {
        mpfr_clear(c[i]);
    }
    return out;
}

Q exact(float x) {
    return Q(static_cast<double>(x));
}

/// Exact ray polynomial of a torus (the expansion of Torus::along over Q).
QPoly exact_along(const Torus<float>& s, const Vec3f& o, const Vec3f& d) {
    Q a = 0, b = 0, c = 0, ea = 0, eb = 0, ec = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const Q q = exact(o[k]) - exact(s.center[k]);
        const Q dk = exact(d[k]);
        a += dk * dk;
        b += 2 * q * dk;
        c += q * q;
        if (k < 2) {
            ea += dk * dk;
            eb += 2 * q * dk;
            ec += q * q;
        }
    }
    const Q big = exact(s.major), small = exact(s.minor);
    c += big * big - small * small;
    const Q r4 = 4 * big * big;
    return {c * c - r4 * ec, 2 * b * c - r4 * eb, b * b + 2 * a * c - r4 * ea, 2 * a * b, a * a};
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

float uni(std::mt19937_64& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}

Vec3f random_unit(std::mt19937_64& rng) {
    for (;;) {
        const Vec3f v{uni(rng, -1, 1), uni(rng, -1, 1), uni(rng, -1, 1)};
        const float l2 = length_squared(v);
        if (l2 > 0.01f && l2 <= 1) {
            return v / std::sqrt(l2);
        }
    }
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
            set.oracle[i] =
                solve_exact(exact_along(c.surface, c.ray.org, c.ray.dir), c.ray.tmin, c.ray.tmax);
        });
        sets.push_back(std::move(set));
    }
    return sets;
}

/// The surface in scalar T.
template <class T>
Torus<T> convert_surface(const Torus<float>& s) {
    return {Vec3<T>(s.center), static_cast<T>(s.major), static_cast<T>(s.minor)};
}
template <class T>
TangleCube<T> convert_surface(const TangleCube<float>& s) {
    return {Vec3<T>(s.center), static_cast<T>(s.scale)};
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
        return convert_surface<T>(c.surface);
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

}  // namespace rtlab::xcheck
