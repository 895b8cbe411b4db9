#pragma once
// The batch loop of SceneTracer (internal to trace/): sinks, the closest and any-hit queries and
// trace_batch, included only by the trace/batch_*.cpp files. Each of those instantiates one
// (query, sink) pair over every primitive set and structure type, so the instantiations spread
// over several translation units (one held ~6 GB and >13 CPU-minutes in release).

#include "base/function_ref.h"
#include "trace/batch.h"
#include "trace/wide_soa.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <tbb/enumerable_thread_specific.h>
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

// Counting: ray i's counts into per_ray[i] when per_ray is given, else into one TraversalStats
// per thread, all added to *out at the end. One sink for both, so the counted loop of a query is
// compiled once (each instantiation of the loop over every set and structure costs minutes).
struct CountSink {
    TraversalStats* out = nullptr;
    std::span<TraversalStats> per_ray{};
    tbb::enumerable_thread_specific<TraversalStats> counts{};
    struct Local {
        TraversalStats& thread;
        std::span<TraversalStats> per_ray;
        TraversalStats& operator[](std::size_t i) { return per_ray.empty() ? thread : per_ray[i]; }
    };
    Local local() { return {counts.local(), per_ray}; }
    void finish() {
        if (out != nullptr) {
            for (const TraversalStats& c : counts) {
                *out += c;
            }
        }
    }
};

// True when set s of method M on structure A is traced leaf by leaf with M's leaf kernel
// (trace/leaf_kernel.h) over its slot-ordered leaf data.
template <class M, class A>
bool uses_leaf_kernel(const PrimSet<M>& s, const A&) {
    if constexpr (LeafRangeAccel<A>) {
        return s.soa.size() != 0;
    } else {
        return false;
    }
}

// The leaf callbacks' signatures (closest / any hit, one primitive id / a leaf's slot range).
using IdFn = bool(std::uint32_t, Rayf&);
using LeavesFn = bool(std::uint32_t, std::uint32_t, Rayf&);
using AnyIdFn = bool(std::uint32_t, const Rayf&);
using AnyLeavesFn = bool(std::uint32_t, std::uint32_t, const Rayf&);

// What a query hands a structure as its leaf callback: the lambda itself when timed (inlined), a
// FunctionRef when counted, so a counted pass compiles each structure's traversal once instead of
// once per method (the counts are the same: same traversal, same tests; counting is never timed).
template <class Stats, class Sig, class F>
decltype(auto) callback(F& f) {
    if constexpr (std::is_same_v<Stats, NoStats>) {
        return (f);
    } else {
        return FunctionRef<Sig>(f);
    }
}

// Rays [begin, end) of one TBB range as the wide BVH block traversal takes them (trace/
// wide_soa.h's RayBlock): the query reads ray i and keeps its answer, the sink's local counts.
template <class Query, class Soa, class Local>
struct QueryBlock {
    const Query& query;
    const Soa& soa;
    Local& local;
    std::size_t begin;
    std::size_t end;

    bool take(std::size_t i, Rayf& ray) const { return query.take(i, ray); }
    template <class Found>
    void put(std::size_t i, const Found& found) const {
        query.put(i, soa, found);
    }
    auto& stats(std::size_t i) { return local[i]; }
};

// The rays [begin, end) of set s on wide BVH bvh with M's leaf kernel inlined into traversal
// (trace/wide_soa.h), in one call.
template <bool IsRobust, class Query, class M, unsigned N, class Local>
void wide_leaf_block(const Query& query,
                     const PrimSet<M>& s,
                     const WideBvh<N>& bvh,
                     std::size_t begin,
                     std::size_t end,
                     Local& local) {
    QueryBlock<Query, LeafData<M>, Local> block{query, s.soa, local, begin, end};
    wide_leaf_trace_block<Query::is_any_hit, IsRobust, M>(bvh, s.soa, block);
}

// Closest hit: each set starts from the nearest hit of the sets before it. The method's per-ray
// set-up runs once per ray and set, before traversal. Sets with slot-ordered leaf data test whole
// leaves with their method's leaf kernel (ids looked up only for the reported hit). On wide BVHs
// trace_batch runs such sets' ranges through wide_leaf_block instead of trace(), with take() and
// put().
struct ClosestQuery {
    std::span<const Rayf> rays;
    std::span<Hit> hits;

    template <class M>
    static constexpr bool accepts = IntersectionMethod<M>;
    static constexpr bool is_any_hit = false;

    // Ray i with its window shrunk to the hit so far.
    bool take(std::size_t i, Rayf& ray) const {
        ray = rays[i];
        ray.tmax = std::min(ray.tmax, hits[i].t);
        return true;
    }
    // The hit of leaf-data slot h.slot becomes ray i's.
    template <class Soa>
    void put(std::size_t i, const Soa& soa, const SlotHit& h) const {
        hits[i] = {h.hit.t, h.hit.u, h.hit.v, soa.id(h.slot)};
    }

