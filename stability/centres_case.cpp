// Rays through sphere centres, from origins rounded onto sphere surfaces (the near root of the
// quadratic is then within rounding of t = 0) and from inside spheres (the far root, exactly
// once). Shapes and rays are rounded to the precision under test; references are exact for the
// rounded input (crosscheck/exact.h).
#include "crosscheck/exact.h"
#include "intersect/sphere/methods.h"
#include "stability/cases.h"
#include "stability/exact_judge.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace rtlab::stab {

namespace {

/// Centre in [-100, 100]^3, radius log-uniform in [1e-2, 1e2], rounded to T.
template <class T>
Sphered random_sphere(Sampler& rng) {
    const Vec3d c{rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100)};
    return {round_to<T>(c),
            static_cast<double>(static_cast<T>(std::pow(10.0, rng.uniform(-2, 2))))};
}

/// kind 0: through the centre from 2 to 100 radii away; 1: origin rounded onto the surface,
/// window from 0; 2: the same with tmin = 1e-4 r / |d| (a secondary ray's window); 3: origin
/// inside (an eighth exactly at the centre, the rest within 0.999 r).
template <class T>
SphereSamples make_samples(int kind, std::size_t n, std::uint64_t seed, std::uint64_t stream) {
    Sampler rng(seed, stream);
    SphereSamples s;
    for (std::size_t i = 0; i < n; ++i) {
        const Sphered sp = random_sphere<T>(rng);
        Rayd ray;
        if (kind == 0) {
            const Vec3d org =
                sp.center + rng.unit() * (sp.radius * std::pow(10.0, rng.uniform(0.3, 2)));
            ray = {round_to<T>(org), Vec3d{}};
            ray.dir = round_to<T>((sp.center - ray.org) * rng.uniform(0.5, 2));
        } else if (kind == 1 || kind == 2) {
            ray.org = round_to<T>(sp.center + rng.unit() * sp.radius);
            ray.dir = round_to<T>(rng.unit() * rng.uniform(0.5, 2));
            if (kind == 2) {
                ray.tmin = static_cast<double>(static_cast<T>(1e-4 * sp.radius / length(ray.dir)));
            }
        } else {
            ray.org = i % 8 == 0 ? sp.center : round_to<T>(sp.center + rng.ball(0.999 * sp.radius));
            ray.dir = round_to<T>(rng.unit() * rng.uniform(0.5, 2));
        }
        s.spheres.push_back(sp);
        s.rays.push_back(ray);
    }
    add_sphere_truth(s);
    return s;
}

