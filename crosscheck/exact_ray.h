#pragma once
// The traced float ray as CGAL sees it in the cross-checks' exact oracles: two exact points of
// the lazy exact kernel (Epeck), so every predicate and construction on them is exact for the ray
// actually traced.

#include "intersect/ray.h"
#include "intersect/vec.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

namespace rtlab::xcheck {

/// The traced ray as two exact points: P1 = org and P2 = org + dir. P2 is summed exactly: the
/// double sum of the floats is exact only while no component of dir is below 2^-29 of org's, and
/// the denormal directions of the checks' axis sets would otherwise be judged as zero components.
struct ExactRay {
    using K = CGAL::Exact_predicates_exact_constructions_kernel;
    K::Point_3 p1, p2;
    explicit ExactRay(const Rayf& r) {
        const Vec3d o(r.org), d(r.dir);
        p1 = K::Point_3(o.x, o.y, o.z);
        p2 = p1 + K::Vector_3(d.x, d.y, d.z);
    }
};

}  // namespace rtlab::xcheck
