// Sweep folders: binding a sweep to DIR, reading shard result files, status.
#include "sweep/sweep_dir.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "sweep/case_check.h"

#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace rtlab::sweep {

namespace fs = std::filesystem;

namespace {

nlohmann::json read_json(const fs::path& file) {
    std::ifstream in(file);
    if (!in) {
        throw Error(file.string() + ": cannot open");
    }
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(file.string() + ": not valid JSON (" + e.what() + ")");
    }
}

Planned make_planned(const fs::path& dir, SweepFile s, std::size_t shards) {
    Planned p;
    p.dir = dir;
    p.cases = expand_cases(s);
    p.shards = deal_shards(s, p.cases, shards);
    p.sweep = std::move(s);
    return p;
}

}  // namespace

fs::path shard_file(const fs::path& dir, std::size_t k) {
    return dir / "results" / fmt::format("shard-{:04}.jsonl", k);
}

Planned plan_into(const fs::path& file, const fs::path& dir, std::size_t shards, bool write) {
    SweepFile s = load_sweep_file(file);
    const fs::path stored = dir / "sweep.json";
    const fs::path plan = dir / "plan.json";
    if (!dir.empty() && fs::exists(stored)) {
        const SweepFile old = load_sweep_file(stored);
        if (old.normalized != s.normalized) {
            throw Error(dir.string() + ": holds another sweep (its sweep.json differs from " +
                        file.string() + "); use a new output folder");
        }
        const auto old_shards = read_json(plan).at("shards").get<std::size_t>();
        if (shards != 0 && shards != old_shards) {
            throw Error(fmt::format("{}: was planned with {} shards, not {}", dir.string(),
                                    old_shards, shards));
        }
        return make_planned(dir, std::move(s), old_shards);
    }
    Planned p = make_planned(dir, std::move(s), shards);
    // A folder that holds the sweep was checked when it was planned (shard runs reopen it).
    check_cases(p.sweep, p.cases, file.string());
    if (!write) {
        return p;
    }
    std::error_code ec;
    fs::create_directories(dir / "results", ec);
    if (ec) {
        throw Error(dir.string() + ": cannot create (" + ec.message() + ")");
    }
    nlohmann::json pj;
    pj["sweep"] = p.sweep.name;
    pj["shards"] = p.shards.size();
    pj["cases"] = p.cases.size();
    write_file_atomically(plan, pj.dump(1) + "\n");
    write_file_atomically(stored, p.sweep.normalized.dump(2) + "\n");
    return p;
}

Planned open_dir(const fs::path& dir) {
    if (!fs::is_regular_file(dir / "sweep.json") || !fs::is_regular_file(dir / "plan.json")) {
        throw Error(dir.string() + ": not a sweep folder (no sweep.json and plan.json)");
    }
    SweepFile s = load_sweep_file(dir / "sweep.json");
    return make_planned(dir, std::move(s),
                        read_json(dir / "plan.json").at("shards").get<std::size_t>());
}

std::vector<nlohmann::json> read_shard_file(const fs::path& file) {
    std::vector<nlohmann::json> out;
    std::ifstream in(file);
    if (!in) {
        return out;
    }
    std::string line;
    for (std::size_t n = 1; std::getline(in, line); ++n) {
        if (line.empty()) {
            continue;
        }
        nlohmann::json j;
        try {
            j = nlohmann::json::parse(line);
        } catch (const nlohmann::json::exception&) {
            throw Error(fmt::format("{}:{}: not a JSON line", file.string(), n));
        }
        if (!j.is_object() || !j.contains("case") || !j["case"].is_string()) {
            throw Error(fmt::format("{}:{}: no \"case\" id", file.string(), n));
        }
        out.push_back(std::move(j));
    }
    return out;
}

std::map<std::string, nlohmann::json> read_results(const fs::path& dir) {
    std::map<std::string, nlohmann::json> out;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dir / "results", ec)) {
        if (e.path().extension() != ".jsonl") {
            continue;  // temporaries of atomic writes and anything else
        }
        for (nlohmann::json& j : read_shard_file(e.path())) {
            const std::string id = j["case"].get<std::string>();
            auto it = out.find(id);
            if (it == out.end() || j.value("status", "") == "done") {
                out[id] = std::move(j);
            }
        }
    }
    return out;
}

Status status_of(const Planned& p, const std::map<std::string, nlohmann::json>& results) {
    Status st;
    for (const Case& c : p.cases) {
        const auto it = results.find(c.id);
        if (it == results.end()) {
            ++st.missing;
            st.missing_cases.push_back(c.index);
        } else if (it->second.value("status", "") == "done") {
            ++st.done;
        } else {
            ++st.failed;
            st.failed_cases.push_back(c.index);
        }
    }
    return st;
}

}  // namespace rtlab::sweep