/// Root-choice judgement (kinds 1-3): a hit/miss disagreement or a t off the exact one by more
/// than 1e-3 of the sphere's chord scale r / |d| is a failure; t errors are relative to
/// max(|t|, r / |d|). With `once` a second query from just past the hit must miss. Where the
/// exact root lies within 1e-6 r / |d| of tmin the answer is decided by rounding and not judged.
template <class M>
Row root_row(const SphereSamples& s,
             const std::string& case_name,
             const std::string& label,
             bool once) {
    using T = typename M::Scalar;
    std::size_t fail = 0, undecided = 0, near_taken = 0, far_taken = 0, missed = 0, second = 0;
    std::vector<double> errs;
    std::vector<typename M::Prepared> prepared;
    std::vector<Ray<T>> rays;
    for (std::size_t i = 0; i < s.rays.size(); ++i) {
        prepared.push_back(M::prepare(
            Sphere<T>{Vec3<T>(s.spheres[i].center), static_cast<T>(s.spheres[i].radius)}));
        rays.push_back(static_cast<Ray<T>>(s.rays[i]));
    }
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const double scale = s.spheres[i].radius / length(s.rays[i].dir);
        const auto hit = M::intersect(prepared[i], rays[i]);
        if (!hit) {
            ++missed;
        } else if (static_cast<double>(hit->t) - s.rays[i].tmin < 1e-3 * scale) {
            ++near_taken;
        } else {
            ++far_taken;
        }
        const ExactTruth& tr = s.truth[i];
        if (tr.hit && std::abs(tr.t - s.rays[i].tmin) < 1e-6 * scale) {
            ++undecided;
            continue;
        }
        if (hit.has_value() != tr.hit) {
            ++fail;
            continue;
        }
        if (hit) {
            const double t = static_cast<double>(hit->t);
            const double e = std::abs(t - tr.t) / std::max(std::abs(tr.t), scale);
            if (!std::isfinite(t) || e > 1e-3) {
                ++fail;
                continue;
            }
            errs.push_back(e);
            if (once) {
                Ray<T> again = rays[i];
                again.tmin = hit->t + std::abs(hit->t) * T(16) * std::numeric_limits<T>::epsilon();
                if (M::intersect(prepared[i], again)) {
                    ++second;
                    ++fail;
                }
            }
        }
    }
    const Stopwatch sw;
    std::size_t sink = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        sink += M::intersect(prepared[i], rays[i]).has_value() ? 1 : 0;
    }
    const double ns = sw.ns() / static_cast<double>(std::max<std::size_t>(1, rays.size()));
    volatile std::size_t keep = sink;
    static_cast<void>(keep);
    std::string note = "took the near root (t - tmin < 1e-3 r/|d|) " + std::to_string(near_taken) +
                       ", the far root " + std::to_string(far_taken) + ", missed " +
                       std::to_string(missed) + "; " + std::to_string(undecided) +
                       " rays with the exact root within 1e-6 r/|d| of tmin not judged";
    if (once) {
        note += "; second hits after the first " + std::to_string(second);
    }
    Row r = make_row(case_name, std::string(M::name) + " " + label, precision_of<T>(), rays.size(),
                     fail, once ? "misses + wrong roots + second hits" : "wrong hit/miss or root",
                     ns, note);
    if (!errs.empty()) {
        const auto mid = errs.begin() + static_cast<std::ptrdiff_t>(errs.size() / 2);
        std::nth_element(errs.begin(), mid, errs.end());
        r.median_rel_t_err = *mid;
        r.max_rel_t_err = *std::max_element(errs.begin(), errs.end());
    }
    return r;
}

template <class T>
void run_precision(const Options& opt, std::vector<Row>& rows) {
    const std::uint64_t base = std::is_same_v<T, float> ? 300 : 400;
    const SphereSamples centre = make_samples<T>(0, opt.rays, opt.seed, base);
    std::vector<Ray<T>> rays;
    for (const Rayd& r : centre.rays) {
        rays.push_back(static_cast<Ray<T>>(r));
    }
    for_each_sphere_method<T>([&]<class M>() {
        const MethodTally t = judge<M>(rays, centre.truth, [&](std::size_t i) {
            return Sphere<T>{Vec3<T>(centre.spheres[i].center),
                             static_cast<T>(centre.spheres[i].radius)};
        });
        rows.push_back(tally_row("centres/through_centre", std::string(M::name), precision_of<T>(),
                                 t, "origin 2-100 radii away"));
    });
    const SphereSamples surf0 = make_samples<T>(1, opt.rays, opt.seed, base + 1);
    const SphereSamples surf1 = make_samples<T>(2, opt.rays, opt.seed, base + 2);
    const SphereSamples inside = make_samples<T>(3, opt.rays, opt.seed, base + 3);
    for_each_sphere_method<T>([&]<class M>() {
        rows.push_back(root_row<M>(surf0, "centres/on_surface", "tmin=0", false));
        rows.push_back(root_row<M>(surf1, "centres/on_surface", "tmin=1e-4r", false));
        rows.push_back(root_row<M>(inside, "centres/inside", "", true));
    });
}

}  // namespace

std::vector<Row> run_centres(const Options& opt) {
    std::vector<Row> rows;
    run_precision<float>(opt, rows);
    run_precision<double>(opt, rows);
    return rows;
}

}  // namespace rtlab::stab
