// rtlab_bench: one Google Benchmark executable for every suite in bench/.
#include "bench/benchmarks.h"

#include <benchmark/benchmark.h>

int main(int argc, char** argv) {
    rtlab::bench::register_intersect_benchmarks();
    rtlab::bench::register_trace_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
