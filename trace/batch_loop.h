#pragma once
// The batch loop of SceneTracer (internal to trace/): sinks, the closest and any-hit queries and
// trace_batch, included only by the trace/batch_*.cpp files. Each of those instantiates one
// (query, sink) pair over every primitive set and structure type, so the instantiations spread
// over several translation units (one held ~6 GB and >13 CPU-minutes in release).

#include "trace/batch.h"
#include "trace/wide_soa.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <type_traits>

namespace rtlab::batch {

// Rays per TBB task: large enough to amortise scheduling, small enough to balance 2..64 cores.
constexpr std::size_t grain = 256;

// Runs f(set, accel, robust-tag) with every type static: once per set per batch.
template <class F>
void visit_set(const AnyPrimSet& set, bool robust, F&& f) {
    std::visit(
        [&](const auto& s) {
            visit_accel(s.accel, [&](const auto& acc) {
                if (robust) {
                    f(s, acc, std::true_type{});
                } else {
                    f(s, acc, std::false_type{});
                }
            });
        },
        set);
}

// Stats sinks of the batch loop: local() is taken once per TBB range, local[i] is what ray i's
// traversal counts into, finish() runs after the last set.

// No counting: traversal compiles without counter updates.
struct NoSink {
    struct Local {
        NoStats none;
        NoStats& operator[](std::size_t) { return none; }
    };
    Local local() { return {}; }
    void finish() {}
};

// One TraversalStats per thread, all added to *out at the end.
struct BatchSink {
    TraversalStats* out;
    tbb::enumerable_thread_specific<TraversalStats> counts{};
    struct Local {
        TraversalStats& thread;
        TraversalStats& operator[](std::size_t) { return thread; }
    };
    Local local() { return {counts.local()}; }
    void finish() {
        for (const TraversalStats& c : counts) {
            *out += c;
        }
    }
};

// Each ray's own counts, per_ray[i] for rays[i].
struct PerRaySink {
    std::span<TraversalStats> per_ray;
    struct Local {
        std::span<TraversalStats> per_ray;
        TraversalStats& operator[](std::size_t i) { return per_ray[i]; }
    };
    Local local() { return {per_ray}; }
    void finish() {}
};

// True when set s of method M on structure A is traced leaf by leaf with M's SIMD leaf kernel.
template <class M, class A>
bool uses_leaf_kernel(const PrimSet<M>& s, const A&) {
    if constexpr (has_leaf_kernel<M> && LeafRangeAccel<A>) {
        return s.soa.size() != 0;
    } else {
        return false;
    }
}

// True when set s is traced leaf by leaf over its slot-ordered primitives (slot_prims).
template <class M, class A>
bool uses_slot_prims(const PrimSet<M>& s, const A&) {
    if constexpr (!has_leaf_kernel<M> && LeafRangeAccel<A>) {
        return !s.slot_prims.empty();
    } else {
        return false;
    }
}

// True when M is the watertight method (leaf kernels on the vertices layout).
template <class M>
inline constexpr bool is_watertight = std::is_same_v<M, Watertight<float>>;

// The watertight per-ray set-up the leaf kernels take: rd itself for watertight, else none.
template <class M>
const WatertightRay<float>* ray_data_ptr(const RayDataOf<M>& rd) {
    if constexpr (is_watertight<M>) {
        return &rd;
    } else {
        return nullptr;
    }
}

// True when M's leaf kernel is the sphere one (SphereStable<float>).
template <class M>
inline constexpr bool is_sphere_soa = std::is_same_v<LeafSoa<M>, SphereSoA>;

// The leaf kernel of M (MollerTrumbore, Watertight or SphereStable) on slots [first,
// first + count).
template <class M>
std::optional<SlotHit> leaf_closest(const LeafSoa<M>& q,
                                    std::uint32_t first,
                                    std::uint32_t count,
                                    Rayf& ray,
                                    const RayDataOf<M>& rd) {
    if constexpr (is_sphere_soa<M>) {
        return sphere_soa_closest(q, first, count, ray, rd);
    } else if constexpr (is_watertight<M>) {
        return soa_closest_watertight(q, first, count, ray, rd);
    } else {
        return soa_closest_mt(q, first, count, ray);
    }
}

template <class M>
std::optional<std::uint32_t> leaf_any(const LeafSoa<M>& q,
                                      std::uint32_t first,
                                      std::uint32_t count,
                                      const Rayf& ray,
                                      const RayDataOf<M>& rd) {
    if constexpr (is_sphere_soa<M>) {
        return sphere_soa_any(q, first, count, ray, rd);
    } else if constexpr (is_watertight<M>) {
        return soa_any_watertight(q, first, count, ray, rd);
    } else {
        return soa_any_mt(q, first, count, ray);
    }
}

// M's leaf kernel inlined into wide BVH traversal (trace/wide_soa.h): the closest hit's slot and
// hit (IsAnyHit false) or any hit's slot.
template <bool IsAnyHit, bool IsRobust, class M, unsigned N, class R, class Stats>
SoaFound<IsAnyHit> wide_leaf_trace(
    const WideBvh<N>& bvh, const LeafSoa<M>& q, R& ray, const RayDataOf<M>& rd, Stats& stats) {
    if constexpr (is_sphere_soa<M>) {
        return wide_sphere_trace<IsAnyHit, IsRobust>(bvh, q, ray, rd, stats);
    } else {
        return wide_soa_trace<IsAnyHit, IsRobust, is_watertight<M>>(bvh, q, ray,
                                                                    ray_data_ptr<M>(rd), stats);
    }
}

// Closest hit: each set starts from the nearest hit of the sets before it. The method's per-ray
// set-up runs once per ray and set, before traversal. Sets with slot-ordered leaf data test whole
// leaves (ids looked up only for the reported hit); on wide BVHs the leaf kernel is inlined into
// traversal (trace/wide_soa.h).
struct ClosestQuery {
    std::span<const Rayf> rays;
    std::span<Hit> hits;

