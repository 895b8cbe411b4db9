// Renderer benchmarks render/flake_mirror/{auto,all_features}: the mirror-only SPD sphere flake
// (size 3, reflect-only spheres on a plain floor, three lights) rendered with the integrator
// instance the scene's features select (shadows + reflection) and with every feature compiled in
// (refraction, Fresnel, absorption, dispersion and textures present but never used). The point:
// leaving out what the scene does not need costs nothing and may save time. Counter: rays/s.
#include "bench/benchmarks.h"
#include "datasets_gen/generators.h"
#include "render/renderer.h"

#include <benchmark/benchmark.h>

#include <memory>

namespace {

using namespace rtlab;

struct FlakeFixture {
    Scene scene;
    std::unique_ptr<SceneTracer> tracer;
};

const FlakeFixture& flake_fixture() {
    static const FlakeFixture fx = [] {
        gen::GenOptions o;
        o.size = 3;
        FlakeFixture f;
        f.scene = gen::generate("flake", o);
        f.tracer = std::make_unique<SceneTracer>(f.scene, TraceSetup{});
        return f;
    }();
    return fx;
}

void bm_render(benchmark::State& state, bool all_features) {
    const FlakeFixture& fx = flake_fixture();
    RenderSettings r;
    r.width = bench::quick_mode() ? 64 : 128;
    r.height = r.width;
    r.all_features = all_features;
    RenderStats last;
    for (auto _ : state) {
        const RenderResult res = render(fx.scene, *fx.tracer, r);
        last = res.stats;
        benchmark::DoNotOptimize(res.image.pixels.data());
    }
    state.counters["rays/s"] = benchmark::Counter(static_cast<double>(last.total()),
                                                  benchmark::Counter::kIsIterationInvariantRate);
    state.counters["rays"] = static_cast<double>(last.total());
    state.SetLabel(plan_render(fx.scene, r).instantiation);
}

}  // namespace

void rtlab::bench::register_render_benchmarks() {
    benchmark::RegisterBenchmark("render/flake_mirror/auto", bm_render, false)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark("render/flake_mirror/all_features", bm_render, true)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}
