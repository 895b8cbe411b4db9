// SceneTracer: one structure per non-empty primitive set; the batch loops live in
// trace/batch_*.cpp.
#include "trace/scene_tracer.h"

#include "trace/batch.h"
#include "trace/batch_loop.h"
#include "trace/clip.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <type_traits>

namespace rtlab {

namespace {

template <class M>
AnyPrimSet make_set(const std::vector<typename M::Shape>& shapes,
                    std::vector<std::uint32_t> ids,
                    const AccelSpec& accel,
                    bool leaf_slots,
                    const ClipFn& clip,
                    const ExtentFn& extent,
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
    set.accel = build_accel(accel, BuildInput{bounds, clip, extent});
    build_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    visit_accel(set.accel, [&](const auto& a) {
        if constexpr (LeafRangeAccel<std::decay_t<decltype(a)>>) {
            if (leaf_slots) {
                set.soa = LeafKernel<M>::make(set.prims, a.prim_ids, set.ids);
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
    bool leaf_slots;  ///< keep slot-ordered leaf data where the structure offers whole leaves
    std::vector<AnyPrimSet>& sets;
    std::vector<std::string>& labels;
    double& build_ms;

    // Adds shapes (global ids `ids`) unless empty; clip enables kd-tree perfect splits, extent
    // the wide BVHs' exact diagonal slabs.
    template <class Shape>
    void operator()(const std::vector<Shape>& shapes,
                    std::vector<std::uint32_t> ids,
                    const ClipFn& clip = {},
                    const ExtentFn& extent = {}) {
        if (shapes.empty()) {
            return;
        }
        using Family = FamilyOf<Shape>;
        const std::string_view m = pick_method(family(Family::name), setup.methods);
        const bool found = with_method_named<Shape>(m, [&]<class M>() {
            sets.push_back(
                make_set<M>(shapes, std::move(ids), accel, leaf_slots, clip, extent, build_ms));
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

/// Exact extents for shape types with a shape_extent overload (trace/clip.h); the others'
/// structures take their boxes'.
template <class S>
ExtentFn extent_for(const std::vector<S>& shapes) {
    if constexpr (requires(const S& s, const Vec3f& d) { shape_extent(s, d); }) {
        return [&shapes](std::uint32_t i, const Vec3f& d) { return shape_extent(shapes[i], d); };
    } else {
        return {};
    }
}

/// Walks acc for ray r offering its leaves to a callback that tests nothing (whole leaves where
/// the structure offers them, as the leaf kernels take them).
template <bool IsRobust, class A>
bool walk_only(const A& acc, Rayf& r) {
    if constexpr (LeafRangeAccel<A>) {
        return acc.template intersect_leaves<IsRobust>(
            r, [](std::uint32_t, std::uint32_t, Rayf&) { return false; });
    } else {
        return acc.template intersect<IsRobust>(r, [](std::uint32_t, Rayf&) { return false; });
    }
}

}  // namespace

SceneTracer::SceneTracer(const Scene& scene, const TraceSetup& setup)
    : accel_spec_(setup.accel), robust_(setup.robust) {
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
    if constexpr (requires { std::get<ShapeBucket<Trianglef>>(buckets.all); }) {
        triangles_ = std::get<ShapeBucket<Trianglef>>(buckets.all).shapes;
    }
    const bool slots = slot_ordered_leaves(accel_spec_) && !setup.exact;
    SetAdder add{setup, accel_spec_, slots, sets_, set_methods_, build_ms_};
    std::apply(
        [&](auto&... b) {
            (add(b.shapes, std::move(b.ids), clip_for(b.shapes), extent_for(b.shapes)), ...);
        },
        buckets.all);
    if (setup.exact) {
        enter_exact(setup);
    }
}

void SceneTracer::enter_exact(const TraceSetup& setup) {
    if (!setup.methods.empty()) {
        throw std::invalid_argument(
            "exact mode tests triangles with the certified test only: a method (" +
            setup.methods.front() + ") would have no effect");
    }
    for (const std::string& label : set_methods_) {
        if (!label.starts_with("triangle=")) {
            throw std::invalid_argument(
                "exact mode certifies triangle hits only, and the scene holds " +
                label.substr(0, label.find('=')) + " primitives");
        }
    }
    // Every registered structure's robust traversal offers every triangle an exact ray touches
    // (tests/exact_query_test.cpp checks each against CGAL), so none is refused.
    exact_ = true;
    robust_ = true;
    if (slot_ordered_leaves(accel_spec_) && !sets_.empty()) {
        const auto [tris, a] = exact_set();
        exact_slots_ = exact_slots(*a, tris.tris, tris.ids);
    }
    for (std::string& label : set_methods_) {
        label = "triangle=exact";
    }
}

std::pair<ExactTriangles, const AnyAccel*> SceneTracer::exact_set() const {
    if (sets_.empty()) {
        return {ExactTriangles{}, nullptr};
    }
    return std::visit(
        [&](const auto& set) {
            return std::pair{
                ExactTriangles{triangles_, set.ids, exact_slots_.first, exact_slots_.second},
                &set.accel};
        },
        sets_.front());
}

ExactCounts SceneTracer::exact_counts(std::span<const Rayf> rays, bool any_hit) const {
    if (!exact_) {
        throw std::logic_error("exact_counts: not in exact mode");
    }
    ExactCounts c;
    const auto [tris, a] = exact_set();
    if (a == nullptr) {
        c.rays = rays.size();
        return c;
    }
    if (any_hit) {
        std::vector<std::uint32_t> blocker(rays.size(), invalid_id);
        exact_any(*a, tris, rays, blocker, nullptr, &c);
    } else {
        std::vector<Hit> hits(rays.size());
        exact_closest(*a, tris, rays, hits, nullptr, &c);
    }
    return c;
}

std::vector<std::pair<CostEstimate, double>> SceneTracer::cost_figures(const CostParams& p,
                                                                       bool with_epo) const {
    std::vector<std::pair<CostEstimate, double>> out;
    for (std::size_t i = 0; i < sets_.size(); ++i) {
        const AnyAccel& a =
            std::visit([](const auto& set) -> const AnyAccel& { return set.accel; }, sets_[i]);
        const bool triangles = set_methods_[i].starts_with("triangle=");
        const double epo = with_epo && triangles && has_end_point_overlap(a)
                               ? end_point_overlap(a, triangles_, p)
                               : -1.0;
        out.emplace_back(expected_cost(a), epo);
    }
    return out;
}

std::vector<AccelInfo> SceneTracer::infos() const {
    std::vector<AccelInfo> out;
    for (const AnyPrimSet& s : sets_) {
        out.push_back(std::visit([](const auto& set) { return accel_info(set.accel); }, s));
    }
    return out;
}

std::size_t SceneTracer::leaf_bytes() const {
    if (exact_) {
        // The triangles the certified test reads, in slot order where kept so, with their ids.
        const std::size_t slots = exact_slots_.first.size();
        const std::size_t n = slots > 0 ? slots : triangles_.size();
        return n * (sizeof(Trianglef) + sizeof(std::uint32_t));
    }
    std::size_t total = 0;
    for (const AnyPrimSet& s : sets_) {
        total += std::visit(
            [](const auto& set) -> std::size_t {
                if (set.soa.size() > 0) {
                    return set.soa.bytes();
                }
                return set.prims.size() * sizeof(set.prims[0]) +
                       set.ids.size() * sizeof(std::uint32_t);
            },
            s);
    }
    return total;
}

void SceneTracer::intersect(std::span<const Rayf> rays,
                            std::span<Hit> hits,
                            TraversalStats* stats) const {
    if (hits.size() != rays.size()) {
        throw std::invalid_argument("intersect: hits and rays differ in size");
    }
    std::fill(hits.begin(), hits.end(), Hit{});
    if (exact_) {
        if (const auto [tris, a] = exact_set(); a != nullptr) {
            exact_closest(*a, tris, rays, hits, stats);
        }
    } else if (stats != nullptr) {
        batch::closest_counted(sets_, robust_, rays, hits, *stats);
    } else {
        batch::closest(sets_, robust_, rays, hits);
    }
}

void SceneTracer::intersect_counted(std::span<const Rayf> rays,
                                    std::span<Hit> hits,
                                    std::span<TraversalStats> per_ray) const {
    if (hits.size() != rays.size() || per_ray.size() != rays.size()) {
        throw std::invalid_argument("intersect_counted: hits, counts and rays differ in size");
    }
    if (exact_) {
        throw std::invalid_argument("per-ray counts are not available in exact mode");
    }
    std::fill(hits.begin(), hits.end(), Hit{});
    batch::closest_per_ray(sets_, robust_, rays, hits, per_ray);
}

void SceneTracer::traverse(std::span<const Rayf> rays, std::span<const Hit> hits) const {
    if (hits.size() != rays.size()) {
        throw std::invalid_argument("traverse: hits and rays differ in size");
    }
    std::atomic<std::size_t> reported{0};  // keeps the walks (their leaves never report a hit)
    for (const AnyPrimSet& s : sets_) {
        const AnyAccel& a =
            std::visit([](const auto& set) -> const AnyAccel& { return set.accel; }, s);
        visit_accel(a, [&](const auto& acc) {
            const auto body = [&](std::size_t begin, std::size_t end) {
                std::size_t n = 0;
                for (std::size_t i = begin; i != end; ++i) {
                    Rayf r = rays[i];
                    r.tmax = std::min(r.tmax, hits[i].t);
                    n += robust_ ? walk_only<true>(acc, r) : walk_only<false>(acc, r);
                }
                reported += n;
            };
            batch::parallel_blocks(rays.size(), body);
        });
    }
}

void SceneTracer::occluded(std::span<const Rayf> rays,
                           std::span<std::uint32_t> blocker,
                           TraversalStats* stats) const {
    if (blocker.size() != rays.size()) {
        throw std::invalid_argument("occluded: blockers and rays differ in size");
    }
    std::fill(blocker.begin(), blocker.end(), invalid_id);
    if (exact_) {
        if (const auto [tris, a] = exact_set(); a != nullptr) {
            exact_any(*a, tris, rays, blocker, stats);
        }
    } else if (stats != nullptr) {
        batch::any_counted(sets_, robust_, rays, blocker, *stats);
    } else {
        batch::any(sets_, robust_, rays, blocker);
    }
}

}  // namespace rtlab
