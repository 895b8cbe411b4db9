// SceneTracer: one structure per non-empty primitive set; batches visit (method, structure) once.
#include "trace/scene_tracer.h"

#include "trace/clip.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace rtlab {

namespace {

// Rays per TBB task: large enough to amortise scheduling, small enough to balance 2..64 cores.
constexpr std::size_t grain = 256;

template <class M>
AnyPrimSet make_set(std::vector<typename M::Shape> shapes,
                    std::vector<std::uint32_t> ids,
                    const std::string& accel,
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
    return set;
}

// Picks the method named for `family` in `wanted` (or the family's default) and builds the set
// with the method type at position I of Ms whose name matches.
template <class... Ms>
AnyPrimSet make_named_set(
    std::string_view method,
    std::vector<typename std::tuple_element_t<0, std::tuple<Ms...>>::Shape> shapes,
    std::vector<std::uint32_t> ids,
    const std::string& accel,
    const ClipFn& clip,
    double& build_ms) {
    AnyPrimSet out;
    bool found = false;
    (
        [&] {
            if (!found && Ms::name == method) {
                out = make_set<Ms>(std::move(shapes), std::move(ids), accel, clip, build_ms);
                found = true;
            }
        }(),
        ...);
    if (!found) {
        throw std::invalid_argument("internal: method " + std::string(method) + " not in its set");
    }
    return out;
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

// Runs body(range, sink) over [0, n) in parallel; sink is a per-thread TraversalStats when
// counting, else NoStats, so the uncounted path compiles without any counter updates.
template <class Body>
void parallel_rays(std::size_t n,
                   tbb::enumerable_thread_specific<TraversalStats>* counts,
                   const Body& body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          if (counts != nullptr) {
                              body(r, counts->local());
                          } else {
                              NoStats none;
                              body(r, none);
                          }
                      });
}

void add_counts(const tbb::enumerable_thread_specific<TraversalStats>& counts,
                TraversalStats* stats) {
    if (stats != nullptr) {
        for (const TraversalStats& c : counts) {
            *stats += c;
        }
    }
}

}  // namespace

const std::vector<MethodFamily>& method_families() {
    static const std::vector<MethodFamily> families{
        {"triangle", {"moller_trumbore", "badouel", "segura_feito", "watertight"}},
        {"sphere", {"stable", "geometric", "algebraic"}},
        {"polygon", {"crossing_count", "winding_number"}},
        {"box", {"slabs", "slabs_robust"}},
        {"obb", {"obb_slabs"}},
        {"implicit", {"closed_form", "newton", "laguerre"}},
    };
    return families;
}

