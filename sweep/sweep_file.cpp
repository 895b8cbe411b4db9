// Loading and validating sweep files.
#include "sweep/sweep_file.h"

#include "accel/any_accel.h"
#include "base/error.h"
#include "datasets_gen/generators.h"
#include "scene/scene_io.h"
#include "sweep/json_read.h"
#include "trace/method_check.h"
#include "trace/ray_gen.h"

#include <fmt/format.h>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rtlab::sweep {

namespace {

using namespace detail;

const std::set<std::string> top_keys{
    "name",   "seed",  "scenes", "structures", "methods", "rays",       "threads",  "repeat",
    "warmup", "stats", "robust", "exact",      "renders", "crosscheck", "base_dir", "comment"};

SceneSource parse_scene(const ojson& s,
                        const std::string& where,
                        const std::filesystem::path& base) {
    SceneSource src;
    if (!s.is_object()) {
        fail(where, "expected an object {\"generator\": ...} or {\"file\": ...}");
    }
    for (const auto& [k, v] : s.items()) {
        const std::string w = where + "." + k;
        if (k == "generator") {
            src.generator = get_string(v, w);
        } else if (k == "file") {
            src.file = get_string(v, w);
        } else if (k == "name") {
            src.label = get_string(v, w);
        } else if (k == "size") {
            src.size = static_cast<int>(get_int(v, w, 0, 64));
        } else if (k == "as") {
            const std::string as = get_string(v, w);
            if (as != "mesh" && as != "spheres") {
                fail(w, fmt::format("expected \"spheres\" or \"mesh\", got \"{}\"", as));
            }
            src.as_mesh = as == "mesh";
        } else if (k == "tess") {
            src.tess = get_string(v, w);
        } else if (k == "seed") {
            src.seed = static_cast<std::uint64_t>(get_int(v, w, 0, INT64_MAX));
        } else {
            fail(w, "unknown key (scene keys: generator size as tess seed name, or file name)");
        }
    }
    if (src.generator.empty() == src.file.empty()) {
        fail(where, "name exactly one of \"generator\" and \"file\"");
    }
    if (!src.generator.empty()) {
        const gen::Generator* g = gen::find_generator(src.generator);
        if (g == nullptr) {
            std::string names;
            for (const gen::Generator& x : gen::generators()) {
                names += fmt::format("{}{}", names.empty() ? "" : " ", x.name);
            }
            fail(where + ".generator",
                 fmt::format("unknown generator '{}' (known: {})", src.generator, names));
        }
        const int size = src.size < 0 ? g->default_size : src.size;
        if (size < g->min_size || size > g->max_size) {
            fail(where + ".size", fmt::format("{} is outside [{}, {}] for {}", size, g->min_size,
                                              g->max_size, src.generator));
        }
        src.size = size;
        try {
            (void)gen::parse_sphere_tess(src.tess);
        } catch (const std::exception& e) {
            fail(where + ".tess", e.what());
        }
        src.key = fmt::format("{},size={},as={},tess={},seed={}", src.generator, size,
                              src.as_mesh ? "mesh" : "spheres", src.tess, src.seed);
    } else {
        src.path = base / src.file;
        if (!std::filesystem::is_regular_file(src.path)) {
            fail(where + ".file", src.path.string() + " does not exist");
        }
        src.key = fmt::format("file:{}", src.file);
    }
    if (src.label.empty()) {
        src.label = src.key;
    }
    return src;
}

std::string value_text(const ojson& v, const std::string& where) {
    if (v.is_string()) {
        return v.get<std::string>();
    }
    if (v.is_number()) {
        return v.dump();
    }
    fail(where, fmt::format("expected a number, a string or a list of them, got {}", v.dump()));
}

std::string check_method_list(const ojson& m, const std::string& where) {
    const std::string text = get_string(m, where);
    if (text == "default") {
        return "";
    }
    std::stringstream ss(text);
    std::string name;
    std::vector<std::string> names;
    while (std::getline(ss, name, ',')) {
        if (method_family(name).empty()) {
            fail(where, fmt::format("unknown method '{}' (see rtlab list)", name));
        }
        names.push_back(name);
    }
    check_one_method_per_family(names, fmt::format("{}: '{}'", where, text));
    return text;
}

// The "rays" object: kinds (checked) and count.
void parse_rays(const ojson& rays, const std::string& where, SweepFile& s) {
    if (!rays.is_object()) {
        fail(where + ": rays", "expected {\"kinds\": [...], \"count\": N}");
    }
    for (const auto& [k, v] : rays.items()) {
        if (k == "kinds") {
            for (const ojson& kind : as_list(v)) {
                const std::string name = get_string(kind, where + ": rays.kinds");
                try {
                    (void)parse_ray_kind(name);
                } catch (const std::exception&) {
                    fail(
                        where + ": rays.kinds",
                        fmt::format("unknown ray kind '{}' (primary shadow diffuse random)", name));
                }
                s.kinds.push_back(name);
            }
        } else if (k == "count") {
            s.ray_count =
                static_cast<std::size_t>(get_int(v, where + ": rays.count", 1, 100000000));
        } else {
            fail(where + ": rays." + k, "unknown key (rays keys: kinds count)");
        }
    }
    if (s.kinds.empty()) {
        s.kinds = {"primary"};
    }
}

}  // namespace

