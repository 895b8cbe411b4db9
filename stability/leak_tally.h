#pragma once
// Counting and classifying the leaks of one triangle method through one structure: a ray that
// hits nothing is a leak; a leak is the traversal's fault when the method alone (no boxes) hits a
// triangle that the exact ray meets, since conservative traversal must offer every such triangle.

#include "crosscheck/exact.h"
#include "stability/case_util.h"

#include <cstddef>
#include <string>
#include <vector>

namespace rtlab::stab {

/// Leaks of one (method, structure, traversal) subject, classified per ray.
struct LeakTally {
    std::size_t leaks = 0;  ///< rays that hit nothing
    /// Leaks for which the method alone hits a triangle that the exact ray meets: the traversal
    /// never offered it (a defect under robust traversal).
    std::size_t lost = 0;
    /// Leaks for which the method alone hits only triangles the exact ray misses (its rounding
    /// reports a point just outside): traversal may cull them, robust or not.
    std::size_t outside = 0;
};

/// What method M finds alone, testing every triangle of a mesh without boxes.
struct MethodAlone {
    bool any = false;    ///< it hits some triangle
    bool exact = false;  ///< it hits one that the exact ray (its float values taken as exact)
                         ///< meets within the ray's window
};

/// One pass of method M over every triangle of `mesh` (no boxes); stops at the first hit the
/// exact ray confirms.
template <class M>
MethodAlone method_alone(const TriangleMesh& mesh, const Rayf& ray) {
    const RayDataOf<M> data = precompute_ray<M>(ray);
    MethodAlone out;
    for (std::size_t i = 0; i < mesh.triangle_count(); ++i) {
        const auto c = mesh.corners(i);
        if (!occluded_with<M>(M::prepare({c[0], c[1], c[2]}), ray, data)) {
            continue;
        }
        out.any = true;
        const Triangled exact{Vec3d(c[0]), Vec3d(c[1]), Vec3d(c[2])};
        if (xcheck::exact_triangle_hit(exact, static_cast<Rayd>(ray)).hit) {
            out.exact = true;
            break;
        }
    }
    return out;
}

/// Classifies the leaks among `hits` (one per ray of `rays`, traced through some structure with
/// method M over `mesh`) and adds them to `tally`.
template <class M>
void tally_leaks(const TriangleMesh& mesh,
                 const std::vector<Rayf>& rays,
                 const std::vector<Hit>& hits,
                 LeakTally& tally) {
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (hits[i].valid()) {
            continue;
        }
        ++tally.leaks;
        const MethodAlone alone = method_alone<M>(mesh, rays[i]);
        if (alone.exact) {
            ++tally.lost;
        } else if (alone.any) {
            ++tally.outside;
        }
    }
}

/// The note of a leak row, and whether it is a defect (rays lost by robust traversal).
inline std::string leak_note(const LeakTally& t, bool robust) {
    std::string note;
    const auto add = [&note](const std::string& s) { note += (note.empty() ? "" : "; ") + s; };
    const std::size_t own = t.leaks - t.lost - t.outside;
    if (own > 0) {
        add(std::to_string(own) +
            " the method leaks by itself (rounding at shared edges and "
            "vertices)");
    }
    if (t.outside > 0) {
        add(std::to_string(t.outside) +
            " the method hits only outside the exact triangle (a point a rounding off its edge), "
            "which traversal may cull");
    }
    if (t.lost > 0) {
        add(std::to_string(t.lost) +
            (robust ? " lost by robust traversal: the method hits a triangle the exact ray meets, "
                      "never offered (a bug)"
                    : " lost by the plain slab test: it rounds a box the exact ray touches to a "
                      "miss (robust traversal pads it)"));
    }
    return note;
}

}  // namespace rtlab::stab
