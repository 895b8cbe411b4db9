#pragma once
// The plumbing every checker shares: the seeded float generator and ray-set helpers of the box and
// polygon checks, the method selection (wanted names, float then double), the timed runs of a
// method over oracle-judged samples, and the assembly of the "all" row and the per-set rows.
// Timing is split: the per-ray set-up (precompute) of all rays, then the tests on the set-up data.
// Each checker keeps its own shapes, ray sets and oracle; shapes reach a method through a
// `convert(shape_or_case, std::type_identity<T>{})` callable that returns the shape in scalar T.

#include "crosscheck/accumulator.h"
#include "crosscheck/crosscheck.h"
#include "intersect/hit.h"
#include "intersect/method.h"
#include "intersect/ray.h"
#include "intersect/vec.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtlab::xcheck {

/// Seeded float generator (mt19937_64 bits, our own mapping, so results do not depend on the
/// standard library's distributions).
class Rng {
public:
    /// Same seed, same sequence.
    explicit Rng(std::uint64_t seed) : g_(seed) {}
    /// Uniform in [a, b].
    float uni(float a, float b) {
        const float u = static_cast<float>(g_() >> 40) * 0x1p-24f;
        return a + (b - a) * u;
    }
    /// Uniform integer in [0, n).
    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(g_() % n); }
    /// True with probability p.
    bool coin(float p) { return uni(0.0f, 1.0f) < p; }
    /// Random direction, length in [0.1, 1], not normalised.
    Vec3f dir() {
        for (;;) {
            const Vec3f d{uni(-1, 1), uni(-1, 1), uni(-1, 1)};
            const float l2 = length_squared(d);
            if (l2 <= 1.0f && l2 >= 0.01f) {
                return d;
            }
        }
    }

private:
    std::mt19937_64 g_;
};

/// Uniform float in [lo, hi) through the standard library's distribution, as the sphere and
/// implicit checks draw their sets (their recorded results depend on this mapping).
inline float uni(std::mt19937_64& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}

/// A point v of the unit ball outside the ball of radius 0.1, by rejection from the cube (uni),
/// with its squared length.
inline std::pair<Vec3f, float> ball_shell_point(std::mt19937_64& rng) {
    for (;;) {
        const Vec3f v{uni(rng, -1, 1), uni(rng, -1, 1), uni(rng, -1, 1)};
        const float l2 = length_squared(v);
        if (l2 > 0.01f && l2 <= 1) {
            return {v, l2};
        }
    }
}

/// Rays per set for N sets: an equal split of n, the remainder going to the first sets.
template <std::size_t N>
std::array<std::size_t, N> split_rays(std::size_t n) {
    std::array<std::size_t, N> c{};
    for (std::size_t s = 0; s < N; ++s) {
        c[s] = n / N + (s < n % N ? 1 : 0);
    }
    return c;
}

/// A small signed offset: exactly 0 a third of the time, else +-[0, 1e-6].
inline float tiny(Rng& rng) {
    return rng.coin(0.33f) ? 0.0f : rng.uni(-1e-6f, 1e-6f);
}

/// A zero that is -0.0 half the time, or (rarely) a denormal of either sign.
inline float zero_like(Rng& rng) {
    if (rng.coin(0.1f)) {
        return rng.coin(0.5f) ? 1e-40f : -1e-40f;
    }
    return rng.coin(0.5f) ? 0.0f : -0.0f;
}

/// One traced ray: which shape it is tested against and which set it belongs to.
struct Sample {
    Rayf ray;                 ///< the ray, in float so both precisions trace the same one
    std::uint32_t shape = 0;  ///< index into Workload::shapes
    std::uint8_t set = 0;     ///< index of the ray set
};

/// The oracle's answer for one sample.
struct Truth {
    bool hit = false;  ///< the exact hit/miss answer
    double t = 0;      ///< the exact nearest t, rounded to double (0 on a miss)
};

/// Shapes and samples of one check; truth[i] is the oracle's answer for samples[i].
template <class Shape>
struct Workload {
    std::vector<Shape> shapes;    ///< the float shapes
    std::vector<Sample> samples;  ///< all rays of all sets
    std::vector<Truth> truth;     ///< one answer per sample
};

