// rtlab_bench: one Google Benchmark executable for every suite in bench/.
// Our own flags, --quick and --accel SPEC, are removed before Google Benchmark parses the rest.
#include "accel/any_accel.h"
#include "base/atomic_file.h"
#include "bench/benchmarks.h"

#include <benchmark/benchmark.h>

#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace {
bool quick = false;
std::string suite = "all";
std::vector<std::string> specs;  // canonical specs named by --accel, in order

constexpr std::string_view own_flags =
    "rtlab_bench flags (before Google Benchmark's own, listed below):\n"
    "  --quick        smaller sizes and fewer cases (the whole run in about a minute)\n"
    "  --accel SPEC   trace and build benchmarks for this structure spec only, e.g.\n"
    "                 --accel 'bvh:binned,max_leaf=8' (repeatable; default: every registry row\n"
    "                 but brute, with default parameters; see rtlab list)\n"
    "  --suite NAME   all (default: every suite below but targets) or targets (the BVH layouts'\n"
    "                 target table against Embree: SF 4 tessellated flake with floor, SF 4 and\n"
    "                 SF 5 analytic, 1 and 2 threads, Embree medium and high; bench/report.py\n"
    "                 --suite targets writes it into docs/results.md; with --quick sizes 2 and\n"
    "                 3), grid2 (the two-level grid and the cost model: every row on the flake\n"
    "                 with its floor, the stadium and analytic spheres, one thread, with\n"
    "                 cost_model, measured_cost and epo; builds at 1 and 2 threads;\n"
    "                 bench/report.py --suite grid2 writes it into docs/results.md) or kdtree\n"
    "                 (the kd-tree's targets: kdtree:sah against the binary BVHs, interleaved\n"
    "                 in one process, one thread; bench/report_kdtree.py makes the table)\n\n";
}  // namespace

bool rtlab::bench::quick_mode() {
    return quick;
}

bool rtlab::bench::specs_named() {
    return !specs.empty();
}

std::vector<std::string> rtlab::bench::bench_specs() {
    if (!specs.empty()) {
        return specs;
    }
    std::vector<std::string> out;
    for (const AccelEntry& e : accel_registry()) {
        if (e.name != "brute") {  // O(N) per ray: the reference for correctness, not a contender
            out.push_back(default_spec(e).canonical());
        }
    }
    return out;
}

int main(int argc, char** argv) {
    int kept = 1;
    std::string out_file;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string_view arg(argv[i]);
            if (arg == "--quick") {
                quick = true;
            } else if (arg == "--suite" && i + 1 < argc) {
                suite = argv[++i];
                if (suite != "all" && suite != "targets" && suite != "grid2" && suite != "kdtree") {
                    throw std::invalid_argument(
                        "--suite must be all, targets, grid2 or kdtree, not '" + suite + "'");
                }
            } else if (arg == "--accel" && i + 1 < argc) {
                specs.push_back(rtlab::parse_accel_spec(argv[++i]).canonical());
            } else if (arg.starts_with("--accel=")) {
                specs.push_back(rtlab::parse_accel_spec(arg.substr(8)).canonical());
            } else {
                if (arg == "--help") {
                    std::cout << own_flags;
                }
                if (arg.starts_with("--benchmark_out=")) {
                    // The same rule as rtlab's outputs (base/atomic_file.h): a new file, rtlab's
                    // own earlier output or a device; never through a link or over another file.
                    out_file = std::string(arg.substr(16));
                    rtlab::check_output_path(out_file);
                }
                argv[kept++] = argv[i];
            }
        }
    } catch (const std::exception& e) {
        std::cerr << "rtlab_bench: " << e.what() << "\n";
        return 2;
    }
    argc = kept;
    if (suite == "targets") {
        rtlab::bench::register_targets_benchmarks();
    } else if (suite == "grid2") {
        rtlab::bench::register_grid2_benchmarks();
    } else if (suite == "kdtree") {
        rtlab::bench::register_kdtree_benchmarks();
    } else {
        rtlab::bench::register_intersect_benchmarks();
        rtlab::bench::register_roots_benchmarks();
        rtlab::bench::register_trace_benchmarks();
        rtlab::bench::register_render_benchmarks();
        rtlab::bench::register_embree_benchmarks();
        rtlab::bench::register_build_benchmarks();
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    const std::size_t ran = benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    if (!out_file.empty() && std::filesystem::is_regular_file(out_file)) {
        rtlab::mark_output(out_file);  // Google Benchmark wrote it: marked as rtlab's own
    }
    if (ran == 0) {  // a filter that matches nothing is a mistake, not a successful run
        std::cerr << "rtlab_bench: no benchmark matches the filter (list them with "
                     "--benchmark_list_tests)\n";
        return 1;
    }
    return 0;
}
