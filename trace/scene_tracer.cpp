// SceneTracer: one structure per non-empty primitive set; batches visit (method, structure) once.
#include "trace/scene_tracer.h"

#include "trace/clip.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <type_traits>

namespace rtlab {

namespace {

// Rays per TBB task: large enough to amortise scheduling, small enough to balance 2..64 cores.
constexpr std::size_t grain = 256;

template <class M>
AnyPrimSet make_set(const std::vector<typename M::Shape>& shapes,
                    std::vector<std::uint32_t> ids,
                    const AccelSpec& accel,
                    const ClipFn& clip,
                    double& build_ms) {
    PrimSet<M> set;
    set.prims.reserve(shapes.size());
    std::vector<Bounds3f> bounds;
    bounds.reserve(shapes.size());
    for (const typename M::Shape& s : shapes) {
        set.prims.push_back(M::prepare(s));
        bounds.push_back(M::bounds(set.prims.back()));
    }
    set.ids = std::move(ids);
    const auto t0 = std::chrono::steady_clock::now();
    set.accel = build_accel(accel, BuildInput{bounds, clip});
    build_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    visit_accel(set.accel, [&](const auto& a) {
        if constexpr (LeafRangeAccel<std::decay_t<decltype(a)>>) {
            if (!a.soa_leaves) {
                return;
            }
            if constexpr (soa_layout_of<M>.has_value()) {
                set.soa = make_triangle_soa(set.prims, a.prim_ids, *soa_layout_of<M>, set.ids);
            } else {
                set.slot_prims.reserve(a.prim_ids.size());
                set.slot_ids.reserve(a.prim_ids.size());
                for (const std::uint32_t id : a.prim_ids) {
                    set.slot_prims.push_back(set.prims[id]);
                    set.slot_ids.push_back(set.ids[id]);
                }
            }
        }
    });
    return set;
}

std::string_view pick_method(const MethodFamily& fam, const std::vector<std::string>& wanted) {
    for (const std::string& w : wanted) {
        for (std::string_view m : fam.methods) {
            if (m == w) {
                return m;
            }
        }
    }
    return fam.methods.front();
}

const MethodFamily& family(std::string_view name) {
    for (const MethodFamily& f : method_families()) {
        if (f.family == name) {
            return f;
        }
    }
    throw std::logic_error("no method family " + std::string(name));
}

// Appends one prepared set per non-empty shape group, with the method the setup names for the
// group's family (the family's default when it names none), and its "family=method" label.
struct SetAdder {
    const TraceSetup& setup;
    const AccelSpec& accel;
    std::vector<AnyPrimSet>& sets;
    std::vector<std::string>& labels;
    double& build_ms;

