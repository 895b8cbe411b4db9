// The one cost model (accel/cost_model.h) and the end-point overlap of BVHs. Every BVH layout is
// first flattened into one node list (accel/flat_bvh.h: box, children or leaf slots), so the model
// and EPO are written once for binary, pair, wide and any later BVH layout.

#include "accel/cost_model.h"

#include "accel/flat_bvh.h"

#include <array>
#include <cmath>
#include <concepts>
#include <functional>
#include <span>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <vector>

namespace rtlab {

namespace {

/// Surface-area probabilities relative to one root box (1 when the root has no area).
struct AreaRatio {
    double root;
    explicit AreaRatio(const Bounds3f& b) : root(static_cast<double>(b.surface_area())) {}
    double operator()(const Bounds3f& b) const {
        return root > 0 ? static_cast<double>(b.surface_area()) / root : 1.0;
    }
};

FlatBvh flatten(const Bvh& b) {
    FlatBvh f;
    f.prim_ids = b.prim_ids;
    if (b.nodes.empty()) {
        return f;
    }
    // Flat index i is Bvh node i: children are appended as their parent is reached.
    f.nodes.resize(b.nodes.size());
    for (std::size_t i = 0; i < b.nodes.size(); ++i) {
        const BvhNode& n = b.nodes[i];
        FlatNode& out = f.nodes[i];
        out.box = n.bounds();
        if (n.is_leaf()) {
            out.first = n.first;
            out.count = n.prim_count();
        } else {
            out.kid_first = static_cast<std::uint32_t>(f.kids.size());
            f.kids.push_back(n.first);
            f.kids.push_back(n.first + 1);
            out.kid_end = static_cast<std::uint32_t>(f.kids.size());
        }
    }
    return f;
}

FlatBvh flatten(const PairBvh& b) {
    FlatBvh f;
    f.prim_ids = b.prim_ids;
    if (b.prim_ids.empty()) {
        return f;
    }
    if (b.root_count > 0) {
        f.add(b.root_box, b.root_child, b.root_count);
        return f;
    }
    // (pair node index, flat index) of the inner nodes still to expand.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> todo{{0, f.add(b.root_box, 0, 0)}};
    while (!todo.empty()) {
        const auto [pi, fi] = todo.back();
        todo.pop_back();
        const PairNode& n = b.nodes[pi];
        std::array<std::uint32_t, 2> kid{};
        for (int c = 0; c < 2; ++c) {
            kid[c] = f.add(n.child_bounds(c), n.count_of(c) > 0 ? n.child[c] : 0, n.count_of(c));
            if (n.count_of(c) == 0) {
                todo.emplace_back(n.child[c], kid[c]);
            }
        }
        f.nodes[fi].kid_first = static_cast<std::uint32_t>(f.kids.size());
        f.kids.insert(f.kids.end(), kid.begin(), kid.end());
        f.nodes[fi].kid_end = static_cast<std::uint32_t>(f.kids.size());
    }
    return f;
}

template <unsigned N>
FlatBvh flatten(const WideBvh<N>& b) {
    FlatBvh f;
    f.prim_ids = b.prim_ids;
    f.counts_child_tests = false;
    if (b.nodes.empty()) {
        return f;
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> todo{{0, f.add(b.bounds(), 0, 0)}};
    while (!todo.empty()) {
        const auto [wi, fi] = todo.back();
        todo.pop_back();
        const WideNode<N>& n = b.nodes[wi];
        std::vector<std::uint32_t> kid;
        for (unsigned i = 0; i < N; ++i) {
            if (!n.occupied(i)) {
                continue;
            }
            kid.push_back(f.add(n.bounds(i), n.is_leaf(i) ? n.child[i] : 0, n.count[i]));
            if (!n.is_leaf(i)) {
                todo.emplace_back(n.child[i], kid.back());
            }
        }
        f.nodes[fi].kid_first = static_cast<std::uint32_t>(f.kids.size());
        f.kids.insert(f.kids.end(), kid.begin(), kid.end());
        f.nodes[fi].kid_end = static_cast<std::uint32_t>(f.kids.size());
    }
    return f;
}

/// True for a BVH layout: one that offers flatten (here, or beside its type for a layout added
/// later, found by argument-dependent lookup).
template <class T>
concept Flattens = requires(const T& s) {
    { flatten(s) } -> std::same_as<FlatBvh>;
};

CostEstimate flat_cost(const FlatBvh& f) {
    CostEstimate e;
    if (f.nodes.empty()) {
        return e;
    }
    const AreaRatio p(f.nodes[0].box);
    e.nodes = 1;  // the root is entered (binary: its box is tested) by every ray
    for (std::size_t i = 0; i < f.nodes.size(); ++i) {
        const FlatNode& n = f.nodes[i];
        if (n.leaf()) {
            e.prims += p(n.box) * n.count;
        } else if (f.counts_child_tests) {
            e.nodes += p(n.box) * (n.kid_end - n.kid_first);
        } else if (i != 0) {
            e.nodes += p(n.box);
        }
    }
    return e;
}

/// Area of the part of triangle t inside box b (Sutherland & Hodgman 1974 clipping, in double).
double clipped_area(const Trianglef& t, const Bounds3f& b) {
    using V = Vec3<double>;
    const auto d = [](const Vec3f& v) { return V{v.x, v.y, v.z}; };
    std::array<V, 9> poly{d(t.p0), d(t.p1), d(t.p2)}, next{};
    std::size_t n = 3;
    for (std::size_t axis = 0; axis < 3 && n > 0; ++axis) {
        for (int side = 0; side < 2 && n > 0; ++side) {
            const double plane = side == 0 ? b.lo[axis] : b.hi[axis];
            const auto inside = [&](const V& v) {
                return side == 0 ? v[axis] >= plane : v[axis] <= plane;
            };
            std::size_t m = 0;
            for (std::size_t i = 0; i < n; ++i) {
                const V& a = poly[i];
                const V& c = poly[(i + 1) % n];
                if (inside(a)) {
                    next[m++] = a;
                }
                if (inside(a) != inside(c) && m < next.size()) {
                    const double s = (plane - a[axis]) / (c[axis] - a[axis]);
                    next[m++] = a + (c - a) * s;
                }
            }
            poly = next;
            n = m;
        }
    }
    V sum{0, 0, 0};
    for (std::size_t i = 1; i + 1 < n; ++i) {
        sum = sum + cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
    }
    return 0.5 * length(sum);
}

bool overlaps(const Bounds3f& a, const Bounds3f& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
           a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

double flat_epo(const FlatBvh& f, std::span<const Trianglef> triangles, const CostParams& p) {
    if (f.nodes.empty()) {
        return 0;
    }
    const auto area = [&](std::uint32_t id) {
        const Trianglef& t = triangles[id];
        return 0.5 * static_cast<double>(length(cross(t.p1 - t.p0, t.p2 - t.p0)));
    };
    double total = 0;
    for (const std::uint32_t id : f.prim_ids) {
        if (id != padding_slot) {
            total += area(id);
        }
    }
    if (!(total > 0)) {
        return 0;
    }
    // Node n's overlap: the surface of the leaves outside n's subtree clipped to box(n); the
    // query walks from the root and never enters n itself.
    const auto node_overlap = [&](std::uint32_t target) {
        const Bounds3f& box = f.nodes[target].box;
        double a = 0;
        std::vector<std::uint32_t> stack{0};
        while (!stack.empty()) {
            const std::uint32_t m = stack.back();
            stack.pop_back();
            const FlatNode& n = f.nodes[m];
            if (m == target || !overlaps(n.box, box)) {
                continue;
            }
            if (n.leaf()) {
                for (std::uint32_t s = n.first; s < n.first + n.count; ++s) {
                    a += clipped_area(triangles[f.prim_ids[s]], box);
                }
            } else {
                stack.insert(stack.end(), f.kids.begin() + n.kid_first, f.kids.begin() + n.kid_end);
            }
        }
        const FlatNode& t = f.nodes[target];
        return (t.leaf() ? p.ci * t.count : p.ct) * a;
    };
    const double sum = tbb::parallel_reduce(
        tbb::blocked_range<std::uint32_t>(1, static_cast<std::uint32_t>(f.nodes.size()), 64), 0.0,
        [&](const tbb::blocked_range<std::uint32_t>& r, double acc) {
            for (std::uint32_t i = r.begin(); i != r.end(); ++i) {
                acc += node_overlap(i);
            }
            return acc;
        },
        std::plus<>{});
    return sum / total;
}

/// Adds the cells of frame g (P(cell) each) to e.nodes, and records in span[id] the box of
/// the cells listing primitive id (cell lists start[c], start[c + 1] of prims).
void add_grid_cells(const GridFrame& g,
                    const AreaRatio& p,
                    const std::uint32_t* start,
                    std::span<const std::uint32_t> prims,
                    std::vector<Bounds3f>& span,
                    CostEstimate& e) {
    e.nodes += static_cast<double>(g.cell_count()) * p(Bounds3f(g.box.lo, g.box.lo + g.cell_size));
    for (std::uint32_t z = 0; z < g.res[2]; ++z) {
        for (std::uint32_t y = 0; y < g.res[1]; ++y) {
            for (std::uint32_t x = 0; x < g.res[0]; ++x) {
                const std::size_t c = g.index(x, y, z);
                if (start[c] == start[c + 1]) {
                    continue;
                }
                const Vec3f lo = g.box.lo + Vec3f{static_cast<float>(x) * g.cell_size.x,
                                                  static_cast<float>(y) * g.cell_size.y,
                                                  static_cast<float>(z) * g.cell_size.z};
                const Bounds3f cell(lo, lo + g.cell_size);
                for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
                    span[prims[k]].extend(cell);
                }
            }
        }
    }
}

/// E[prims] of a grid with a perfect mailbox: a primitive is tested once when the line meets
/// any of its cells, i.e. (for cells forming a box) the box its cells span.
double grid_prims(const std::vector<Bounds3f>& span, const AreaRatio& p) {
    double sum = 0;
    for (const Bounds3f& b : span) {
        if (is_usable_box(b)) {
            sum += p(b);
        }
    }
    return sum;
}

}  // namespace

CostEstimate expected_cost(const BruteForce& a) {
    CostEstimate e;
    Bounds3f root;
    for (const Bounds3f& b : a.boxes) {
        if (is_usable_box(b)) {
            root.extend(b);
        }
    }
    const AreaRatio p(root);
    for (const Bounds3f& b : a.boxes) {
        e.nodes += 1;
        e.prims += is_usable_box(b) ? p(b) : 0.0;
    }
    return e;
}

// The kd-tree's cells follow from the scene box and the splits on the path (pre-order nodes, the
// below child right after its parent). Kept to the public node layout only.
CostEstimate expected_cost(const KdTree& a) {
    CostEstimate e;
    if (a.nodes.empty()) {
        return e;
    }
    const AreaRatio p(a.scene_bounds);
    std::vector<std::pair<std::uint32_t, Bounds3f>> stack{{0, a.scene_bounds}};
    while (!stack.empty()) {
        const auto [i, cell] = stack.back();
        stack.pop_back();
        const KdNode& n = a.nodes[i];
        e.nodes += p(cell);
        if (n.is_leaf()) {
            e.prims += p(cell) * n.prim_count();
            continue;
        }
        Bounds3f below = cell, above = cell;
        below.hi[n.axis()] = n.split();
        above.lo[n.axis()] = n.split();
        stack.emplace_back(i + 1, below);
        stack.emplace_back(n.above_child(), above);
    }
    return e;
}

CostEstimate expected_cost(const Grid& a) {
    CostEstimate e;
    if (a.cell_start.empty()) {
        return e;
    }
    const AreaRatio p(a.box);
    std::vector<Bounds3f> span(a.prim_present.size());
    add_grid_cells(a, p, a.cell_start.data(), a.cell_prims, span, e);
    e.prims = grid_prims(span, p);
    return e;
}

CostEstimate expected_cost(const TwoLevelGrid& a) {
    CostEstimate e;
    if (a.top_sub.empty()) {
        return e;
    }
    const AreaRatio p(a.top.box);
    e.nodes += static_cast<double>(a.top.cell_count()) *
               p(Bounds3f(a.top.box.lo, a.top.box.lo + a.top.cell_size));
    std::vector<Bounds3f> span(a.prim_present.size());
    for (const SubGrid& s : a.subs) {
        add_grid_cells(s.frame, p, a.cell_start.data() + s.first_cell, a.cell_prims, span, e);
    }
    e.prims = grid_prims(span, p);
    return e;
}

CostEstimate expected_cost(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) {
        if constexpr (Flattens<std::decay_t<decltype(s)>>) {
            return flat_cost(flatten(s));
        } else {
            return expected_cost(s);
        }
    });
}

bool has_end_point_overlap(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) { return Flattens<std::decay_t<decltype(s)>>; });
}

double end_point_overlap(const AnyAccel& a,
                         std::span<const Trianglef> triangles,
                         const CostParams& p) {
    return visit_accel(a, [&](const auto& s) -> double {
        if constexpr (Flattens<std::decay_t<decltype(s)>>) {
            return flat_epo(flatten(s), triangles, p);
        } else {
            return -1.0;
        }
    });
}

std::vector<Bounds3f> bvh_node_boxes(const AnyAccel& a) {
    return visit_accel(a, [&](const auto& s) {
        std::vector<Bounds3f> boxes;
        if constexpr (Flattens<std::decay_t<decltype(s)>>) {
            for (const FlatNode& n : flatten(s).nodes) {
                boxes.push_back(n.box);
            }
        }
        return boxes;
    });
}

}  // namespace rtlab