/// The samples of every set in set order, counts[s] of set s: sample j of set s tests shape
/// pick(s, j) with the ray make_ray(s, shape), called in that order (so a seeded generator the
/// callables share advances the same way on every run).
template <std::size_t N, class Pick, class MakeRay>
std::vector<Sample> make_samples(const std::array<std::size_t, N>& counts,
                                 const Pick& pick,
                                 const MakeRay& make_ray) {
    std::vector<Sample> samples;
    for (std::size_t s = 0; s < N; ++s) {
        for (std::size_t j = 0; j < counts[s]; ++j) {
            Sample smp;
            smp.shape = pick(s, j);
            smp.set = static_cast<std::uint8_t>(s);
            smp.ray = make_ray(s, smp.shape);
            samples.push_back(smp);
        }
    }
    return samples;
}

/// Fills truth[i] = oracle(shapes[s.shape], s.ray) for every sample, in parallel.
template <class Shape, class Oracle>
void compute_truth(Workload<Shape>& w, Oracle oracle) {
    w.truth.assign(w.samples.size(), Truth{});
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, w.samples.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                              const Sample& s = w.samples[i];
                              w.truth[i] = oracle(w.shapes[s.shape], s.ray);
                          }
                      });
}

/// "float" or "double".
template <class T>
std::string precision_name() {
    return std::is_same_v<T, float> ? "float" : "double";
}

/// The names `prefix + M::name` of the methods that for_each(std::type_identity<float>{}, visitor)
/// visits, in its order.
template <class ForEach>
std::vector<std::string> method_names(const ForEach& for_each, std::string_view prefix = "") {
    std::vector<std::string> names;
    const auto add = [&]<class M>() {
        names.push_back(std::string(prefix) + std::string(M::name));
    };
    for_each(std::type_identity<float>{}, add);
    return names;
}

/// For each wanted name in order, float (if opt.f32) then double (if opt.f64): calls
/// run.template operator()<M>() for the method M with `prefix + M::name` equal to that name.
/// for_each(std::type_identity<T>{}, visitor) calls visitor.template operator()<M>() for every
/// method M of precision T.
template <class ForEach, class Run>
void run_wanted(const std::vector<std::string>& wanted,
                const Options& opt,
                const ForEach& for_each,
                const Run& run,
                std::string_view prefix = "") {
    for (const std::string& name : wanted) {
        const auto one = [&]<class M>() {
            if (std::string(prefix) + std::string(M::name) == name) {
                run.template operator()<M>();
            }
        };
        if (opt.f32) {
            for_each(std::type_identity<float>{}, one);
        }
        if (opt.f64) {
            for_each(std::type_identity<double>{}, one);
        }
    }
}

/// Wall time in ns per item of f(), which handles `items` items: repeated until 20 ms have passed
/// (at most 1000 times) so short passes still give a stable figure.
template <class F>
double ns_per_item(const F& f, std::size_t items) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    std::size_t passes = 0;
    do {
        f();
        ++passes;
    } while (Clock::now() - start < std::chrono::milliseconds(20) && passes < 1000);
    return std::chrono::duration<double, std::nano>(Clock::now() - start).count() /
           static_cast<double>(std::max<std::size_t>(1, passes * items));
}

/// The timing of a method's per-ray set-up over some rays.
struct SetupTiming {
    bool has_setup = false;  ///< the method has a precompute step
    double ns_per_ray = 0;   ///< its single-thread time per ray (0 without set-up)
    std::size_t rays = 0;    ///< rays set up
};

/// precompute_ray<M>(rays[i]) for every i, and (for methods with set-up) its time per ray.
template <class M>
std::vector<RayDataOf<M>> precompute_all(const std::vector<Ray<typename M::Scalar>>& rays,
                                         SetupTiming& timing) {
    std::vector<RayDataOf<M>> data;
    data.reserve(rays.size());
    const auto pass = [&] {
        data.clear();  // keeps the capacity: no allocation inside the timed pass
        for (const Ray<typename M::Scalar>& r : rays) {
            data.push_back(precompute_ray<M>(r));
        }
    };
    timing = {HasRayData<M>, 0.0, rays.size()};
    if constexpr (HasRayData<M>) {
        timing.ns_per_ray = ns_per_item(pass, rays.size());
    } else {
        pass();
    }
    return data;
}