    template <class M>
    static constexpr bool accepts = IntersectionMethod<M>;

    template <bool IsRobust, class M, class A, class Stats>
    void trace(const PrimSet<M>& s, const A& acc, std::size_t i, Stats& stats) const {
        Rayf ray = rays[i];
        ray.tmax = std::min(ray.tmax, hits[i].t);
        const RayDataOf<M> rd = precompute_ray<M>(ray);
        if constexpr (has_leaf_kernel<M> && LeafRangeAccel<A>) {
            if (uses_leaf_kernel(s, acc)) {
                if constexpr (is_wide_bvh<A>) {
                    const auto h = wide_leaf_trace<false, IsRobust, M>(acc, s.soa, ray, rd, stats);
                    if (h) {
                        hits[i] = {h->hit.t, h->hit.u, h->hit.v, s.soa.id(h->slot)};
                    }
                    return;
                }
                SlotHit best{};
                const auto leaf = [&](std::uint32_t first, std::uint32_t count, Rayf& rr) {
                    const auto h = leaf_closest<M>(s.soa, first, count, rr, rd);
                    if (h) {
                        best = *h;
                    }
                    return h.has_value();
                };
                if (acc.template intersect_leaves<IsRobust>(ray, leaf, stats)) {
                    hits[i] = {best.hit.t, best.hit.u, best.hit.v, s.soa.id(best.slot)};
                }
                return;
            }
        }
        std::uint32_t best = invalid_id;
        PrimHit<float> best_hit{};
        if constexpr (LeafRangeAccel<A>) {
            if (uses_slot_prims(s, acc)) {
                const auto leaf = [&](std::uint32_t first, std::uint32_t count, Rayf& rr) {
                    bool found = false;
                    for (std::uint32_t k = first; k < first + count; ++k) {
                        if (const auto h = intersect_with<M>(s.slot_prims[k], rr, rd)) {
                            rr.tmax = h->t;
                            best = k;
                            best_hit = *h;
                            found = true;
                        }
                    }
                    return found;
                };
                if (acc.template intersect_leaves<IsRobust>(ray, leaf, stats)) {
                    hits[i] = {best_hit.t, best_hit.u, best_hit.v, s.slot_ids[best]};
                }
                return;
            }
        }
        const auto leaf = [&, rd](std::uint32_t id, Rayf& rr) {
            const auto h = intersect_with<M>(s.prims[id], rr, rd);
            if (!h) {
                return false;
            }
            rr.tmax = h->t;
            best = id;
            best_hit = *h;
            return true;
        };
        if (acc.template intersect<IsRobust>(ray, leaf, stats)) {
            hits[i] = {best_hit.t, best_hit.u, best_hit.v, s.ids[best]};
        }
    }
};

// Any hit: rays an earlier set already blocks are skipped. Per-ray set-up as ClosestQuery.
struct AnyHitQuery {
    std::span<const Rayf> rays;
    std::span<std::uint32_t> blocker;

