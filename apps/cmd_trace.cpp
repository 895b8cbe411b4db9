// rtlab trace: builds one structure per primitive set of a scene, traces a ray file, and prints
// exactly one JSON object (build and trace time, hits, throughput, optional counts) on stdout.
#include "accel/spec.h"
#include "apps/commands.h"
#include "apps/method_check.h"
#include "base/atomic_file.h"
#include "base/split.h"
#include "scene/scene_io.h"
#include "trace/binary_io.h"
#include "trace/measure.h"
#include "trace/measure_json.h"
#include "trace/scene_tracer.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <tbb/global_control.h>
#include <tbb/info.h>

namespace rtlab::app {

namespace {

struct TraceArgs {
    std::string scene;
    std::string rays;
    std::string accel{default_accel};
    std::string method;
    bool any_hit = false;
    std::string hits;
    int threads = 0;
    int repeat = 5;
    bool warmup = true;
    bool stats = false;
    bool robust = false;
    bool exact = false;
    bool leaf_time = false;
};

int run_trace(const TraceArgs& a) {
    std::optional<tbb::global_control> threads;
    if (a.threads > 0) {
        threads.emplace(tbb::global_control::max_allowed_parallelism,
                        static_cast<std::size_t>(a.threads));
    }
    const AccelSpec accel = parse_accel_spec(a.accel);  // bad specs fail first
    if (!a.hits.empty()) {
        check_output_path(a.hits);
    }
    const Scene scene = load_scene(a.scene);
    const std::vector<Rayf> rays = load_rays(a.rays);
    TraceSetup setup = checked_setup(accel, a.method, a.robust);
    setup.exact = a.exact;
    const SceneTracer tracer(scene, setup);
    check_methods_used(tracer, setup.methods, "trace");

    MeasureOptions opt;
    opt.any_hit = a.any_hit;
    opt.repeat = a.repeat;
    opt.warmup = a.warmup ? 1 : 0;
    opt.stats = a.stats;
    opt.epo = a.stats;
    opt.leaf_time = a.leaf_time;
    std::vector<Hit> hits;
    const TraceMeasurement m = measure_trace(tracer, rays, opt, &hits);

    nlohmann::json j;
    j["scene"] = a.scene;
    j["accel"] = accel.canonical();
    std::string methods;
    for (const std::string& name : tracer.set_methods()) {
        methods += (methods.empty() ? "" : ",") + name.substr(name.find('=') + 1);
    }
    j["method"] = methods;
    j["sets"] = tracer.set_methods();
    j["query"] = a.any_hit ? "any_hit" : "closest_hit";
    j["robust"] = a.robust || a.exact;
    j["exact"] = a.exact;
    j["threads"] = a.threads > 0 ? a.threads : tbb::info::default_concurrency();
    j["repeat"] = a.repeat;
    j["warmup"] = a.warmup;
    write_measurement(j, m);
    if (a.exact && a.stats) {
        const ExactCounts c = tracer.exact_counts(rays, a.any_hit);
        j["exact_tests"] = c.tests;
        j["exact_fallbacks"] = c.fallbacks;
        j["fallback_rays"] = c.fallback_rays;
        j["fallback_rays_per_million"] =
            c.rays > 0 ? 1e6 * static_cast<double>(c.fallback_rays) / static_cast<double>(c.rays)
                       : 0.0;
    }
    if (!a.hits.empty()) {
        save_hits(a.hits, hits);
    }
    std::cout << j.dump() << "\n";
    return 0;
}

}  // namespace

Command add_trace(CLI::App& root) {
    auto a = std::make_shared<TraceArgs>();
    CLI::App* sub = root.add_subcommand(
        "trace",
        "Trace a ray file through a scene with one structure per primitive set; prints one JSON "
        "object (accel method rays hits build_ms trace_ms mrays_per_s accel_bytes nodes leaves "
        "max_depth sah_cost [traverse_ms leaf_share] [nodes_per_ray prims_per_ray cost_model "
        "measured_cost [epo]])");
    sub->add_option("scene,--scene", a->scene,
                    "Scene JSON or mesh file (.obj .ply .off .stl), positional or --scene")
        ->required();
    sub->add_option("--rays", a->rays, "Ray file (32-byte float32 records, see rtlab rays)")
        ->required();
    sub->add_option("--accel", a->accel,
                    "Structure spec NAME[,key=value]..., e.g. 'bvh:binned,max_leaf=8' (see rtlab "
                    "list; default " +
                        std::string(default_accel) + "); the JSON names the canonical spec");
    std::string defaults;
    for (const MethodFamily& f : method_families()) {
        defaults += (defaults.empty() ? "" : ", ") + std::string(f.methods.front());
    }
    CLI::Option* method =
        sub->add_option("--method", a->method,
                        "Intersection method(s), comma-separated, one per primitive family "
                        "(defaults: " +
                            defaults + "; all: rtlab list)");
    sub->add_flag("--any-hit", a->any_hit, "Any-hit (occlusion) queries instead of closest hit");
    sub->add_option("--hits", a->hits,
                    "Write hits: per ray float32 t (+inf miss; 0 occluded with --any-hit), "
                    "uint32 prim (0xFFFFFFFF miss), float32 u, v");
    sub->add_option("--threads", a->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    sub->add_option("--repeat", a->repeat,
                    "Timed runs; trace_ms is their median (default 5, after one untimed warm-up "
                    "run)")
        ->check(CLI::Range(1, 10000));
    sub->add_flag("!--no-warmup", a->warmup,
                  "Time the first run too (no untimed warm-up run before the --repeat runs)");
    sub->add_flag("--stats", a->stats,
                  "Count nodes and primitive tests per ray (separate pass); adds the one cost "
                  "model's prediction (cost_model), the measured ct*nodes + ci*prims "
                  "(measured_cost) and, for BVHs over triangles, the end-point overlap (epo); see "
                  "docs/architecture.md");
    sub->add_flag("--robust", a->robust, "Robust traversal: conservative box tests (Ize 2013)");
    sub->add_flag("--exact", a->exact,
                  "Certified hits of triangle meshes: robust traversal, the exact ray/triangle "
                  "test (double with error bounds, exact arithmetic where they cannot decide), "
                  "exact ties to the lowest primitive id; with --stats also exact_tests, "
                  "exact_fallbacks, fallback_rays and fallback_rays_per_million")
        ->excludes(method);
    sub->add_flag("--leaf-time", a->leaf_time,
                  "Also time the traversal alone (--repeat runs, each ray's window ending at its "
                  "hit, leaves offered but not tested): traverse_ms, and leaf_share = 1 - "
                  "traverse_ms / trace_ms, about the share of leaf work")
        ->excludes("--any-hit");
    return {sub, [a] { return run_trace(*a); }};
}

}  // namespace rtlab::app