    template <bool IsRobust, class M, class A, class Stats>
    void trace(const PrimSet<M>& s, const A& acc, std::size_t i, Stats& stats) const {
        Rayf ray;
        take(i, ray);
        const RayDataOf<M> rd = precompute_ray<M>(ray);
        if constexpr (LeafRangeAccel<A>) {
            if (uses_leaf_kernel(s, acc)) {
                SlotHit best{};
                const auto leaf = [&](std::uint32_t first, std::uint32_t count, Rayf& rr) {
                    const auto h = kernel_closest<M>(s.soa, first, count, rr, rd);
                    if (h) {
                        best = *h;
                    }
                    return h.has_value();
                };
                if (acc.template intersect_leaves<IsRobust>(ray, callback<Stats, LeavesFn>(leaf),
                                                            stats)) {
                    put(i, s.soa, best);
                }
                return;
            }
        }
        std::uint32_t best = invalid_id;
        PrimHit<float> best_hit{};
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
        if (acc.template intersect<IsRobust>(ray, callback<Stats, IdFn>(leaf), stats)) {
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
    static constexpr bool is_any_hit = true;

    // Ray i, unless an earlier set blocks it.
    bool take(std::size_t i, Rayf& ray) const {
        if (blocker[i] != invalid_id) {
            return false;
        }
        ray = rays[i];
        return true;
    }
    // Leaf-data slot `slot` blocks ray i.
    template <class Soa>
    void put(std::size_t i, const Soa& soa, std::uint32_t slot) const {
        blocker[i] = soa.id(slot);
    }

    template <bool IsRobust, class M, class A, class Stats>
    void trace(const PrimSet<M>& s, const A& acc, std::size_t i, Stats& stats) const {
        if (blocker[i] != invalid_id) {
            return;
        }
        const RayDataOf<M> rd = precompute_ray<M>(rays[i]);
        if constexpr (LeafRangeAccel<A>) {
            if (uses_leaf_kernel(s, acc)) {
                std::uint32_t slot = 0;
                const auto leaf = [&](std::uint32_t first, std::uint32_t count, const Rayf& rr) {
                    const auto h = kernel_any<M>(s.soa, first, count, rr, rd);
                    slot = h.value_or(0);
                    return h.has_value();
                };
                if (acc.template occluded_leaves<IsRobust>(
                        rays[i], callback<Stats, AnyLeavesFn>(leaf), stats)) {
                    put(i, s.soa, slot);
                }
                return;
            }
        }
        std::uint32_t found = invalid_id;
        const auto leaf = [&, rd](std::uint32_t id, const Rayf& rr) {
            if (!occluded_with<M>(s.prims[id], rr, rd)) {
                return false;
            }
            found = id;
            return true;
        };
        if (acc.template occluded<IsRobust>(rays[i], callback<Stats, AnyIdFn>(leaf), stats)) {
            blocker[i] = s.ids[found];
        }
    }
};

// Rays [begin, end) of set s: in one block through the wide BVH traversal with a hand-written
// SIMD leaf kernel inlined where that applies, else ray by ray (the generic kernel is inlined
// into the ray-by-ray traversal, compiled once per method, not once per method and SIMD level).
// Counted passes take the ray-by-ray path with the same leaf kernels as callbacks (the same
// visits and counts, tests/*_soa_test.cpp): timing never counts, and the inlined kernels, once
// per SIMD level, are the bulk of a batch unit's build.
template <bool IsRobust, class Query, class M, class A, class Local>
void trace_range(const Query& query,
                 const PrimSet<M>& s,
                 const A& acc,
                 std::size_t begin,
                 std::size_t end,
                 Local& local) {
    if constexpr (LeafKernel<M>::simd && is_wide_bvh<A> && std::is_same_v<Local, NoSink::Local>) {
        if (uses_leaf_kernel(s, acc)) {
            wide_leaf_block<IsRobust>(query, s, acc, begin, end, local);
            return;
        }
    }
    for (std::size_t i = begin; i != end; ++i) {
        query.template trace<IsRobust>(s, acc, i, local[i]);
    }
}

// body(begin, end) over [0, n) in blocks of about `grain` in parallel (trace/batch_loop.cpp). Not
// a template: TBB's parallel_for is compiled once instead of once per method and structure (a
// quarter of a batch unit's code), for one indirect call per block.
void parallel_blocks(std::size_t n, FunctionRef<void(std::size_t, std::size_t)> body);

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
                const auto body = [&](std::size_t begin, std::size_t end) {
                    auto local = sink.local();
                    trace_range<decltype(is_robust)::value>(query, s, acc, begin, end, local);
                };
                parallel_blocks(query.rays.size(), body);
            }
        });
    }
    sink.finish();
}

}  // namespace rtlab::batch
