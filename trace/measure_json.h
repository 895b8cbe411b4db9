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
    j["rays"] = m.rays;
    j["hits"] = m.hits;
    j["build_ms"] = m.build_ms;
    j["trace_ms"] = m.trace_ms;
    j["trace_ms_runs"] = m.trace_ms_runs;
    j["mrays_per_s"] = m.mrays_per_s;
    j["accel_bytes"] = m.accel_bytes;
    j["bytes_per_prim"] = m.bytes_per_prim;
    j["nodes"] = m.nodes;
    j["leaves"] = m.leaves;
    j["max_depth"] = m.max_depth;
    j["sah_cost"] = m.sah_cost;
    if (m.has_stats) {
        j["nodes_per_ray"] = m.nodes_per_ray;
        j["prims_per_ray"] = m.prims_per_ray;
        j["cost_model"] = m.cost_model;
        j["measured_cost"] = m.measured_cost;
        if (m.epo >= 0) {
            j["epo"] = m.epo;
        }
    }
}

}  // namespace rtlab
