#pragma once
// One cross-check row as JSON: `rtlab crosscheck --json` prints these, `rtlab sweep` records them.

#include "crosscheck/crosscheck.h"

#include <nlohmann/json.hpp>

namespace rtlab::xcheck {

/// The row's fields under their own names (a NaN error becomes null).
inline nlohmann::json row_json(const Row& r) {
    return {{"prim", r.prim},
            {"method", r.method},
            {"precision", r.precision},
            {"set", r.set},
            {"rays", r.rays},
            {"agree", r.agree},
            {"wrong_t", r.wrong_t},
            {"t_tol", r.t_tol},
            {"false_hit", r.false_hit},
            {"false_miss", r.false_miss},
            {"max_rel_t_err", r.max_rel_t_err},
            {"median_rel_t_err", r.median_rel_t_err},
            {"has_setup", r.has_setup},
            {"setup_ns_per_ray", r.setup_ns_per_ray},
            {"ns_per_test", r.ns_per_test}};
}

}  // namespace rtlab::xcheck
