// run_shard: measures a shard's cases through trace/measure.h and records them.
#include "sweep/shard_runner.h"

#include "accel/any_accel.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/fnv1a.h"
#include "base/split.h"
#include "crosscheck/crosscheck.h"
#include "crosscheck/row_json.h"
#include "render/image.h"
#include "render/renderer.h"
#include "sweep/provenance.h"
#include "trace/measure.h"
#include "trace/measure_json.h"
#include "trace/ray_gen.h"
#include "trace/scene_tracer.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tbb/global_control.h>
#include <tbb/info.h>

namespace rtlab::sweep {

namespace {

// What a shard keeps between cases: the current scene and its ray sets, the current tracer.
struct Workspace {
    std::size_t scene_index = SIZE_MAX;
    std::optional<Scene> scene;
    std::string scene_error;  // non-empty: the scene failed to load, every case of it fails
    std::map<std::string, std::vector<Rayf>> rays;
    std::string tracer_key;
    std::unique_ptr<SceneTracer> tracer;
};

void use_scene(Workspace& w, const SweepFile& s, std::size_t index) {
    if (w.scene_index == index) {
        return;
    }
    w = Workspace{};
    w.scene_index = index;
    try {
        w.scene = make_scene(s.scenes[index]);
    } catch (const std::exception& e) {
        w.scene_error = e.what();
    }
}

nlohmann::json params_of(const std::string& spec) {
    const AccelSpec a = parse_accel_spec(spec);
    nlohmann::json p = nlohmann::json::object();
    for (std::size_t i = 0; i < a.entry->params.size(); ++i) {
        const ParamSpec& ps = a.entry->params[i];
        if (!a.applies(i)) {
            continue;  // as the canonical spec: only the keys that take effect
        }
        if (ps.kind == ParamKind::choice) {
            p[std::string(ps.key)] = ps.format(a.values[i]);
        } else if (ps.kind == ParamKind::integer) {
            p[std::string(ps.key)] = static_cast<std::int64_t>(a.values[i]);
        } else {
            p[std::string(ps.key)] = std::stod(ps.format(a.values[i]));  // as the spec writes it
        }
    }
    return p;
}

// The fields that say what case c is (before anything is measured).
void describe_case(const Planned& p, const Case& c, nlohmann::json& j) {
    j["case"] = c.id;
    j["index"] = c.index;
    j["type"] = to_string(c.type);
    j["scene"] = scene_label(p.sweep, c);
    if (c.type != CaseType::crosscheck) {
        j["scene_key"] = p.sweep.scenes[c.scene].key;
        j["spec"] = c.spec;
        j["structure"] = c.spec.substr(0, c.spec.find(','));
        j["params"] = params_of(c.spec);
    } else {
        j["prim"] = p.sweep.crosschecks[c.entry].prim;
    }
    j["methods"] = c.methods.empty() ? "default" : c.methods;
    j["kind"] = c.kind;
    if (c.type == CaseType::trace) {
        j["query"] = c.any_hit() ? "any_hit" : "closest_hit";
        j["ray_count"] = p.sweep.ray_count;
        j["repeat"] = p.sweep.repeat;
    }
    j["threads"] = c.threads;
}

// Builds the case's structure unless the workspace holds it already (same spec, methods and
// threads).
void use_tracer(Workspace& w, const SweepFile& s, const Case& c, int threads) {
    const std::string key = fmt::format("{}|{}|{}", c.spec, c.methods, threads);
    if (w.tracer_key != key) {
        w.tracer.reset();
        w.tracer_key.clear();
        TraceSetup setup;
        setup.accel = parse_accel_spec(c.spec);
        setup.methods = split_commas(c.methods);
        setup.robust = s.robust;
        setup.exact = s.exact;
        w.tracer = std::make_unique<SceneTracer>(*w.scene, setup);
        w.tracer_key = key;
    }
}

// "family=method" of every set the tracer built, space-separated: what ran.
std::string sets_text(const SceneTracer& tracer) {
    std::string sets;
    for (const std::string& x : tracer.set_methods()) {
        sets += fmt::format("{}{}", sets.empty() ? "" : " ", x);
    }
    return sets;
}

// Measures trace case c into j (throws on failure; the caller records the error).
void measure_case(Workspace& w, const SweepFile& s, const Case& c, int threads, nlohmann::json& j) {
    if (!w.scene_error.empty()) {
        throw Error(w.scene_error);
    }
    auto rays_it = w.rays.find(c.kind);
    if (rays_it == w.rays.end()) {
        rays_it =
            w.rays.emplace(c.kind, make_rays(*w.scene, parse_ray_kind(c.kind), s.ray_count, s.seed))
                .first;
    }
    use_tracer(w, s, c, threads);
    MeasureOptions opt;
    opt.any_hit = c.any_hit();
    opt.repeat = s.repeat;
    opt.warmup = s.warmup;
    opt.stats = s.stats;
    const TraceMeasurement m = measure_trace(*w.tracer, rays_it->second, opt);
    j["sets"] = sets_text(*w.tracer);
    j["primitives"] = w.tracer->primitive_count();
    write_measurement(j, m);
}

// FNV-1a over the pixels' float bits: equal images give equal hashes (a render is the same for
// any thread count), so runs on different machines or schedulers compare case for case.
std::string image_hash(const Image& img) {
    Fnv1a h;
    for (const Vec3f& p : img.pixels) {
        for (std::size_t k = 0; k < 3; ++k) {
            h.add_u32(std::bit_cast<std::uint32_t>(p[k]));
        }
    }
    return fmt::format("{:016x}", h.value());
}

// Renders case c into DIR/images/<id>.png (.exr for depth, which keeps the distances) and
// records the figures in j.
void measure_render(Workspace& w, const Planned& p, const Case& c, int threads, nlohmann::json& j) {
    if (!w.scene_error.empty()) {
        throw Error(w.scene_error);
    }
    use_tracer(w, p.sweep, c, threads);
    const RenderRows& r = p.sweep.renders[c.entry];
    RenderSettings rs;
    rs.width = r.width;
    rs.height = r.height;
    rs.max_depth = r.max_depth;
    rs.aov = parse_aov(c.kind);
    RenderResult res = render(*w.scene, *w.tracer, rs);
    j["width"] = r.width;
    j["height"] = r.height;
    j["depth"] = r.max_depth;
    j["image_hash"] = image_hash(res.image);
    j["non_finite_pixels"] = clear_non_finite(res.image);
    const std::string image =
        fmt::format("images/{}.{}", c.id, rs.aov == Aov::depth ? "exr" : "png");
    std::filesystem::create_directories(p.dir / "images");
    write_image(res.image, p.dir / image, rs.aov == Aov::color);
    j["image"] = image;
    const RenderStats& st = res.stats;
    j["sets"] = sets_text(*w.tracer);
    j["primitives"] = w.tracer->primitive_count();
    j["rays"] = st.total();
    j["eye_rays"] = st.eye;
    j["shadow_rays"] = st.shadow;
    j["reflected_rays"] = st.reflected;
    j["refracted_rays"] = st.refracted;
    j["hits"] = st.hits;
    j["build_ms"] = w.tracer->build_ms();
    j["render_ms"] = st.render_ms;
    j["mrays_per_s"] =
        st.render_ms > 0 ? static_cast<double>(st.total()) / (st.render_ms * 1e3) : 0.0;
}

// Runs cross-check case c (one method, one precision) and records its row in j.
void measure_crosscheck(const Planned& p, const Case& c, nlohmann::json& j) {
    const CrosscheckRows& x = p.sweep.crosschecks[c.entry];
    xcheck::Options opt;
    opt.methods = {c.methods};
    opt.f32 = c.kind == "float";
    opt.f64 = !opt.f32;
    opt.rays = x.rays;
    opt.seed = x.seed;
    const std::vector<xcheck::Row> rows = xcheck::find_prim_check(x.prim)->run(opt);
    if (rows.size() != 1) {
        throw Error(fmt::format("crosscheck {} {} {}: {} rows, expected 1", x.prim, c.methods,
                                c.kind, rows.size()));
    }
    const nlohmann::json row = xcheck::row_json(rows.front());
    for (const auto& [k, v] : row.items()) {
        if (k != "set" && k != "method") {
            j[k] = v;
        }
    }
    j["seed"] = x.seed;
}

void write_shard(const std::filesystem::path& file, const std::vector<nlohmann::json>& lines) {
    std::string text;
    for (const nlohmann::json& l : lines) {
        text += l.dump() + "\n";
    }
    write_file_atomically(file, text);
}

}  // namespace

int default_cpus() {
    if (const char* v = std::getenv("SLURM_CPUS_PER_TASK")) {
        const int n = std::atoi(v);
        if (n > 0) {
            return n;
        }
    }
    return tbb::info::default_concurrency();
}

ShardOutcome run_shard(const Planned& p, std::size_t k, const ShardOptions& opt) {
    if (k >= p.shards.size()) {
        throw Error(fmt::format("sweep: shard {} does not exist ({} shards: 0..{})", k,
                                p.shards.size(), p.shards.size() - 1));
    }
    const std::filesystem::path file = shard_file(p.dir, k);
    const std::map<std::string, nlohmann::json> known = read_results(p.dir);
    // Keep this shard's done lines; failed and missing cases run (again).
    std::vector<nlohmann::json> lines;
    ShardOutcome out;
    std::vector<const Case*> todo;
    for (const std::size_t i : p.shards[k]) {
        const Case& c = p.cases[i];
        const auto it = known.find(c.id);
        if (it != known.end() && it->second.value("status", "") == "done") {
            lines.push_back(it->second);
            ++out.skipped;
        } else {
            todo.push_back(&c);
        }
    }
    const nlohmann::json prov = run_provenance();
    const int cpus = opt.cpus > 0 ? opt.cpus : default_cpus();
    Workspace w;
    for (const Case* c : todo) {
        const int threads = c->threads > 0 ? c->threads : cpus;
        nlohmann::json j;
        describe_case(p, *c, j);
        j["shard"] = k;
        nlohmann::json pv = prov;
        pv["start"] = utc_now();
        pv["seed"] = p.sweep.seed;
        // More threads than the process may use run as many as it may (TBB caps them).
        pv["threads_used"] = std::min(threads, tbb::info::default_concurrency());
        try {
            const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                            static_cast<std::size_t>(threads));
            if (c->type == CaseType::crosscheck) {
                measure_crosscheck(p, *c, j);
            } else {
                use_scene(w, p.sweep, c->scene);
                if (c->type == CaseType::render) {
                    measure_render(w, p, *c, threads, j);
                } else {
                    measure_case(w, p.sweep, *c, threads, j);
                }
            }
            j["status"] = "done";
            ++out.done;
        } catch (const std::exception& e) {
            j["status"] = "failed";
            j["error"] = e.what();
            w.tracer.reset();
            w.tracer_key.clear();
            ++out.failed;
        }
        pv["end"] = utc_now();
        pv["end_unix"] = unix_now();
        j["provenance"] = pv;
        if (opt.log != nullptr) {
            *opt.log << fmt::format(
                            "[shard {}] {} {} {} {} {} {}: {}\n", k, c->id, to_string(c->type),
                            scene_label(p.sweep, *c), c->spec, j["methods"].get<std::string>(),
                            c->kind,
                            j["status"] != "done"
                                ? fmt::format("FAILED: {}", j["error"].get<std::string>())
                            : c->type == CaseType::crosscheck
                                ? fmt::format("{} of {} agree", j["agree"].get<std::size_t>(),
                                              j["rays"].get<std::size_t>())
                                : fmt::format("{:.3f} Mrays/s", j["mrays_per_s"].get<double>()))
                     << std::flush;
        }
        lines.push_back(std::move(j));
        write_shard(file, lines);
    }
    if (todo.empty() && !std::filesystem::exists(file) && !lines.empty()) {
        write_shard(file, lines);
    }
    return out;
}

}  // namespace rtlab::sweep
