// rtlab compare: compares two hit files ray by ray. t must agree within a relative tolerance; the
// primitive must be the same unless the two hits are an exact tie (same t within the tolerance,
// e.g. a ray through a shared edge). A NaN t on a hit is a disagreement (it equals nothing, so it
// is never within the tolerance). Prints one JSON object; exits 1 when the files disagree.
#include "apps/commands.h"
#include "trace/binary_io.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace rtlab::app {

namespace {
struct CompareArgs {
    std::string a, b;
    double rel_tol = 1e-6;
    bool any_hit = false;
};
}  // namespace

Command add_compare(CLI::App& root) {
    auto a = std::make_shared<CompareArgs>();
    CLI::App* sub = root.add_subcommand(
        "compare",
        "Compare two hit files (rtlab trace --hits): same hit/miss, t within --rel-tol (a NaN t "
        "never is), same primitive except exact ties; prints one JSON object, exit 1 on "
        "disagreement");
    sub->add_option("A", a->a, "First hit file")->required();
    sub->add_option("B", a->b, "Second hit file")->required();
    sub->add_option("--rel-tol", a->rel_tol, "Relative tolerance on t (default 1e-6)")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_flag("--any-hit", a->any_hit,
                  "Files come from --any-hit: compare occluded or not only (any blocker counts)");
    return {sub, [a] {
                const std::vector<Hit> ha = load_hits(a->a);
                const std::vector<Hit> hb = load_hits(a->b);
                if (ha.size() != hb.size()) {
                    throw std::runtime_error(a->b + ": " + std::to_string(hb.size()) +
                                             " hits, but " + a->a + " has " +
                                             std::to_string(ha.size()));
                }
                std::size_t hit_miss = 0, t_diff = 0, nan_t = 0, ties = 0;
                double max_rel = 0;
                for (std::size_t i = 0; i < ha.size(); ++i) {
                    const Hit& x = ha[i];
                    const Hit& y = hb[i];
                    if (x.valid() != y.valid()) {
                        ++hit_miss;
                        continue;
                    }
                    if (!x.valid() || a->any_hit) {
                        continue;
                    }
                    const double tx = x.t, ty = y.t;
                    const double rel = std::abs(tx - ty) / std::max(std::abs(tx), 1e-30);
                    if (std::isnan(rel)) {
                        ++nan_t;  // counted in t_diff as well: a NaN t agrees with nothing
                    } else {
                        max_rel = std::max(max_rel, rel);
                    }
                    if (!(rel <= a->rel_tol)) {
                        ++t_diff;
                    } else if (x.prim != y.prim) {
                        ++ties;  // same t, other primitive: an exact tie (shared edge, overlap)
                    }
                }
                const bool agree = hit_miss == 0 && t_diff == 0;
                nlohmann::json j{{"a", a->a},
                                 {"b", a->b},
                                 {"rays", ha.size()},
                                 {"agree", agree},
                                 {"hit_miss", hit_miss},
                                 {"t_diff", t_diff},
                                 {"nan_t", nan_t},
                                 {"ties", ties},
                                 {"max_rel_t_diff", max_rel}};
                std::cout << j.dump() << "\n";
                return agree ? 0 : 1;
            }};
}

}  // namespace rtlab::app