    // Adds shapes (global ids `ids`) unless empty; clip enables kd-tree perfect splits.
    template <class Shape>
    void operator()(const std::vector<Shape>& shapes,
                    std::vector<std::uint32_t> ids,
                    const ClipFn& clip = {}) {
        if (shapes.empty()) {
            return;
        }
        using Family = FamilyOf<Shape>;
        const std::string_view m = pick_method(family(Family::name), setup.methods);
        const bool found = with_method_named<Shape>(m, [&]<class M>() {
            sets.push_back(make_set<M>(shapes, std::move(ids), accel, clip, build_ms));
        });
        if (!found) {
            throw std::invalid_argument("internal: method " + std::string(m) + " not in its set");
        }
        labels.push_back(std::string(Family::name) + "=" + std::string(m));
    }
};

/// The shapes of one type gathered from a scene, with their global primitive ids.
template <class S>
struct ShapeBucket {
    std::vector<S> shapes;
    std::vector<std::uint32_t> ids;
};

template <class List>
struct ShapeBuckets;
template <class... Ss>
struct ShapeBuckets<std::tuple<Ss...>> {
    std::tuple<ShapeBucket<Ss>...> all;
};

/// kd-tree perfect splits for shape types with a clip_shape_bounds overload (trace/clip.h).
template <class S>
ClipFn clip_for(const std::vector<S>& shapes) {
    if constexpr (requires(const S& s, const Bounds3f& box) { clip_shape_bounds(s, box); }) {
        return [&shapes](std::uint32_t i, const Bounds3f& box) {
            return clip_shape_bounds(shapes[i], box);
        };
    } else {
        return {};
    }
}

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
    if constexpr (soa_layout_of<M>.has_value() && LeafRangeAccel<A>) {
        return s.soa.size() != 0;
    } else {
        return false;
    }
}

// True when set s is traced leaf by leaf over its slot-ordered primitives (slot_prims).
template <class M, class A>
bool uses_slot_prims(const PrimSet<M>& s, const A&) {
    if constexpr (!soa_layout_of<M>.has_value() && LeafRangeAccel<A>) {
        return !s.slot_prims.empty();
    } else {
        return false;
    }
}

// The leaf kernel of M (MollerTrumbore or Watertight) on slots [first, first + count).
template <class M>
std::optional<SlotHit> leaf_closest(const TriangleSoA& q,
                                    std::uint32_t first,
                                    std::uint32_t count,
                                    Rayf& ray,
                                    const RayDataOf<M>& rd) {
    if constexpr (std::is_same_v<M, Watertight<float>>) {
        return soa_closest_watertight(q, first, count, ray, rd);
    } else {
        return soa_closest_mt(q, first, count, ray);
    }
}

template <class M>
std::optional<std::uint32_t> leaf_any(const TriangleSoA& q,
                                      std::uint32_t first,
                                      std::uint32_t count,
                                      const Rayf& ray,
                                      const RayDataOf<M>& rd) {
    if constexpr (std::is_same_v<M, Watertight<float>>) {
        return soa_any_watertight(q, first, count, ray, rd);
    } else {
        return soa_any_mt(q, first, count, ray);
    }
}

// Closest hit: each set starts from the nearest hit of the sets before it. The method's per-ray
// set-up runs once per ray and set, before traversal. Sets with slot-ordered leaf data test whole
// leaves (ids looked up only for the reported hit).
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
        if constexpr (soa_layout_of<M>.has_value() && LeafRangeAccel<A>) {
            if (uses_leaf_kernel(s, acc)) {
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
        if constexpr (soa_layout_of<M>.has_value() && LeafRangeAccel<A>) {
            if (uses_leaf_kernel(s, acc)) {
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

// trace_batch counting per thread into *stats when given, else without counters.
template <class Query>
void trace_maybe_counted(const std::vector<AnyPrimSet>& sets,
                         bool robust,
                         const Query& query,
                         TraversalStats* stats) {
    if (stats != nullptr) {
        BatchSink sink{stats};
        trace_batch(sets, robust, query, sink);
    } else {
        NoSink sink;
        trace_batch(sets, robust, query, sink);
    }
}

}  // namespace

SceneTracer::SceneTracer(const Scene& scene, const TraceSetup& setup) : robust_(setup.robust) {
    const AccelSpec accel = parse_accel_spec(setup.accel);  // throws on a bad spec
    accel_spec_ = accel.canonical();
    for (const std::string& w : setup.methods) {
        bool known = false;
        for (const MethodFamily& f : method_families()) {
            known = known || std::find(f.methods.begin(), f.methods.end(), w) != f.methods.end();
        }
        if (!known) {
            std::string list;
            for (const MethodFamily& f : method_families()) {
                for (std::string_view m : f.methods) {
                    list += (list.empty() ? "" : ", ") + std::string(m);
                }
            }
            throw std::invalid_argument("unknown method '" + w + "' (known: " + list + ")");
        }
    }

    const std::vector<std::uint32_t> base = primitive_id_base(scene);
    prim_count_ = base.back();
    // One bucket per traced shape type; each object's table entry emits its world shapes into
    // the bucket of their type, and each non-empty bucket becomes a set, in table order.
    ShapeBuckets<TracedShapes> buckets;
    const auto gather = [&buckets]<class S>(S shape, std::uint32_t id) {
        auto& b = std::get<ShapeBucket<S>>(buckets.all);
        b.shapes.push_back(std::move(shape));
        b.ids.push_back(id);
    };
    for (std::size_t k = 0; k < scene.order.size(); ++k) {
        const ObjectRef r = scene.order[k];
        const std::uint32_t id = base[k];
        visit_object(scene, r, [&]<class P>(const auto& o) { P::shapes(o, id, gather); });
    }
    SetAdder add{setup, accel, sets_, set_methods_, build_ms_};
    std::apply([&](auto&... b) { (add(b.shapes, std::move(b.ids), clip_for(b.shapes)), ...); },
               buckets.all);
}

std::vector<AccelInfo> SceneTracer::infos() const {
    std::vector<AccelInfo> out;
    for (const AnyPrimSet& s : sets_) {
        out.push_back(std::visit([](const auto& set) { return accel_info(set.accel); }, s));
    }
    return out;
}

void SceneTracer::intersect(std::span<const Rayf> rays,
                            std::span<Hit> hits,
                            TraversalStats* stats) const {
    if (hits.size() != rays.size()) {
        throw std::invalid_argument("intersect: hits and rays differ in size");
    }
    std::fill(hits.begin(), hits.end(), Hit{});
    trace_maybe_counted(sets_, robust_, ClosestQuery{rays, hits}, stats);
}

void SceneTracer::intersect_counted(std::span<const Rayf> rays,
                                    std::span<Hit> hits,
                                    std::span<TraversalStats> per_ray) const {
    if (hits.size() != rays.size() || per_ray.size() != rays.size()) {
        throw std::invalid_argument("intersect_counted: hits, counts and rays differ in size");
    }
    std::fill(hits.begin(), hits.end(), Hit{});
    PerRaySink sink{per_ray};
    trace_batch(sets_, robust_, ClosestQuery{rays, hits}, sink);
}

void SceneTracer::occluded(std::span<const Rayf> rays,
                           std::span<std::uint32_t> blocker,
                           TraversalStats* stats) const {
    if (blocker.size() != rays.size()) {
        throw std::invalid_argument("occluded: blockers and rays differ in size");
    }
    std::fill(blocker.begin(), blocker.end(), invalid_id);
    trace_maybe_counted(sets_, robust_, AnyHitQuery{rays, blocker}, stats);
}

}  // namespace rtlab
