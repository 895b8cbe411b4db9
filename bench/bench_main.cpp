// rtlab_bench: one Google Benchmark executable for every suite in bench/.
// Our own flag, --quick, is removed before Google Benchmark parses the rest.
#include "bench/benchmarks.h"

#include <benchmark/benchmark.h>

#include <string_view>

namespace {
bool quick = false;
}  // namespace

bool rtlab::bench::quick_mode() {
    return quick;
}

int main(int argc, char** argv) {
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::string_view(argv[i]) == "--quick") {
            quick = true;
        } else {
            argv[kept++] = argv[i];
        }
    }
    argc = kept;
    rtlab::bench::register_intersect_benchmarks();
    rtlab::bench::register_roots_benchmarks();
    rtlab::bench::register_trace_benchmarks();
    rtlab::bench::register_render_benchmarks();
    rtlab::bench::register_embree_benchmarks();
    rtlab::bench::register_build_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