    template <class M>
    static constexpr bool accepts = true;

    template <bool IsRobust, class M, class A, class Stats>
    void trace(const PrimSet<M>& s, const A& acc, std::size_t i, Stats& stats) const {
        if (blocker[i] != invalid_id) {
            return;
        }
        const RayDataOf<M> rd = precompute_ray<M>(rays[i]);
        if constexpr (has_leaf_kernel<M> && LeafRangeAccel<A>) {
            if (uses_leaf_kernel(s, acc)) {
                if constexpr (is_wide_bvh<A>) {
                    const auto h =
                        wide_leaf_trace<true, IsRobust, M>(acc, s.soa, rays[i], rd, stats);
                    if (h) {
                        blocker[i] = s.soa.id(*h);
                    }
                    return;
                }
                std::uint32_t slot = 0;
                const auto leaf = [&](std::uint32_t first, std::uint32_t count, const Rayf& rr) {
                    const auto h = leaf_any<M>(s.soa, first, count, rr, rd);
                    slot = h.value_or(0);
                    return h.has_value();
                };
                if (acc.template occluded_leaves<IsRobust>(rays[i], leaf, stats)) {
                    blocker[i] = s.soa.id(slot);
                }
                return;
            }
        }
        std::uint32_t found = invalid_id;
        if constexpr (LeafRangeAccel<A>) {
            if (uses_slot_prims(s, acc)) {
                const auto leaf = [&](std::uint32_t first, std::uint32_t count, const Rayf& rr) {
                    for (std::uint32_t k = first; k < first + count; ++k) {
                        if (occluded_with<M>(s.slot_prims[k], rr, rd)) {
                            found = k;
                            return true;
                        }
                    }
                    return false;
                };
                if (acc.template occluded_leaves<IsRobust>(rays[i], leaf, stats)) {
                    blocker[i] = s.slot_ids[found];
                }
                return;
            }
        }
        const auto leaf = [&, rd](std::uint32_t id, const Rayf& rr) {
            if (!occluded_with<M>(s.prims[id], rr, rd)) {
                return false;
            }
            found = id;
            return true;
        };
        if (acc.template occluded<IsRobust>(rays[i], leaf, stats)) {
            blocker[i] = s.ids[found];
        }
    }
};

// The one batch loop: every set in order (its method and structure static), its rays in
// parallel. Each ray is independent, so results do not depend on the thread count.
template <class Query, class Sink>
void trace_batch(const std::vector<AnyPrimSet>& sets, bool robust, const Query& query, Sink& sink) {
    for (const AnyPrimSet& set : sets) {
        visit_set(set, robust, [&](const auto& s, const auto& acc, auto is_robust) {
            using M = typename std::decay_t<decltype(s)>::Method;
            if constexpr (!Query::template accepts<M>) {
                throw std::invalid_argument(std::string(M::name) +
                                            " answers hit/no-hit only: trace with --any-hit");
            } else {
                tbb::parallel_for(tbb::blocked_range<std::size_t>(0, query.rays.size(), grain),
                                  [&](const tbb::blocked_range<std::size_t>& r) {
                                      auto local = sink.local();
                                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                          query.template trace<decltype(is_robust)::value>(
                                              s, acc, i, local[i]);
                                      }
                                  });
            }
        });
    }
    sink.finish();
}

}  // namespace rtlab::batch
