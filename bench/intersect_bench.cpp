// Ray-triangle tests per method and precision: time per test over a fixed set of random triangles
// and rays (the error side of these methods is `rtlab crosscheck --prim triangle`).
#include "bench/benchmarks.h"
#include "intersect/triangle/methods.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace rtlab;

template <class T>
struct TriangleFixture {
    std::vector<Triangle<T>> tris;
    std::vector<Ray<T>> rays;
};

template <class T>
const TriangleFixture<T>& triangle_fixture() {
    static const TriangleFixture<T> fx = [] {
        TriangleFixture<T> f;
        std::mt19937_64 rng(7);
        const auto u = [&] { return static_cast<T>(static_cast<double>(rng() >> 11) * 0x1.0p-53); };
        for (int i = 0; i < 256; ++i) {
            const Vec3<T> c{u(), u(), u()};
            const auto corner = [&] { return c + Vec3<T>{u(), u(), u()} * T(0.2); };
            f.tris.push_back({corner(), corner(), corner()});
        }
        for (int i = 0; i < 256; ++i) {
            const Vec3<T> o{u() * T(2) - T(0.5), u() * T(2) - T(0.5), T(-1)};
            const Vec3<T> target{u(), u(), u()};
            f.rays.push_back({o, target - o});
        }
        return f;
    }();
    return fx;
}

template <class M>
void bm_triangle(benchmark::State& state) {
    using T = typename M::Scalar;
    const TriangleFixture<T>& fx = triangle_fixture<T>();
    std::vector<typename M::Prepared> prepared;
    for (const Triangle<T>& t : fx.tris) {
        prepared.push_back(M::prepare(t));
    }
    std::uint64_t hits = 0;
    for (auto _ : state) {
        for (const Ray<T>& r : fx.rays) {
            for (const auto& p : prepared) {
                hits += M::occluded(p, r) ? 1u : 0u;
            }
        }
    }
    benchmark::DoNotOptimize(hits);
    const double tests = static_cast<double>(fx.rays.size() * prepared.size());
    // Tests per second, inverted: seconds per test (printed with an SI prefix, e.g. 19.6n).
    state.counters["time/test"] = benchmark::Counter(
        tests, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

void rtlab::bench::register_intersect_benchmarks() {
    const auto add = [](auto tag, const char* precision) {
        using T = decltype(tag);
        for_each_triangle_method<T>([&]<class M>() {
            const std::string name = "intersect/triangle/" + std::string(M::name) + "/" + precision;
            benchmark::RegisterBenchmark(name.c_str(), bm_triangle<M>);
        });
    };
    add(float{}, "float");
    add(double{}, "double");
}