SceneTracer::SceneTracer(const Scene& scene, const TraceSetup& setup) : robust_(setup.robust) {
    if (find_accel(setup.accel) == nullptr) {
        build_accel(setup.accel, BuildInput{});  // throws the message listing known names
    }
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
    std::vector<Triangle<float>> tris;
    std::vector<std::uint32_t> tri_ids;
    std::vector<Sphere<float>> spheres;
    std::vector<std::uint32_t> sphere_ids;
    std::vector<Polygon<float>> polys;
    std::vector<std::uint32_t> poly_ids;
    std::vector<Bounds3f> boxes;
    std::vector<std::uint32_t> box_ids;
    std::vector<Obb<float>> obbs;
    std::vector<std::uint32_t> obb_ids;
    std::vector<Torus<float>> tori;
    std::vector<std::uint32_t> torus_ids;
    std::vector<TangleCube<float>> tangles;
    std::vector<std::uint32_t> tangle_ids;
    // Each object's table entry emits its world shapes; the overload for the shape type keeps it.
    const Overloaded gather{[&](const Triangle<float>& t, std::uint32_t i) {
                                tris.push_back(t);
                                tri_ids.push_back(i);
                            },
                            [&](const Sphere<float>& t, std::uint32_t i) {
                                spheres.push_back(t);
                                sphere_ids.push_back(i);
                            },
                            [&](Polygon<float> t, std::uint32_t i) {
                                polys.push_back(std::move(t));
                                poly_ids.push_back(i);
                            },
                            [&](const Bounds3f& t, std::uint32_t i) {
                                boxes.push_back(t);
                                box_ids.push_back(i);
                            },
                            [&](const Obb<float>& t, std::uint32_t i) {
                                obbs.push_back(t);
                                obb_ids.push_back(i);
                            },
                            [&](const Torus<float>& t, std::uint32_t i) {
                                tori.push_back(t);
                                torus_ids.push_back(i);
                            },
                            [&](const TangleCube<float>& t, std::uint32_t i) {
                                tangles.push_back(t);
                                tangle_ids.push_back(i);
                            }};
    for (std::size_t k = 0; k < scene.order.size(); ++k) {
        const ObjectRef r = scene.order[k];
        const std::uint32_t id = base[k];
        visit_object(scene, r, [&]<class P>(const auto& o) { P::shapes(o, id, gather); });
    }

    const auto add = [&](std::string_view fam, AnyPrimSet set, std::string_view method) {
        sets_.push_back(std::move(set));
        set_methods_.push_back(std::string(fam) + "=" + std::string(method));
    };
    const std::string& acc = setup.accel;
    if (!tris.empty()) {
        const std::string_view m = pick_method(family("triangle"), setup.methods);
        // Perfect splits for kd-trees: the triangle clipped to the node box.
        const ClipFn clip = [&tris](std::uint32_t i, const Bounds3f& box) {
            return clip_triangle_bounds(tris[i].p0, tris[i].p1, tris[i].p2, box);
        };
        add("triangle",
            make_named_set<MollerTrumbore<float>, Badouel<float>, SeguraFeito<float>,
                           Watertight<float>>(m, tris, std::move(tri_ids), acc, clip, build_ms_),
            m);
    }
    if (!spheres.empty()) {
        const std::string_view m = pick_method(family("sphere"), setup.methods);
        add("sphere",
            make_named_set<SphereStable<float>, SphereGeometric<float>, SphereAlgebraic<float>>(
                m, std::move(spheres), std::move(sphere_ids), acc, {}, build_ms_),
            m);
    }
    if (!polys.empty()) {
        const std::string_view m = pick_method(family("polygon"), setup.methods);
        add("polygon",
            make_named_set<PolygonCrossing<float>, PolygonWinding<float>>(
                m, std::move(polys), std::move(poly_ids), acc, {}, build_ms_),
            m);
    }
    if (!boxes.empty()) {
        const std::string_view m = pick_method(family("box"), setup.methods);
        add("box",
            make_named_set<AabbSlabs<float>, AabbSlabsRobust<float>>(
                m, std::move(boxes), std::move(box_ids), acc, {}, build_ms_),
            m);
    }
    if (!obbs.empty()) {
        const std::string_view m = pick_method(family("obb"), setup.methods);
        add("obb",
            make_named_set<ObbSlabs<float>>(m, std::move(obbs), std::move(obb_ids), acc, {},
                                            build_ms_),
            m);
    }
    if (!tori.empty()) {
        const std::string_view m = pick_method(family("implicit"), setup.methods);
        add("implicit",
            make_named_set<ImplicitClosedForm<Torus, float>, ImplicitNewton<Torus, float>,
                           ImplicitLaguerre<Torus, float>>(m, std::move(tori), std::move(torus_ids),
                                                           acc, {}, build_ms_),
            m);
    }
    if (!tangles.empty()) {
        const std::string_view m = pick_method(family("implicit"), setup.methods);
        add("implicit",
            make_named_set<ImplicitClosedForm<TangleCube, float>, ImplicitNewton<TangleCube, float>,
                           ImplicitLaguerre<TangleCube, float>>(
                m, std::move(tangles), std::move(tangle_ids), acc, {}, build_ms_),
            m);
    }
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
    tbb::enumerable_thread_specific<TraversalStats> counts;
    for (const AnyPrimSet& set : sets_) {
        visit_set(set, robust_, [&](const auto& s, const auto& acc, auto robust) {
            using M = typename std::decay_t<decltype(s)>::Method;
            if constexpr (!IntersectionMethod<M>) {
                throw std::invalid_argument(std::string(M::name) +
                                            " answers hit/no-hit only: trace with --any-hit");
            } else {
                const auto trace_range = [&](const tbb::blocked_range<std::size_t>& r, auto& sink) {
                    for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        Rayf ray = rays[i];
                        ray.tmax = std::min(ray.tmax, hits[i].t);
                        std::uint32_t best = invalid_id;
                        PrimHit<float> best_hit{};
                        const auto leaf = [&](std::uint32_t id, Rayf& rr) {
                            const auto h = M::intersect(s.prims[id], rr);
                            if (!h) {
                                return false;
                            }
                            rr.tmax = h->t;
                            best = id;
                            best_hit = *h;
                            return true;
                        };
                        if (acc.template intersect<decltype(robust)::value>(ray, leaf, sink)) {
                            hits[i] = {best_hit.t, best_hit.u, best_hit.v, s.ids[best]};
                        }
                    }
                };
                parallel_rays(rays.size(), stats != nullptr ? &counts : nullptr, trace_range);
            }
        });
    }
    add_counts(counts, stats);
}

