// The registry table: one row per structure and builder configuration.

#include "accel/any_accel.h"

#include <stdexcept>

namespace rtlab {

namespace {

/// Build function of a Bvh row with builder B and otherwise default settings.
template <BvhBuilder B>
AnyAccel build_bvh_row(const BuildInput& in) {
    Bvh::Config cfg;
    cfg.builder = B;
    return Bvh::build(in, cfg);
}

/// Build function of a KdTree row with builder B and otherwise default settings.
template <KdBuilder B>
AnyAccel build_kdtree_row(const BuildInput& in) {
    KdTree::Config cfg;
    cfg.builder = B;
    return KdTree::build(in, cfg);
}

AnyAccel build_grid_row(const BuildInput& in) {
    return Grid::build(in);
}

AnyAccel build_brute_row(const BuildInput& in) {
    return BruteForce::build(in);
}

const AccelEntry registry_rows[] = {
    {"brute", "brute force: every primitive box per ray (the reference)", &build_brute_row},
    {"bvh:median", "binary BVH, object median on the largest centroid axis",
     &build_bvh_row<BvhBuilder::median>},
    {"bvh:binned", "binary BVH, binned SAH with 16 bins (Wald 2007)",
     &build_bvh_row<BvhBuilder::binned_sah>},
    {"bvh:sweep", "binary BVH, full-sweep SAH (MacDonald & Booth 1990)",
     &build_bvh_row<BvhBuilder::sweep_sah>},
    {"bvh:lbvh", "binary BVH, Morton-code radix tree (Karras 2012)",
     &build_bvh_row<BvhBuilder::lbvh>},
    {"kdtree:sah", "kd-tree, O(N log N) SAH event sweep (Wald & Havran 2006)",
     &build_kdtree_row<KdBuilder::sah>},
    {"kdtree:median", "kd-tree, spatial median of the longest axis, SAH termination",
     &build_kdtree_row<KdBuilder::median>},
    {"grid:uniform", "uniform grid, Woo resolution (4 cells/prim), 3D-DDA (Amanatides & Woo 1987)",
     &build_grid_row},
};

}  // namespace

std::span<const AccelEntry> accel_registry() {
    return registry_rows;
}

const AccelEntry* find_accel(std::string_view name) {
    for (const AccelEntry& e : registry_rows) {
        if (e.name == name) {
            return &e;
        }
    }
    return nullptr;
}

AnyAccel build_accel(std::string_view name, const BuildInput& in) {
    if (const AccelEntry* e = find_accel(name)) {
        return e->build(in);
    }
    std::string known;
    for (const AccelEntry& e : registry_rows) {
        known += known.empty() ? "" : ", ";
        known += e.name;
    }
    throw std::invalid_argument("unknown acceleration structure '" + std::string(name) +
                                "' (known: " + known + ")");
}

AccelInfo accel_info(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) { return s.info(); });
}

std::string accel_validate(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) { return s.validate(); });
}

Bounds3f accel_bounds(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) { return s.bounds(); });
}

}  // namespace rtlab