/// Collects one method's per-set accumulators and timings, then emits the "all" row followed
/// (with by_set) by one row per set, in the order the sets were added.
class MethodRows {
public:
    /// t_tol and has_t as for Accumulator (has_t false for hit/no-hit methods).
    MethodRows(std::string prim,
               std::string method,
               std::string precision,
               double t_tol,
               bool by_set,
               bool has_t = true)
        : prim_(std::move(prim))
        , method_(std::move(method))
        , precision_(std::move(precision))
        , by_set_(by_set)
        , all_(t_tol, has_t) {}

    /// One set: its accumulator, the wall time of its test pass and the tests that pass made,
    /// and the set-up timing of its rays.
    void add_set(const Accumulator& acc,
                 const std::string& set,
                 double ns,
                 std::size_t tests,
                 const SetupTiming& setup) {
        all_.merge(acc);
        all_ns_ += ns;
        all_tests_ += tests;
        all_setup_ns_ += setup.ns_per_ray * static_cast<double>(setup.rays);
        all_setup_rays_ += setup.rays;
        has_setup_ = setup.has_setup;
        if (by_set_) {
            set_rows_.push_back(with_setup(acc.row(prim_, method_, precision_, set, per(ns, tests)),
                                           setup.ns_per_ray));
        }
    }

    /// Appends the "all" row and the per-set rows to rows.
    void emit(std::vector<Row>& rows) const {
        rows.push_back(
            with_setup(all_.row(prim_, method_, precision_, "all", per(all_ns_, all_tests_)),
                       per(all_setup_ns_, all_setup_rays_)));
        rows.insert(rows.end(), set_rows_.begin(), set_rows_.end());
    }

private:
    static double per(double ns, std::size_t n) { return n ? ns / static_cast<double>(n) : 0.0; }
    Row with_setup(Row r, double setup_ns_per_ray) const {
        r.has_setup = has_setup_;
        r.setup_ns_per_ray = setup_ns_per_ray;
        return r;
    }

    std::string prim_, method_, precision_;
    bool by_set_;
    Accumulator all_;
    double all_ns_ = 0, all_setup_ns_ = 0;
    std::size_t all_tests_ = 0, all_setup_rays_ = 0;
    bool has_setup_ = false;
    std::vector<Row> set_rows_;
};

/// Wall time in ns of one single-threaded pass of intersect_with<M>(prepared[i], rays[i],
/// data[i]) over all i (set-up excluded); the t of the hits goes to a volatile sink so the pass
/// is not optimised away.
template <class M>
double time_pass(const std::vector<typename M::Prepared>& prepared,
                 const std::vector<Ray<typename M::Scalar>>& rays,
                 const std::vector<RayDataOf<M>>& data) {
    const auto start = std::chrono::steady_clock::now();
    double sink = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (const auto hit = intersect_with<M>(prepared[i], rays[i], data[i])) {
            sink += static_cast<double>(hit->t);
        }
    }
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    volatile double keep = sink;
    static_cast<void>(keep);
    return ns;
}

