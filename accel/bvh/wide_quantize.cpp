// Quantised wide nodes (QWideNode8, accel/bvh/wide_node.h): a grid per node and per axis, and each
// plane rounded outward to a code whose dequantised value is checked in the float operations
// traversal uses.

#include "accel/bvh/wide_bvh.h"
#include "accel/bvh/wide_node.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>
#include <utility>

namespace rtlab {

namespace {

constexpr float top_code = 255.0f;

/// The step of a grid from lo to hi (finite, lo <= hi): about (hi - lo) / 255, grown until
/// lo + 255 * step >= hi as floats compute it (so code 255 reaches hi); 0 for a flat axis.
float grid_step(float lo, float hi) {
    if (!(hi > lo)) {
        return 0.0f;
    }
    float s = (hi - lo) / top_code;
    if (!std::isfinite(s)) {
        s = hi / top_code - lo / top_code;  // hi - lo overflows; this does not
    }
    for (int i = 0; lo + top_code * s < hi; ++i) {
        s = i < 8 ? std::nextafter(s, std::numeric_limits<float>::infinity()) : 2.0f * s;
    }
    return s;
}

/// The code of plane value v on the grid of axis a: the largest k with plane(k) <= v (a minimum,
/// down) or the smallest with plane(k) >= v (a maximum, up). Both exist for v inside the grid's
/// range: plane(0) is the origin and plane(255) >= the node's maximum.
std::uint8_t code(const QWideNode8& n, unsigned a, float v, bool up) {
    if (!(n.scale[a] > 0.0f)) {
        return 0;  // a flat axis: every code is the origin
    }
    const double guess = (static_cast<double>(v) - static_cast<double>(n.origin[a])) /
                         static_cast<double>(n.scale[a]);
    const double rounded = up ? std::ceil(guess) : std::floor(guess);
    int k = static_cast<int>(std::clamp(rounded, 0.0, static_cast<double>(top_code)));
    const auto p = [&](int c) { return n.plane(a, static_cast<std::uint8_t>(c)); };
    if (up) {
        while (k < 255 && p(k) < v) {
            ++k;
        }
        while (k > 0 && p(k - 1) >= v) {
            --k;
        }
    } else {
        while (k > 0 && p(k) > v) {
            --k;
        }
        while (k < 255 && p(k + 1) <= v) {
            ++k;
        }
    }
    return static_cast<std::uint8_t>(k);
}

}  // namespace

QWideNode8 quantize_wide_node(const WideNode<8>& n) {
    QWideNode8 q{};
    Bounds3f box;
    for (unsigned i = 0; i < 8; ++i) {
        q.child[i] = n.child[i];
        if (!n.occupied(i)) {
            continue;
        }
        if (n.count[i] > std::numeric_limits<std::uint16_t>::max()) {
            throw std::invalid_argument("quantised wide node: a leaf of " +
                                        std::to_string(n.count[i]) + " primitives (at most 65535)");
        }
        q.count[i] = static_cast<std::uint16_t>(n.count[i]);
        q.occupied = static_cast<std::uint8_t>(q.occupied | (1u << i));
        box.extend(n.bounds(i));
    }
    for (unsigned a = 0; a < 3; ++a) {
        q.origin[a] = q.occupied != 0 ? box.lo[a] : 0.0f;
        q.scale[a] = q.occupied != 0 ? grid_step(box.lo[a], box.hi[a]) : 0.0f;
    }
    for (unsigned i = 0; i < 8; ++i) {
        for (unsigned a = 0; a < 3; ++a) {
            q.q[0][a][i] = n.occupied(i) ? code(q, a, n.lo[a][i], false) : 0;
            q.q[1][a][i] = n.occupied(i) ? code(q, a, n.hi[a][i], true) : 0;
        }
    }
    return q;
}

WideBvh<8> quantize_bvh8(Bvh binary, ChildOrder order, WideCollapse rule) {
    WideBvh<8> w = collapse_bvh<8>(std::move(binary), order, rule);
    w.qnodes.resize(w.nodes.size());
    tbb::parallel_for(std::size_t{0}, w.nodes.size(),
                      [&](std::size_t i) { w.qnodes[i] = quantize_wide_node(w.nodes[i]); });
    return w;
}

}  // namespace rtlab
