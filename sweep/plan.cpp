// Expanding a sweep into cases with stable ids, and dealing them to shards.
#include "sweep/plan.h"

#include "base/error.h"
#include "base/fnv1a.h"

#include <algorithm>
#include <cstdint>
#include <fmt/format.h>
#include <map>

namespace rtlab::sweep {

namespace {

std::uint64_t fnv1a(const std::string& text) {
    Fnv1a h;
    h.add(text);
    return h.value();
}

// Gives c its id from `what` and appends it; throws when two cases measure the same.
void add_case(Case c,
              const std::string& what,
              std::vector<Case>& out,
              std::map<std::string, std::size_t>& seen) {
    c.index = out.size();
    c.id = fmt::format("{:016x}", fnv1a(what));
    const auto [it, fresh] = seen.emplace(c.id, c.index);
    if (!fresh) {
        throw Error(
            fmt::format("sweep: cases {} and {} are the same ({})", it->second, c.index, what));
    }
    out.push_back(std::move(c));
}

void add_render_cases(const SweepFile& s,
                      std::vector<Case>& out,
                      std::map<std::string, std::size_t>& seen) {
    for (std::size_t e = 0; e < s.renders.size(); ++e) {
        const RenderRows& r = s.renders[e];
        for (const std::size_t sc : r.scenes) {
            for (const std::string& spec : r.specs) {
                for (const std::string& aov : r.aovs) {
                    Case c;
                    c.type = CaseType::render;
                    c.scene = sc;
                    c.spec = spec;
                    c.kind = aov;
                    c.entry = e;
                    add_case(std::move(c),
                             fmt::format("render|{}|{}|{}|{}x{}|depth={}", s.scenes[sc].key, spec,
                                         aov, r.width, r.height, r.max_depth),
                             out, seen);
                }
            }
        }
    }
}

void add_crosscheck_cases(const SweepFile& s,
                          std::vector<Case>& out,
                          std::map<std::string, std::size_t>& seen) {
    for (std::size_t e = 0; e < s.crosschecks.size(); ++e) {
        const CrosscheckRows& x = s.crosschecks[e];
        for (const std::string& m : x.methods) {
            for (const std::string& prec : x.precisions) {
                Case c;
                c.type = CaseType::crosscheck;
                c.scene = s.scenes.size();
                c.methods = m;
                c.kind = prec;
                c.entry = e;
                add_case(std::move(c),
                         fmt::format("crosscheck|{}|{}|{}|rays={},seed={}", x.prim, m, prec, x.rays,
                                     x.seed),
                         out, seen);
            }
        }
    }
}

}  // namespace

const char* to_string(CaseType t) {
    switch (t) {
    case CaseType::render:
        return "render";
    case CaseType::crosscheck:
        return "crosscheck";
    case CaseType::trace:
        break;
    }
    return "trace";
}

std::string scene_label(const SweepFile& s, const Case& c) {
    return c.scene < s.scenes.size() ? s.scenes[c.scene].label : std::string("-");
}

std::vector<Case> expand_cases(const SweepFile& s) {
    std::vector<Case> out;
    std::map<std::string, std::size_t> seen;
    for (std::size_t sc = 0; sc < s.scenes.size(); ++sc) {
        for (const std::string& spec : s.specs) {
            for (const std::string& m : s.methods) {
                for (const int t : s.threads) {
                    for (const std::string& kind : s.kinds) {
                        Case c;
                        c.scene = sc;
                        c.spec = spec;
                        c.methods = m;
                        c.threads = t;
                        c.kind = kind;
                        // exact=true only when set, so other sweeps keep their case ids.
                        add_case(std::move(c),
                                 fmt::format("{}|{}|{}|{}|{}|rays={},seed={},repeat={},warmup={},"
                                             "stats={},robust={}{}",
                                             s.scenes[sc].key, spec, m, t, kind, s.ray_count,
                                             s.seed, s.repeat, s.warmup, s.stats, s.robust,
                                             s.exact ? ",exact=true" : ""),
                                 out, seen);
                    }
                }
            }
        }
    }
    add_render_cases(s, out, seen);
    add_crosscheck_cases(s, out, seen);
    return out;
}

std::vector<std::vector<std::size_t>> deal_shards(const SweepFile& s,
                                                  const std::vector<Case>& cases,
                                                  std::size_t shards) {
    std::vector<std::vector<std::size_t>> by_scene(s.scenes.size() + 1);  // + cross-checks
    for (const Case& c : cases) {
        by_scene[c.scene].push_back(c.index);
    }
    std::erase_if(by_scene, [](const auto& v) { return v.empty(); });
    if (shards == 0) {
        shards = by_scene.size();
    }
    shards = std::min(shards, cases.size());
    std::vector<std::vector<std::size_t>> out(shards);
    if (shards <= by_scene.size()) {
        for (std::size_t i = 0; i < by_scene.size(); ++i) {
            auto& dst = out[i % shards];
            dst.insert(dst.end(), by_scene[i].begin(), by_scene[i].end());
        }
        return out;
    }
    // More shards than scenes: every scene gets at least one, the rest go by case count
    // (largest remainder), and each scene's cases split into contiguous, near-equal runs.
    std::vector<std::size_t> per(by_scene.size(), 1);
    std::size_t left = shards - by_scene.size();
    while (left > 0) {
        std::size_t best = 0;
        double best_load = -1;
        for (std::size_t i = 0; i < by_scene.size(); ++i) {
            const double load =
                static_cast<double>(by_scene[i].size()) / static_cast<double>(per[i]);
            if (per[i] < by_scene[i].size() && load > best_load) {
                best = i;
                best_load = load;
            }
        }
        ++per[best];
        --left;
    }
    std::size_t next = 0;
    for (std::size_t i = 0; i < by_scene.size(); ++i) {
        const std::size_t n = by_scene[i].size();
        for (std::size_t k = 0; k < per[i]; ++k) {
            const std::size_t lo = n * k / per[i];
            const std::size_t hi = n * (k + 1) / per[i];
            out[next++].assign(by_scene[i].begin() + static_cast<std::ptrdiff_t>(lo),
                               by_scene[i].begin() + static_cast<std::ptrdiff_t>(hi));
        }
    }
    out.resize(next);
    return out;
}

}  // namespace rtlab::sweep
