// Reading the planes of every structure kind (stability/structure_planes.h).
#include "stability/structure_planes.h"

#include "accel/cost_model.h"

#include <type_traits>

namespace rtlab::stab {

namespace {

/// The plane x[axis] == pos over `box`.
StructurePlane face_of(const Bounds3f& box, std::uint32_t axis, float pos) {
    StructurePlane p;
    p.axis = axis;
    p.pos = pos;
    p.face = box;
    p.face.lo[axis] = pos;
    p.face.hi[axis] = pos;
    return p;
}

/// The six faces of a non-empty box.
void add_box_faces(const Bounds3f& box, std::vector<StructurePlane>& out) {
    if (box.empty()) {
        return;
    }
    for (std::uint32_t a = 0; a < 3; ++a) {
        out.push_back(face_of(box, a, box.lo[a]));
        out.push_back(face_of(box, a, box.hi[a]));
    }
}

/// A grid frame's cell boundaries, computed as the 3D-DDA computes them (accel/grid/dda.h).
void add_grid_planes(const GridFrame& g, std::vector<StructurePlane>& out) {
    for (std::uint32_t a = 0; a < 3; ++a) {
        for (std::uint32_t i = 0; i <= g.res[a]; ++i) {
            out.push_back(face_of(g.box, a, g.box.lo[a] + static_cast<float>(i) * g.cell_size[a]));
        }
    }
}

/// A kd-tree's split planes, each clipped to its node's cell.
void add_kd_planes(const KdTree& kd, std::vector<StructurePlane>& out) {
    if (kd.nodes.empty()) {
        return;
    }
    std::vector<std::pair<std::uint32_t, Bounds3f>> todo{{0u, kd.scene_bounds}};
    while (!todo.empty()) {
        const auto [index, cell] = todo.back();
        todo.pop_back();
        const KdNode& n = kd.nodes[index];
        if (n.is_leaf()) {
            continue;
        }
        const std::uint32_t a = n.axis();
        out.push_back(face_of(cell, a, n.split()));
        Bounds3f below = cell, above = cell;
        below.hi[a] = n.split();
        above.lo[a] = n.split();
        todo.emplace_back(index + 1, below);
        todo.emplace_back(n.above_child(), above);
    }
}

}  // namespace

std::vector<StructurePlane> structure_planes(const AnyAccel& a) {
    std::vector<StructurePlane> out;
    visit_accel(a, [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, KdTree>) {
            add_kd_planes(s, out);
        } else if constexpr (std::is_same_v<T, Grid>) {
            add_grid_planes(s, out);
        } else if constexpr (std::is_same_v<T, TwoLevelGrid>) {
            add_grid_planes(s.top, out);
            for (const SubGrid& sub : s.subs) {
                add_grid_planes(sub.frame, out);
            }
        } else {
            add_box_faces(s.bounds(), out);
        }
    });
    for (const Bounds3f& box : bvh_node_boxes(a)) {
        add_box_faces(box, out);
    }
    return out;
}

}  // namespace rtlab::stab
