// Every intersection method of intersect/ per primitive kind, precision and ray distribution
// (random, edge-aimed, grazing, far): time per ray-primitive test, and error rates against the
// exact answers of the cross-check's oracles (CGAL, GMP, MPFR; crosscheck/ray_sets.h). The exact
// answers and each method's error counters are computed once, outside the timed loop.
#include "bench/bench_cases.h"
#include "bench/benchmarks.h"
#include "crosscheck/accumulator.h"
#include "crosscheck/ray_sets.h"
#include "intersect/box/methods.h"
#include "intersect/cone/methods.h"
#include "intersect/implicit/methods.h"
#include "intersect/polygon/methods.h"
#include "intersect/sphere/methods.h"
#include "intersect/triangle/methods.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace {

using namespace rtlab;
using xcheck::BenchCases;
using xcheck::Truth;

/// One method's inputs for one distribution, converted to its precision.
template <class M>
struct MethodInput {
    using T = typename M::Scalar;
    std::vector<typename M::Prepared> prepared;  ///< one per shape
    std::vector<Ray<T>> rays;                    ///< the distribution's rays
    std::vector<std::uint32_t> shape;            ///< shape of each ray (unused when all)
    std::vector<Truth> truth;                    ///< exact answer of each ray
    bool all = false;                            ///< each ray tests every shape (closest hit)
};

template <class M, class Shape>
MethodInput<M> make_input(const BenchCases<Shape>& cases, std::uint8_t set) {
    using T = typename M::Scalar;
    MethodInput<M> in;
    in.all = cases.closest_of_all;
    in.prepared.reserve(cases.shapes.size());
    for (const Shape& s : cases.shapes) {
        in.prepared.push_back(M::prepare(bench::to_scalar<T>(s)));
    }
    for (std::size_t i = 0; i < cases.samples.size(); ++i) {
        if (cases.samples[i].set == set) {
            in.rays.push_back(static_cast<Ray<T>>(cases.samples[i].ray));
            in.shape.push_back(cases.samples[i].shape);
            in.truth.push_back(cases.truth[i]);
        }
    }
    return in;
}

/// M's answer for ray i (closest hit over all shapes when in.all; any hit for methods without
/// t); tests counts the ray-primitive tests made. The ray's set-up (precompute) runs once per
/// ray: with one shape per ray it is part of the test, over all shapes it is shared by them.
template <class M>
inline Truth answer(const MethodInput<M>& in, std::size_t i, std::size_t& tests) {
    using T = typename M::Scalar;
    constexpr bool has_t = IntersectionMethod<M>;
    const RayDataOf<M> data = precompute_ray<M>(in.rays[i]);
    if (!in.all) {
        ++tests;
        if constexpr (has_t) {
            const auto h = intersect_with<M>(in.prepared[in.shape[i]], in.rays[i], data);
            return h ? Truth{true, static_cast<double>(h->t)} : Truth{};
        } else {
            return {occluded_with<M>(in.prepared[in.shape[i]], in.rays[i], data), 0.0};
        }
    }
    Ray<T> ray = in.rays[i];  // closest hit shrinks tmax; the set-up data stays valid
    Truth a;
    for (const auto& p : in.prepared) {
        ++tests;
        if constexpr (has_t) {
            if (const auto h = intersect_with<M>(p, ray, data)) {
                a = {true, static_cast<double>(h->t)};
                ray.tmax = h->t;
            }
        } else if (occluded_with<M>(p, ray, data)) {
            a.hit = true;
            break;
        }
    }
    return a;
}

/// The error side of one benchmark, computed on its first run.
struct ErrorStats {
    double rays = 0, false_hit_rate = 0, false_miss_rate = 0, wrong_t_rate = 0, max_rel = 0;
    double median_rel = 0, tests_per_ray = 0;
};

template <class M>
ErrorStats error_stats(const MethodInput<M>& in) {
    xcheck::Accumulator acc(xcheck::t_tolerance<typename M::Scalar>(), IntersectionMethod<M>);
    std::size_t tests = 0;
    for (std::size_t i = 0; i < in.rays.size(); ++i) {
        const Truth a = answer(in, i, tests);
        acc.add(a.hit, in.truth[i].hit, a.t, in.truth[i].t);
    }
    const xcheck::Row row = acc.row("", "", "", "", 0.0);
    const double n = static_cast<double>(std::max<std::size_t>(1, row.rays));
    return {static_cast<double>(row.rays),
            static_cast<double>(row.false_hit) / n,
            static_cast<double>(row.false_miss) / n,
            static_cast<double>(row.wrong_t) / n,
            row.max_rel_t_err,
            row.median_rel_t_err,
            static_cast<double>(tests) / n};
}

