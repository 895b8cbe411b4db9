#pragma once
// A measured batch as the JSON fields that `rtlab trace` prints and a sweep case records, written
// in one place so the two outputs name every figure alike.

#include "trace/measure.h"

#include <nlohmann/json.hpp>

namespace rtlab {

/// Writes m's figures into j: counts, times (the median and every timed run), memory and the
/// structures' own figures; per-ray counts and costs when counted; the end-point overlap when
/// measured.
inline void write_measurement(nlohmann::json& j, const TraceMeasurement& m) {
    j.update({{"rays", m.rays},
              {"hits", m.hits},
              {"build_ms", m.build_ms},
              {"trace_ms", m.trace_ms},
              {"trace_ms_runs", m.trace_ms_runs},
              {"mrays_per_s", m.mrays_per_s},
              {"accel_bytes", m.accel_bytes},
              {"bytes_per_prim", m.bytes_per_prim},
              {"nodes", m.nodes},
              {"leaves", m.leaves},
              {"max_depth", m.max_depth},
              {"sah_cost", m.sah_cost}});
    if (m.traverse_ms >= 0) {
        j.update({{"traverse_ms", m.traverse_ms},
                  {"leaf_share", m.trace_ms > 0 ? 1.0 - m.traverse_ms / m.trace_ms : 0.0}});
    }
    if (m.has_stats) {
        j.update({{"nodes_per_ray", m.nodes_per_ray},
                  {"prims_per_ray", m.prims_per_ray},
                  {"cost_model", m.cost_model},
                  {"measured_cost", m.measured_cost}});
        if (m.epo >= 0) {
            j["epo"] = m.epo;
        }
    }
}

}  // namespace rtlab
