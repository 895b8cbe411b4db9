// measure_trace: the timing loop shared by `rtlab trace` and `rtlab sweep`.
#include "trace/measure.h"

#include "accel/cost_model.h"
#include "accel/spec.h"

#include <algorithm>
#include <chrono>

namespace rtlab {

double median_of(std::vector<double> v) {
    if (v.empty()) {
        return 0;
    }
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

// Milliseconds of each of max(repeat, 1) runs of f.
template <class F>
std::vector<double> timed_runs(int repeat, F&& f) {
    std::vector<double> runs;
    for (int k = 0; k < std::max(repeat, 1); ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        runs.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
    }
    return runs;
}

}  // namespace

TraceMeasurement measure_trace(const SceneTracer& tracer,
                               std::span<const Rayf> rays,
                               const MeasureOptions& opt,
                               std::vector<Hit>* hits_out) {
    std::vector<Hit> hits(rays.size());
    std::vector<std::uint32_t> blockers(rays.size());
    TraceMeasurement m;
    for (int k = 0; k < opt.warmup; ++k) {
        if (opt.any_hit) {
            tracer.occluded(rays, blockers);
        } else {
            tracer.intersect(rays, hits);
        }
    }
    m.trace_ms_runs = timed_runs(opt.repeat, [&] {
        if (opt.any_hit) {
            tracer.occluded(rays, blockers);
        } else {
            tracer.intersect(rays, hits);
        }
    });
    if (opt.any_hit) {
        for (std::size_t i = 0; i < rays.size(); ++i) {
            hits[i] = blockers[i] == invalid_id ? Hit{} : Hit{0.0f, 0.0f, 0.0f, blockers[i]};
        }
    }
    m.rays = rays.size();
    m.hits = static_cast<std::size_t>(
        std::count_if(hits.begin(), hits.end(), [](const Hit& h) { return h.valid(); }));
    m.build_ms = tracer.build_ms();
    m.trace_ms = median_of(m.trace_ms_runs);
    m.mrays_per_s = m.trace_ms > 0 ? static_cast<double>(rays.size()) / (m.trace_ms * 1e3) : 0.0;
    for (const AccelInfo& info : tracer.infos()) {
        m.accel_bytes += info.bytes;
        m.nodes += info.nodes;
        m.leaves += info.leaves;
        m.max_depth = std::max(m.max_depth, info.max_depth);
        m.sah_cost += info.sah_cost;
    }
    m.bytes_per_prim = tracer.primitive_count() > 0
                           ? static_cast<double>(m.accel_bytes) / tracer.primitive_count()
                           : 0.0;
    if (opt.leaf_time && !opt.any_hit) {
        m.traverse_ms = median_of(timed_runs(opt.repeat, [&] { tracer.traverse(rays, hits); }));
    }
    if (opt.stats) {
        // A separate pass, so counting never perturbs the timing above.
        TraversalStats st;
        if (opt.any_hit) {
            tracer.occluded(rays, blockers, &st);
        } else {
            std::vector<Hit> again(rays.size());
            tracer.intersect(rays, again, &st);
        }
        const double n = rays.empty() ? 1.0 : static_cast<double>(rays.size());
        m.has_stats = true;
        m.nodes_per_ray = static_cast<double>(st.nodes) / n;
        m.prims_per_ray = static_cast<double>(st.prims) / n;
        const CostParams p = cost_params(tracer.accel_spec());
        m.measured_cost = measured_cost(p, m.nodes_per_ray, m.prims_per_ray);
        for (const auto& [expected, epo] : tracer.cost_figures(p, opt.epo)) {
            m.cost_model += expected.cost(p);
            m.epo = std::max(m.epo, epo);
        }
    }
    if (hits_out != nullptr) {
        *hits_out = std::move(hits);
    }
    return m;
}

}  // namespace rtlab