/// Memo of error stats by benchmark name (Google Benchmark calls a benchmark several times).
ErrorStats memo_stats(const std::string& key, const auto& compute) {
    static std::mutex mutex;
    static std::map<std::string, ErrorStats> memo;
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = memo.find(key);
    if (it != memo.end()) {
        return it->second;
    }
    return memo[key] = compute();
}

template <class M, class Shape, BenchCases<Shape> (*Make)(std::size_t, std::uint64_t)>
void bm_method(benchmark::State& state, const std::string& key, std::uint8_t set) {
    const MethodInput<M> in = make_input<M>(bench::cached_cases<Shape, Make>(), set);
    const ErrorStats err = memo_stats(key, [&] { return error_stats(in); });
    std::size_t tests = 0;
    for (auto _ : state) {
        double sink = 0;
        for (std::size_t i = 0; i < in.rays.size(); ++i) {
            sink += answer(in, i, tests).t;
        }
        benchmark::DoNotOptimize(sink);
    }
    using benchmark::Counter;
    state.SetItemsProcessed(static_cast<std::int64_t>(tests));
    // tests * 1e-9 per second, inverted: ns per test.
    state.counters["ns/test"] =
        Counter(static_cast<double>(tests) * 1e-9, Counter::kIsRate | Counter::kInvert);
    state.counters["rays"] = err.rays;
    state.counters["tests/ray"] = err.tests_per_ray;
    state.counters["false_hit_rate"] = err.false_hit_rate;
    state.counters["false_miss_rate"] = err.false_miss_rate;
    if constexpr (IntersectionMethod<M>) {  // no t for hit/no-hit methods (Segura-Feito)
        state.counters["wrong_t_rate"] = err.wrong_t_rate;
        state.counters["max_rel_t_err"] = err.max_rel;
        state.counters["median_rel_t_err"] = err.median_rel;
    }
}

/// Registers intersect/<prim>/<method>/<precision>/<set> for every method for_each visits
/// (for_each(std::type_identity<T>{}, visitor)), in float and double, for the given sets.
template <class Shape, BenchCases<Shape> (*Make)(std::size_t, std::uint64_t), class ForEach>
void register_kind(std::string_view prim, const ForEach& for_each, bool has_edge) {
    const auto add = [&]<class T>(std::type_identity<T> tag) {
        for_each(tag, [&]<class M>() {
            for (std::uint8_t set = 0; set < xcheck::bench_set_names.size(); ++set) {
                if (set == xcheck::bench_edge && !has_edge) {
                    continue;
                }
                const std::string name = "intersect/" + std::string(prim) + "/" +
                                         std::string(M::name) + "/" +
                                         (std::is_same_v<T, float> ? "float" : "double") + "/" +
                                         std::string(xcheck::bench_set_names[set]);
                auto* b = benchmark::RegisterBenchmark(name.c_str(), bm_method<M, Shape, Make>,
                                                       name, set);
                b->Unit(benchmark::kMicrosecond);
                if (bench::quick_mode()) {
                    b->MinTime(0.01);
                }
            }
        });
    };
    add(std::type_identity<float>{});
    add(std::type_identity<double>{});
}

}  // namespace

void rtlab::bench::register_intersect_benchmarks() {
    register_kind<Triangle<float>, xcheck::triangle_bench_cases>(
        "triangle", xcheck::for_each_checked_triangle, true);
    register_kind<Polygon<float>, xcheck::polygon_bench_cases>(
        "polygon",
        [](auto tag, const auto& f) { for_each_polygon_method<typename decltype(tag)::type>(f); },
        true);
    register_kind<Bounds3f, xcheck::aabb_bench_cases>(
        "aabb",
        [](auto tag, const auto& f) { for_each_aabb_method<typename decltype(tag)::type>(f); },
        true);
    register_kind<Obb<float>, xcheck::obb_bench_cases>(
        "obb",
        [](auto tag, const auto& f) { for_each_obb_method<typename decltype(tag)::type>(f); },
        true);
    register_kind<Sphere<float>, xcheck::sphere_bench_cases>(
        "sphere",
        [](auto tag, const auto& f) { for_each_sphere_method<typename decltype(tag)::type>(f); },
        false);
    register_kind<Torus<float>, xcheck::torus_bench_cases>(
        "torus",
        [](auto tag, const auto& f) {
            for_each_implicit_method<Torus, typename decltype(tag)::type>(f);
        },
        false);
    register_kind<TangleCube<float>, xcheck::tangle_bench_cases>(
        "tangle",
        [](auto tag, const auto& f) {
            for_each_implicit_method<TangleCube, typename decltype(tag)::type>(f);
        },
        false);
    register_kind<Cone<float>, xcheck::cone_bench_cases>(
        "cone",
        [](auto tag, const auto& f) { for_each_cone_method<typename decltype(tag)::type>(f); },
        true);
}
