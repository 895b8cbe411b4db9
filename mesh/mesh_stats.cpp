// Mesh statistics over index-based undirected edges. Cost: O(F log F) for the edge sort.
#include "mesh/mesh_stats.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>
#include <vector>

namespace rtlab {

namespace {

/// A directed triangle edge, keyed by its undirected vertex pair.
struct HalfEdge {
    std::uint32_t lo, hi;
    bool forward;  ///< traversed lo -> hi
    bool operator<(const HalfEdge& o) const { return std::tie(lo, hi) < std::tie(o.lo, o.hi); }
};

bool is_degenerate(const TriangleMesh& m, std::size_t i) {
    const auto c = m.corners(i);
    if (!is_finite(c[0]) || !is_finite(c[1]) || !is_finite(c[2])) {
        return true;
    }
    const Vec3f n = cross(c[1] - c[0], c[2] - c[0]);
    return n.x == 0 && n.y == 0 && n.z == 0;
}

}  // namespace

MeshStats mesh_stats(const TriangleMesh& m) {
    MeshStats s;
    s.vertices = m.positions.size();
    s.triangles = m.triangles.size();
    s.bounds = m.bounds();

    std::vector<bool> used(m.positions.size(), false);
    std::vector<std::array<std::uint32_t, 3>> sorted;
    sorted.reserve(m.triangles.size());
    std::vector<HalfEdge> edges;
    bool repeated = false;  // a triangle repeating a vertex is not a 2-manifold face
    edges.reserve(3 * m.triangles.size());
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const auto& t = m.triangles[i];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[static_cast<std::size_t>(k)];
            const std::uint32_t b = t[static_cast<std::size_t>((k + 1) % 3)];
            used[a] = true;
            if (a != b) {  // a repeated index is no edge
                edges.push_back({std::min(a, b), std::max(a, b), a < b});
            } else {
                repeated = true;
            }
        }
        s.degenerate_triangles += is_degenerate(m, i) ? 1 : 0;
        auto key = t;
        std::sort(key.begin(), key.end());
        sorted.push_back(key);
    }
    s.unreferenced_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));

    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < sorted.size(); ++i) {
        s.duplicate_triangles += sorted[i] == sorted[i - 1] ? 1 : 0;
    }

    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        std::size_t forward = 0;
        while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) {
            forward += edges[j].forward ? 1 : 0;
            ++j;
        }
        const std::size_t n = j - i;
        ++s.edges;
        if (n == 1) {
            ++s.boundary_edges;
        } else if (n >= 3) {
            ++s.non_manifold_edges;
        } else if (forward != 1) {
            ++s.inconsistent_edges;
        }
        i = j;
    }
    s.closed = s.triangles > 0 && s.boundary_edges == 0 && s.non_manifold_edges == 0 &&
               s.inconsistent_edges == 0 && !repeated;
    return s;
}

}  // namespace rtlab