std::vector<std::string> expand_structure(const ojson& entry, const std::string& where) {
    std::vector<std::string> texts;
    if (entry.is_string()) {
        texts.push_back(entry.get<std::string>());
    } else if (entry.is_object()) {
        if (!entry.contains("spec")) {
            fail(where, "a structure object needs \"spec\"");
        }
        texts.push_back(get_string(entry["spec"], where + ".spec"));
        for (const auto& [k, v] : entry.items()) {
            if (k == "spec") {
                continue;
            }
            std::vector<std::string> next;
            const std::vector<ojson> values = as_list(v);
            if (values.empty()) {
                fail(where + "." + k, "an empty list");
            }
            for (const std::string& t : texts) {
                for (const ojson& x : values) {
                    next.push_back(t + "," + k + "=" + value_text(x, where + "." + k));
                }
            }
            texts = std::move(next);
        }
    } else {
        fail(where, "expected a spec string or {\"spec\": ..., key: [values]}");
    }
    std::vector<std::string> out;
    for (const std::string& t : texts) {
        try {
            out.push_back(parse_accel_spec(t).canonical());
        } catch (const std::invalid_argument& e) {
            fail(where, e.what());
        }
    }
    return out;
}

namespace {

/// The sweep file's JSON (comments allowed): an object with known top-level keys only.
ojson read_sweep_json(const std::filesystem::path& file) {
    const std::string where = file.string();
    std::ifstream in(file);
    if (!in) {
        throw Error(where + ": cannot open");
    }
    std::stringstream text;
    text << in.rdbuf();
    ojson j;
    try {
        j = ojson::parse(text.str(), nullptr, true, /*ignore_comments=*/true);
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(where + ": not valid JSON (" + e.what() + ")");
    }
    if (!j.is_object()) {
        throw Error(where + ": expected a JSON object");
    }
    for (const auto& [k, v] : j.items()) {
        if (top_keys.count(k) == 0) {
            fail(where + ": " + k, "unknown key (see docs/sweeps.md)");
        }
    }
    return j;
}

/// The sweep's axes from j: scenes (each once; files relative to base), structure specs
/// (parameter lists expanded) and method lists.
void parse_sweep_axes(const ojson& j,
                      const std::string& where,
                      const std::filesystem::path& base,
                      SweepFile& s) {
    const auto at = [&](const std::string& k) { return where + ": " + k; };
    if (!j.contains("scenes") || !j["scenes"].is_array() || j["scenes"].empty()) {
        fail(at("scenes"), "a non-empty list of scenes is required");
    }
    std::set<std::string> scene_keys;
    for (std::size_t i = 0; i < j["scenes"].size(); ++i) {
        const std::string w = at(fmt::format("scenes[{}]", i));
        s.scenes.push_back(parse_scene(j["scenes"][i], w, base));
        if (!scene_keys.insert(s.scenes.back().key).second) {
            fail(w, "the same scene twice (" + s.scenes.back().key + ")");
        }
    }
    if (!j.contains("structures") || !j["structures"].is_array() || j["structures"].empty()) {
        fail(at("structures"), "a non-empty list of structure specs is required");
    }
    for (std::size_t i = 0; i < j["structures"].size(); ++i) {
        for (std::string& spec :
             expand_structure(j["structures"][i], at(fmt::format("structures[{}]", i)))) {
            s.specs.push_back(std::move(spec));
        }
    }
    const ojson methods = j.value("methods", ojson::array({"default"}));
    for (std::size_t i = 0; i < as_list(methods).size(); ++i) {
        s.methods.push_back(
            check_method_list(as_list(methods)[i], at(fmt::format("methods[{}]", i))));
    }
    if (s.methods.empty()) {
        fail(at("methods"), "an empty list");
    }
}

/// The sweep's run options from j: threads, repeat, warm-up, stats, robust, exact, renders,
/// cross-checks.
void parse_sweep_options(const ojson& j, const std::string& where, SweepFile& s) {
    const auto at = [&](const std::string& k) { return where + ": " + k; };
    if (j.contains("threads")) {
        s.threads.clear();
        for (const ojson& t : as_list(j["threads"])) {
            s.threads.push_back(static_cast<int>(get_int(t, at("threads"), 0, 1024)));
        }
        if (s.threads.empty()) {
            fail(at("threads"), "an empty list");
        }
    }
    if (j.contains("repeat")) {
        s.repeat = static_cast<int>(get_int(j["repeat"], at("repeat"), 1, 10000));
    }
    if (j.contains("warmup")) {
        s.warmup = static_cast<int>(get_int(j["warmup"], at("warmup"), 0, 10000));
    }
    if (j.contains("stats")) {
        s.stats = get_bool(j["stats"], at("stats"));
    }
    if (j.contains("robust")) {
        s.robust = get_bool(j["robust"], at("robust"));
    }
    if (j.contains("renders")) {
        s.renders = parse_renders(j["renders"], at("renders"), s);
    }
    if (j.contains("exact")) {
        s.exact = get_bool(j["exact"], at("exact"));
    }
    if (s.exact) {
        // Exact mode has one test and keeps no per-ray counts: what would not run is refused.
        for (const std::string& m : s.methods) {
            if (!m.empty()) {
                fail(at("exact"),
                     "runs the certified triangle test only; methods must be "
                     "\"default\" (found \"" +
                         m + "\")");
            }
        }
        for (const RenderRows& r : s.renders) {
            for (const std::string& aov : r.aovs) {
                if (aov == "heatmap") {
                    fail(at("exact"), "keeps no per-ray counts, so no heatmap render");
                }
            }
        }
    }
    if (j.contains("crosscheck")) {
        s.crosschecks = parse_crosschecks(j["crosscheck"], at("crosscheck"));
    }
}

}  // namespace

Scene make_scene(const SceneSource& src) {
    if (!src.generator.empty()) {
        gen::GenOptions o;
        o.size = src.size;
        o.as_mesh = src.as_mesh;
        o.tess = gen::parse_sphere_tess(src.tess);
        o.seed = src.seed;
        return gen::generate(src.generator, o);
    }
    return load_scene(src.path);
}

SweepFile load_sweep_file(const std::filesystem::path& file) {
    const std::string where = file.string();
    ojson j = read_sweep_json(file);
    std::filesystem::path base = std::filesystem::absolute(file).parent_path();
    if (j.contains("base_dir")) {
        base = get_string(j["base_dir"], where + ": base_dir");
    } else {
        j["base_dir"] = base.lexically_normal().string();
    }
    SweepFile s;
    s.normalized = j;
    if (j.contains("name")) {
        s.name = get_string(j["name"], where + ": name");
    }
    if (j.contains("seed")) {
        s.seed = static_cast<std::uint64_t>(get_int(j["seed"], where + ": seed", 0, INT64_MAX));
    }
    parse_sweep_axes(j, where, base, s);
    parse_rays(j.value("rays", ojson::object()), where, s);
    parse_sweep_options(j, where, s);
    return s;
}

}  // namespace rtlab::sweep
