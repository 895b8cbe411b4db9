// The exact query mode (trace/exact_query.h): certified tests in a structure's robust traversal.
#include "trace/exact_query.h"

#include "intersect/triangle/exact_hit.h"

#include <cmath>
#include <limits>
#include <mutex>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rtlab {

namespace {

/// Rays the certified test takes (exact_hit.h's preconditions); others miss.
bool usable(const Rayf& r) {
    return is_finite(r.org) && is_finite(r.dir) && !std::isnan(r.tmin) && !std::isnan(r.tmax);
}

/// One ray's test counts.
struct RayCounts {
    std::uint64_t tests = 0;
    std::uint64_t fallbacks = 0;
};

/// Whether acc's slab tests see ray's line: a direction component that is neither zero nor normal
/// has a reciprocal that overflows, and a slab test then takes the ray as parallel to that axis
/// although it crosses the plane of a face its origin is within a denormal distance of.
bool boxes_see(const Rayf& r) {
    for (std::size_t k = 0; k < 3; ++k) {
        if (r.dir[k] != 0.0f && std::abs(r.dir[k]) < std::numeric_limits<float>::min()) {
            return false;
        }
    }
    return true;
}

/// Offers test(triangle, id, walk) every triangle acc's robust traversal offers for ray: from the
/// slot arrays where q has them, else by structure id; every triangle where the structure's boxes
/// cannot see the ray (boxes_see). walk is ray with the window test shrinks (closest hit); for
/// any hit the first true ends the walk.
template <bool AnyHit, class A, class S, class Test>
void offer(const A& acc, const ExactTriangles& q, const Rayf& ray, S& stats, Test& test) {
    Rayf walk = ray;
    const auto by_id = [&](std::uint32_t i, const Rayf&) {
        return test(q.tris[i], q.ids[i], walk);
    };
    if (!boxes_see(ray)) {
        for (std::uint32_t i = 0; i < q.tris.size(); ++i) {
            if (by_id(i, walk) && AnyHit) {
                return;
            }
        }
        return;
    }
    if constexpr (LeafRangeAccel<A>) {
        if (!q.slot_tris.empty()) {
            const auto leaf = [&](std::uint32_t first, std::uint32_t count, const Rayf&) {
                bool hit = false;
                for (std::uint32_t s = first; s < first + count; ++s) {
                    hit = test(q.slot_tris[s], q.slot_ids[s], walk) || hit;
                    if (hit && AnyHit) {
                        return true;
                    }
                }
                return hit;
            };
            if constexpr (AnyHit) {
                acc.template occluded_leaves<true>(ray, leaf, stats);
            } else {
                acc.template intersect_leaves<true>(walk, leaf, stats);
            }
            return;
        }
    }
    if constexpr (AnyHit) {
        acc.template occluded<true>(ray, by_id, stats);
    } else {
        acc.template intersect<true>(walk, by_id, stats);
    }
}

/// The certified closest hit of ray through acc (see the file comment of exact_query.h).
template <class A, class S>
Hit closest_one(const A& acc, const ExactTriangles& q, const Rayf& ray, S& stats, RayCounts& c) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    ExactHit best;
    const Trianglef* best_tri = nullptr;
    std::uint32_t best_id = invalid_id;
    const auto test = [&](const Trianglef& t, std::uint32_t id, Rayf& walk) {
        // Against walk's window, which ends one float past the best hit: a triangle beyond it
        // cannot tie or beat the best, so its t is not certified for nothing.
        const ExactHit h = exact_intersect(walk, t.p0, t.p1, t.p2);
        ++c.tests;
        c.fallbacks += h.fallback ? 1 : 0;
        if (!h.hit || id == best_id) {
            return false;  // a miss, or the best triangle again (referenced from another leaf)
        }
        if (best_tri != nullptr && h.t >= best.t) {
            // Rounding is monotone: only equal floats need the exact order (and the id rule).
            if (h.t > best.t) {
                return false;
            }
            ++c.fallbacks;
            if (!exact_less(ray, h, t, id, best, *best_tri, best_id)) {
                return false;
            }
        }
        best = h;
        best_tri = &t;
        best_id = id;
        // One float past the rounded t: a triangle whose exact t ties or beats best's lies below.
        walk.tmax = std::min(ray.tmax, std::nextafter(h.t, inf));
        return true;
    };
    offer<false>(acc, q, ray, stats, test);
    Hit out;
    if (best_tri != nullptr) {
        out.t = best.t;
        out.u = best.u;
        out.v = best.v;
        out.prim = best_id;
    }
    return out;
}