void SceneTracer::intersect_counted(std::span<const Rayf> rays,
                                    std::span<Hit> hits,
                                    std::span<TraversalStats> per_ray) const {
    if (hits.size() != rays.size() || per_ray.size() != rays.size()) {
        throw std::invalid_argument("intersect_counted: hits, counts and rays differ in size");
    }
    std::fill(hits.begin(), hits.end(), Hit{});
    for (const AnyPrimSet& set : sets_) {
        visit_set(set, robust_, [&](const auto& s, const auto& acc, auto robust) {
            using M = typename std::decay_t<decltype(s)>::Method;
            if constexpr (!IntersectionMethod<M>) {
                throw std::invalid_argument(std::string(M::name) +
                                            " answers hit/no-hit only: trace with --any-hit");
            } else {
                const auto trace_range = [&](const tbb::blocked_range<std::size_t>& r, auto&) {
                    for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        Rayf ray = rays[i];
                        ray.tmax = std::min(ray.tmax, hits[i].t);
                        std::uint32_t best = invalid_id;
                        PrimHit<float> best_hit{};
                        const auto leaf = [&](std::uint32_t id, Rayf& rr) {
                            const auto h = M::intersect(s.prims[id], rr);
                            if (!h) {
                                return false;
                            }
                            rr.tmax = h->t;
                            best = id;
                            best_hit = *h;
                            return true;
                        };
                        TraversalStats& sink = per_ray[i];
                        if (acc.template intersect<decltype(robust)::value>(ray, leaf, sink)) {
                            hits[i] = {best_hit.t, best_hit.u, best_hit.v, s.ids[best]};
                        }
                    }
                };
                parallel_rays(rays.size(), nullptr, trace_range);
            }
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
    tbb::enumerable_thread_specific<TraversalStats> counts;
    for (const AnyPrimSet& set : sets_) {
        visit_set(set, robust_, [&](const auto& s, const auto& acc, auto robust) {
            using M = typename std::decay_t<decltype(s)>::Method;
            const auto trace_range = [&](const tbb::blocked_range<std::size_t>& r, auto& sink) {
                for (std::size_t i = r.begin(); i != r.end(); ++i) {
                    if (blocker[i] != invalid_id) {
                        continue;
                    }
                    std::uint32_t found = invalid_id;
                    const auto leaf = [&](std::uint32_t id, const Rayf& rr) {
                        if (!M::occluded(s.prims[id], rr)) {
                            return false;
                        }
                        found = id;
                        return true;
                    };
                    if (acc.template occluded<decltype(robust)::value>(rays[i], leaf, sink)) {
                        blocker[i] = s.ids[found];
                    }
                }
            };
            parallel_rays(rays.size(), stats != nullptr ? &counts : nullptr, trace_range);
        });
    }
    add_counts(counts, stats);
}

}  // namespace rtlab
