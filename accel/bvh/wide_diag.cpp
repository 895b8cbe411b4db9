// Diagonal slabs for the wide BVHs (`bounds=dop14`): each slot's extents along diag_dirs, so that
// with the slot's box it is a 14-DOP (Kay & Kajiya 1986's slabs; Klosowski et al. 1998's k-DOP
// hierarchies). Leaf slots take the union of their primitives' extents (BuildInput::extent, or the
// primitive boxes' corners), inner slots the union of their child node's slots, so every slot's
// slabs hold everything below it; the bounds are rounded outward, never cut.

#include "accel/bvh/wide_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tbb/parallel_for.h>

namespace rtlab {

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

DiagExtents empty_extents() {
    DiagExtents e;
    std::fill(std::begin(e.lo), std::end(e.lo), inf);
    std::fill(std::begin(e.hi), std::end(e.hi), -inf);
    return e;
}

void extend(DiagExtents& e, const DiagExtents& o) {
    for (unsigned k = 0; k < 4; ++k) {
        e.lo[k] = std::min(e.lo[k], o.lo[k]);
        e.hi[k] = std::max(e.hi[k], o.hi[k]);
    }
}

template <unsigned N>
DiagExtents slot_extents(const WideDiag<N>& d, unsigned i) {
    DiagExtents e;
    for (unsigned k = 0; k < 4; ++k) {
        e.lo[k] = d.lo[k][i];
        e.hi[k] = d.hi[k][i];
    }
    return e;
}

template <unsigned N>
void set_slot(WideDiag<N>& d, unsigned i, const DiagExtents& e) {
    for (unsigned k = 0; k < 4; ++k) {
        d.lo[k][i] = e.lo[k];
        d.hi[k][i] = e.hi[k];
    }
}

}  // namespace

DiagExtents diag_extents_of_box(const Bounds3f& b) {
    double mag = 0;
    for (unsigned a = 0; a < 3; ++a) {
        mag += std::max(std::abs(static_cast<double>(b.lo[a])),
                        std::abs(static_cast<double>(b.hi[a])));
    }
    DiagExtents e;
    for (unsigned k = 0; k < 4; ++k) {
        const SlabExtent s = outward_extent(diag_dot(k, diag_corner(b, k, true)),
                                            diag_dot(k, diag_corner(b, k, false)), mag);
        e.lo[k] = s.lo;
        e.hi[k] = s.hi;
    }
    return e;
}

DiagExtents diag_extents_of(const BuildInput& in, std::uint32_t id) {
    DiagExtents e;
    for (unsigned k = 0; k < 4; ++k) {
        const SlabExtent s = in.extent(id, diag_dir(k));
        e.lo[k] = s.lo;
        e.hi[k] = s.hi;
    }
    return e;
}

template <unsigned N>
void add_diag_bounds(WideBvh<N>& w, const BuildInput& in) {
    WideDiag<N> empty;
    for (unsigned i = 0; i < N; ++i) {
        set_slot(empty, i, empty_extents());
    }
    w.diags.assign(w.nodes.size(), empty);
    // Leaf slots, node by node in parallel: the primitives' extents.
    tbb::parallel_for(std::size_t{0}, w.nodes.size(), [&](std::size_t node) {
        const WideNode<N>& n = w.nodes[node];
        for (unsigned i = 0; i < N && n.occupied(i); ++i) {
            if (!n.is_leaf(i)) {
                continue;
            }
            DiagExtents e = empty_extents();
            for (std::uint32_t s = n.child[i]; s < n.child[i] + n.count[i]; ++s) {
                const std::uint32_t id = w.prim_ids[s];
                if (id != padding_slot) {
                    extend(e, in.extent ? diag_extents_of(in, id)
                                        : diag_extents_of_box(in.bounds[id]));
                }
            }
            set_slot(w.diags[node], i, e);
        }
    });
    // Inner slots, children first: the union of the child node's slots.
    const auto fill = [&](const auto& self, std::uint32_t node) -> DiagExtents {
        const WideNode<N>& n = w.nodes[node];
        DiagExtents all = empty_extents();
        for (unsigned i = 0; i < N && n.occupied(i); ++i) {
            if (!n.is_leaf(i)) {
                set_slot(w.diags[node], i, self(self, n.child[i]));
            }
            extend(all, slot_extents(w.diags[node], i));
        }
        return all;
    };
    fill(fill, 0);
}

template <unsigned N>
std::string WideBvh<N>::validate_diags() const {
    if (diags.empty()) {
        return {};
    }
    if (diags.size() != nodes.size()) {
        return std::to_string(diags.size()) + " diagonal slab sets for " +
               std::to_string(nodes.size()) + " nodes";
    }
    for (std::size_t node = 0; node < nodes.size(); ++node) {
        const WideNode<N>& n = nodes[node];
        for (unsigned i = 0; i < N; ++i) {
            const auto where = [&] {
                return "node " + std::to_string(node) + " slot " + std::to_string(i) + ": ";
            };
            const DiagExtents e = slot_extents(diags[node], i);
            for (unsigned k = 0; k < 4; ++k) {
                if (!n.occupied(i)) {
                    if (e.lo[k] != inf || e.hi[k] != -inf) {
                        return where() + "empty slot with diagonal slabs";
                    }
                } else if (!(e.lo[k] <= e.hi[k])) {
                    return where() + "empty or NaN diagonal slab";
                }
            }
            if (!n.occupied(i) || n.is_leaf(i)) {
                continue;
            }
            const WideNode<N>& c = nodes[n.child[i]];
            for (unsigned j = 0; j < N && c.occupied(j); ++j) {
                const DiagExtents ce = slot_extents(diags[n.child[i]], j);
                for (unsigned k = 0; k < 4; ++k) {
                    if (ce.lo[k] < e.lo[k] || ce.hi[k] > e.hi[k]) {
                        return where() + "a child's diagonal slab outside its parent's";
                    }
                }
            }
        }
    }
    return {};
}

template void add_diag_bounds(WideBvh<4>&, const BuildInput&);
template void add_diag_bounds(WideBvh<8>&, const BuildInput&);
template void add_diag_bounds(WideBvh<16>&, const BuildInput&);
template std::string WideBvh<4>::validate_diags() const;
template std::string WideBvh<8>::validate_diags() const;
template std::string WideBvh<16>::validate_diags() const;

}  // namespace rtlab
