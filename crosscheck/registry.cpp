// The table of primitive kinds that `rtlab crosscheck --prim` accepts.
#include "crosscheck/checks.h"

#include <array>

namespace rtlab::xcheck {

namespace {
const std::array<PrimCheck, 7> checks{{
    {"triangle", triangle_methods, check_triangles},
    {"polygon", polygon_methods, check_polygons},
    {"aabb", aabb_methods, check_aabbs},
    {"obb", obb_methods, check_obbs},
    {"sphere", sphere_methods, check_spheres},
    {"implicit", implicit_methods, check_implicits},
    {"cone", cone_methods, check_cones},
}};
}  // namespace

std::span<const PrimCheck> prim_checks() {
    return checks;
}

const PrimCheck* find_prim_check(std::string_view prim) {
    for (const PrimCheck& c : checks) {
        if (c.prim == prim) {
            return &c;
        }
    }
    return nullptr;
}

}  // namespace rtlab::xcheck