/// The global id of a triangle ray's window exactly meets, or invalid_id.
template <class A, class S>
std::uint32_t any_one(
    const A& acc, const ExactTriangles& q, const Rayf& ray, S& stats, RayCounts& c) {
    std::uint32_t found = invalid_id;
    const auto test = [&](const Trianglef& t, std::uint32_t id, const Rayf&) {
        const ExactHit h = exact_intersect(ray, t.p0, t.p1, t.p2);
        ++c.tests;
        c.fallbacks += h.fallback ? 1 : 0;
        if (h.hit) {
            found = id;
        }
        return h.hit;
    };
    offer<true>(acc, q, ray, stats, test);
    return found;
}

/// Runs one(acc, ray, stats, counts) -> result for every usable ray in parallel into out, adding
/// the counts to *stats and *counts.
template <class Out, class One>
void for_rays(const AnyAccel& a,
              std::span<const Rayf> rays,
              std::span<Out> out,
              TraversalStats* stats,
              ExactCounts* counts,
              const One& one) {
    std::mutex merge;
    visit_accel(a, [&](const auto& acc) {
        const auto block = [&](const tbb::blocked_range<std::size_t>& r) {
            TraversalStats st;
            ExactCounts ec;
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                if (!usable(rays[i])) {
                    continue;
                }
                RayCounts c;
                if (stats != nullptr) {
                    out[i] = one(acc, rays[i], st, c);
                } else {
                    NoStats none;
                    out[i] = one(acc, rays[i], none, c);
                }
                ec.rays += 1;
                ec.tests += c.tests;
                ec.fallbacks += c.fallbacks;
                ec.fallback_rays += c.fallbacks > 0 ? 1 : 0;
            }
            const std::lock_guard lock(merge);
            if (stats != nullptr) {
                *stats += st;
            }
            if (counts != nullptr) {
                *counts += ec;
            }
        };
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), block);
    });
}

}  // namespace

std::pair<std::vector<Trianglef>, std::vector<std::uint32_t>> exact_slots(
    const AnyAccel& a, std::span<const Trianglef> tris, std::span<const std::uint32_t> ids) {
    std::pair<std::vector<Trianglef>, std::vector<std::uint32_t>> out;
    visit_accel(a, [&](const auto& acc) {
        if constexpr (LeafRangeAccel<std::decay_t<decltype(acc)>>) {
            for (const std::uint32_t slot : acc.prim_ids) {
                const std::uint32_t i = slot == padding_slot ? acc.prim_ids.front() : slot;
                out.first.push_back(tris[i]);
                out.second.push_back(ids[i]);
            }
        }
    });
    return out;
}

void exact_closest(const AnyAccel& a,
                   const ExactTriangles& q,
                   std::span<const Rayf> rays,
                   std::span<Hit> hits,
                   TraversalStats* stats,
                   ExactCounts* counts) {
    const auto one = [&q](const auto& acc, const Rayf& ray, auto& st, RayCounts& c) {
        return closest_one(acc, q, ray, st, c);
    };
    for_rays(a, rays, hits, stats, counts, one);
}

void exact_any(const AnyAccel& a,
               const ExactTriangles& q,
               std::span<const Rayf> rays,
               std::span<std::uint32_t> blocker,
               TraversalStats* stats,
               ExactCounts* counts) {
    const auto one = [&q](const auto& acc, const Rayf& ray, auto& st, RayCounts& c) {
        return any_one(acc, q, ray, st, c);
    };
    for_rays(a, rays, blocker, stats, counts, one);
}

}  // namespace rtlab