/// Runs method M over sets of one-shape-one-ray cases (each Set has `name`, `cases` with a float
/// `ray`, and `oracle` with `hit` and `t`): per set an accuracy pass, then a timed pass, and one
/// row per set plus the "all" row. convert(case, std::type_identity<T>{}) gives the shape in T.
template <class M, class Set, class Convert>
void run_case_sets(std::string_view prim,
                   const std::string& method,
                   const std::vector<Set>& sets,
                   const Convert& convert,
                   bool by_set,
                   std::vector<Row>& rows) {
    using T = typename M::Scalar;
    MethodRows out(std::string(prim), method, precision_name<T>(), t_tolerance<T>(), by_set);
    for (const Set& set : sets) {
        std::vector<typename M::Prepared> prepared;
        std::vector<Ray<T>> rays;
        prepared.reserve(set.cases.size());
        rays.reserve(set.cases.size());
        for (const auto& c : set.cases) {
            prepared.push_back(M::prepare(convert(c, std::type_identity<T>{})));
            rays.push_back(static_cast<Ray<T>>(c.ray));
        }
        SetupTiming setup;
        const std::vector<RayDataOf<M>> data = precompute_all<M>(rays, setup);
        Accumulator acc(t_tolerance<T>());
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const auto hit = intersect_with<M>(prepared[i], rays[i], data[i]);
            acc.add(hit.has_value(), set.oracle[i].hit, hit ? static_cast<double>(hit->t) : 0.0,
                    set.oracle[i].t);
        }
        out.add_set(acc, set.name, time_pass<M>(prepared, rays, data), rays.size(), setup);
    }
    out.emit(rows);
}

/// Runs method M on every sample of a workload: set-up and tests timed separately,
/// single-threaded (each repeated for at least 20 ms), then compared with the truth; rows "all"
/// and (with opt.by_set) one per set name.
/// convert(shape, std::type_identity<T>{}) gives the shape in T.
template <class M, class Shape, std::size_t NSets, class Convert>
void run_workload_method(std::string_view prim,
                         const std::array<const char*, NSets>& set_names,
                         const Workload<Shape>& w,
                         const Convert& convert,
                         const Options& opt,
                         std::vector<Row>& rows) {
    using T = typename M::Scalar;
    std::vector<typename M::Prepared> prepared;
    prepared.reserve(w.shapes.size());
    for (const Shape& s : w.shapes) {
        prepared.push_back(M::prepare(convert(s, std::type_identity<T>{})));
    }
    std::vector<Ray<T>> rays;
    rays.reserve(w.samples.size());
    for (const Sample& s : w.samples) {
        rays.push_back(static_cast<Ray<T>>(s.ray));
    }
    SetupTiming setup;
    const std::vector<RayDataOf<M>> data = precompute_all<M>(rays, setup);
    std::vector<std::optional<PrimHit<T>>> res(rays.size());
    const double ns = ns_per_item(
        [&] {
            for (std::size_t i = 0; i < rays.size(); ++i) {
                res[i] = intersect_with<M>(prepared[w.samples[i].shape], rays[i], data[i]);
            }
        },
        rays.size());

    std::vector<Accumulator> per_set(NSets, Accumulator(t_tolerance<T>()));
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Truth& tr = w.truth[i];
        per_set[w.samples[i].set].add(res[i].has_value(), tr.hit,
                                      res[i] ? static_cast<double>(res[i]->t) : 0.0, tr.t);
    }
    Accumulator all(t_tolerance<T>());
    for (const Accumulator& a : per_set) {
        all.merge(a);
    }
    const std::string method(M::name);
    const std::string precision = precision_name<T>();
    const auto finish = [&](Row r) {
        r.has_setup = setup.has_setup;
        r.setup_ns_per_ray = setup.ns_per_ray;
        rows.push_back(std::move(r));
    };
    finish(all.row(std::string(prim), method, precision, "all", ns));
    if (opt.by_set) {
        for (std::size_t s = 0; s < NSets; ++s) {
            finish(per_set[s].row(std::string(prim), method, precision, set_names[s], ns));
        }
    }
}

/// Runs the selected methods of a kind (known = all its names) over a workload, float then
/// double per method; throws std::invalid_argument on an unknown name (see select_methods).
template <class Shape, std::size_t NSets, class ForEach, class Convert>
std::vector<Row> run_workload(std::string_view prim,
                              const std::array<const char*, NSets>& set_names,
                              const ForEach& for_each,
                              const Workload<Shape>& w,
                              const Convert& convert,
                              const Options& opt) {
    std::vector<Row> rows;
    run_wanted(select_methods(method_names(for_each), opt.methods, prim), opt, for_each,
               [&]<class M>() { run_workload_method<M>(prim, set_names, w, convert, opt, rows); });
    return rows;
}

}  // namespace rtlab::xcheck
