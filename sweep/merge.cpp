// merge_results: shard files to one CSV and one JSON table.
#include "sweep/merge.h"

#include "base/atomic_file.h"

#include <fmt/format.h>
#include <set>

namespace rtlab::sweep {

namespace {

// The table's fixed columns, in order (values missing from a row stay empty).
const std::vector<std::string> columns{
    "case", "index", "status", "type", "scene", "scene_key", "structure", "spec", "methods", "sets",
    "kind", "query", "threads", "ray_count", "repeat", "primitives", "rays", "hits", "build_ms",
    "trace_ms", "mrays_per_s", "accel_bytes", "bytes_per_prim", "nodes", "leaves", "max_depth",
    "sah_cost", "nodes_per_ray", "prims_per_ray", "cost_model", "measured_cost",
    // render cases (kind = AOV)
    "width", "height", "depth", "render_ms", "eye_rays", "shadow_rays", "reflected_rays",
    "refracted_rays", "image", "image_hash", "non_finite_pixels",
    // cross-check cases (methods = the method, kind = the precision)
    "prim", "agree", "wrong_t", "t_tol", "false_hit", "false_miss", "max_rel_t_err",
    "median_rel_t_err", "has_setup", "setup_ns_per_ray", "ns_per_test", "error"};
const std::vector<std::string> prov_columns{"git",   "version", "build",     "compiler",
                                            "host",  "cpu",     "slurm_job", "slurm_task",
                                            "start", "end",     "seed",      "threads_used"};

std::string csv_cell(const nlohmann::json& v) {
    std::string s;
    if (v.is_null()) {
        return s;
    }
    s = v.is_string() ? v.get<std::string>() : v.dump();
    if (s.find_first_of(",\"\n") != std::string::npos) {
        std::string q = "\"";
        for (const char c : s) {
            if (c == '"') {
                q.append("\"\"");
            } else {
                q.push_back(c == '\n' ? ' ' : c);
            }
        }
        return q + "\"";
    }
    return s;
}

}  // namespace

MergeOutcome merge_results(const Planned& p, const std::filesystem::path& table) {
    const std::map<std::string, nlohmann::json> results = read_results(p.dir);
    MergeOutcome out;
    out.status = status_of(p, results);
    std::filesystem::path base = table;
    if (base.extension() == ".csv" || base.extension() == ".json") {
        base.replace_extension();
    }
    out.csv = base;
    out.csv += ".csv";
    out.json = base;
    out.json += ".json";

    nlohmann::json rows = nlohmann::json::array();
    std::vector<std::string> param_keys;
    std::set<std::string> seen_keys;
    for (const Case& c : p.cases) {
        const auto it = results.find(c.id);
        if (it == results.end()) {
            continue;
        }
        rows.push_back(it->second);
        const auto params = it->second.find("params");
        if (params != it->second.end() && params->is_object()) {
            for (const auto& [k, v] : params->items()) {
                if (seen_keys.insert(k).second) {
                    param_keys.push_back(k);
                }
            }
        }
    }
    nlohmann::json missing = nlohmann::json::array();
    for (const std::size_t i : out.status.missing_cases) {
        nlohmann::json m;
        m["case"] = p.cases[i].id;
        m["index"] = i;
        m["type"] = to_string(p.cases[i].type);
        m["scene"] = scene_label(p.sweep, p.cases[i]);
        m["spec"] = p.cases[i].spec;
        m["kind"] = p.cases[i].kind;
        missing.push_back(m);
    }

    std::string csv;
    for (const std::string& c : columns) {
        csv += c + ",";
    }
    for (const std::string& k : param_keys) {
        csv += fmt::format("p_{},", k);
    }
    for (const std::string& k : prov_columns) {
        csv += k + (k == prov_columns.back() ? "\n" : ",");
    }
    for (const nlohmann::json& r : rows) {
        for (const std::string& c : columns) {
            csv += csv_cell(r.value(c, nlohmann::json())) + ",";
        }
        const nlohmann::json params = r.value("params", nlohmann::json::object());
        for (const std::string& k : param_keys) {
            csv += csv_cell(params.value(k, nlohmann::json())) + ",";
        }
        const nlohmann::json prov = r.value("provenance", nlohmann::json::object());
        for (const std::string& k : prov_columns) {
            csv +=
                csv_cell(prov.value(k, nlohmann::json())) + (k == prov_columns.back() ? "\n" : ",");
        }
    }
    nlohmann::json j;
    j["sweep"] = p.sweep.name;
    j["cases"] = rows;
    j["missing"] = missing;
    j["counts"] = {{"total", p.cases.size()},
                   {"done", out.status.done},
                   {"failed", out.status.failed},
                   {"missing", out.status.missing}};
    write_file_atomically(out.csv, csv);
    write_file_atomically(out.json, j.dump(1) + "\n");
    return out;
}

}  // namespace rtlab::sweep
