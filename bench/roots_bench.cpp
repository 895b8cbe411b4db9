// Root finders on the ray quartics of the implicit surfaces (torus, tangle cube): closed form
// (Ferrari/Cardano), Newton capped at k iterations per bracket refinement, Laguerre with
// deflation, plain bisection (intersect/implicit/bisection.h). All run in the same frame (clip
// to the box, polynomial over the window, first root in [0, 1]; implicit.h) on the cross-check's
// rays (random, grazing, far together). Reference t: the exact Sturm isolation over Q refined by
// 256-bit MPFR bisection (crosscheck/implicit_check.cpp), computed once, outside the timing.
#include "bench/bench_cases.h"
#include "bench/benchmarks.h"
#include "crosscheck/accumulator.h"
#include "crosscheck/ray_sets.h"
#include "intersect/implicit/bisection.h"
#include "intersect/implicit/methods.h"

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace {

using namespace rtlab;

/// The cached cases of surface kind S.
template <template <class> class S>
const xcheck::BenchCases<S<float>>& surface_cases() {
    if constexpr (std::is_same_v<S<float>, Torus<float>>) {
        return bench::cached_cases<Torus<float>, xcheck::torus_bench_cases>();
    } else {
        return bench::cached_cases<TangleCube<float>, xcheck::tangle_bench_cases>();
    }
}

/// Error counters of one finder over all rays.
struct RootStats {
    double rays = 0, missed_root_rate = 0, false_hit_rate = 0, max_rel = 0, median_rel = 0;
};

template <template <class> class S, class T, class Finder>
void bm_roots(benchmark::State& state, Finder finder) {
    const xcheck::BenchCases<S<float>>& cases = surface_cases<S>();
    using Method = ImplicitClosedForm<S, T>;  // only for prepare: the finders share the frame
    std::vector<typename Method::Prepared> prepared;
    std::vector<Ray<T>> rays;
    for (const xcheck::Sample& s : cases.samples) {
        prepared.push_back(Method::prepare(bench::to_scalar<T>(cases.shapes[s.shape])));
        rays.push_back(static_cast<Ray<T>>(s.ray));
    }
    const auto solve = [&](std::size_t i) {
        return implicit_intersect(prepared[i], rays[i], finder);
    };

    xcheck::Accumulator acc(xcheck::t_tolerance<T>());
    std::size_t oracle_hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const auto h = solve(i);
        acc.add(h.has_value(), cases.truth[i].hit, h ? static_cast<double>(h->t) : 0.0,
                cases.truth[i].t);
        oracle_hits += cases.truth[i].hit ? 1 : 0;
    }
    const xcheck::Row row = acc.row("", "", "", "", 0.0);

    for (auto _ : state) {
        double sink = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (const auto h = solve(i)) {
                sink += static_cast<double>(h->t);
            }
        }
        benchmark::DoNotOptimize(sink);
    }
    using benchmark::Counter;
    const double n = static_cast<double>(rays.size());
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(rays.size()));
    // n * 1e-9 rays per iteration and second, inverted: ns per ray.
    state.counters["ns/ray"] =
        Counter(n * 1e-9, Counter::kIsIterationInvariantRate | Counter::kInvert);
    state.counters["rays"] = n;
    state.counters["missed_root_rate"] = static_cast<double>(row.false_miss) /
                                         static_cast<double>(std::max<std::size_t>(1, oracle_hits));
    state.counters["false_hit_rate"] = static_cast<double>(row.false_hit) / n;
    state.counters["wrong_t_rate"] = static_cast<double>(row.wrong_t) / n;
    state.counters["max_rel_t_err"] = row.max_rel_t_err;
    state.counters["median_rel_t_err"] = row.median_rel_t_err;
}

template <template <class> class S, class T>
void register_surface() {
    const std::string prefix = "roots/" + std::string(S<T>::name) + "/";
    const std::string precision = std::is_same_v<T, float> ? "float" : "double";
    const auto add = [&](std::string_view finder_name, auto finder) {
        const std::string name = prefix + std::string(finder_name) + "/" + precision;
        auto* b =
            benchmark::RegisterBenchmark(name.c_str(), bm_roots<S, T, decltype(finder)>, finder);
        b->Unit(benchmark::kMicrosecond);
        if (bench::quick_mode()) {
            b->MinTime(0.01);
        }
    };
    add("closed_form", [](const Polynomial<T, 4>& p) -> std::optional<T> {
        const RealRoots<T, 4> r = solve_closed_form_unit(p);
        T u;
        return r.first_in(T(0), T(1), u) ? std::optional<T>(u) : std::nullopt;
    });
    const auto newton = [](auto k) {
        return [](const Polynomial<T, 4>& p) {
            return ImplicitNewton<S, T>::first_root(p, decltype(k)::value);
        };
    };
    add("newton_k4", newton(std::integral_constant<int, 4>{}));
    add("newton_k8", newton(std::integral_constant<int, 8>{}));
    add("newton_k16", newton(std::integral_constant<int, 16>{}));
    add("newton_k32", newton(std::integral_constant<int, 32>{}));
    add("laguerre", [](const Polynomial<T, 4>& p) -> std::optional<T> {
        const auto r = laguerre_real_roots(p);
        T u;
        return r.first_in(T(0), T(1), u) ? std::optional<T>(u) : std::nullopt;
    });
    add("bisection", [](const Polynomial<T, 4>& p) { return bisection_first_root(p); });
}

}  // namespace

void rtlab::bench::register_roots_benchmarks() {
    register_surface<Torus, float>();
    register_surface<Torus, double>();
    register_surface<TangleCube, float>();
    register_surface<TangleCube, double>();
}
