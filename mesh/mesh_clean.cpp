// Mesh cleaning: one pass over triangles, one compaction of vertices. Cost: O(V + F).
#include "mesh/mesh_clean.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace rtlab {

CleanReport clean_mesh(TriangleMesh& m) {
    CleanReport r;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const auto c = m.corners(i);
        if (!is_finite(c[0]) || !is_finite(c[1]) || !is_finite(c[2])) {
            ++r.non_finite_triangles;
            continue;
        }
        const Vec3f n = cross(c[1] - c[0], c[2] - c[0]);
        if (n.x == 0 && n.y == 0 && n.z == 0) {
            ++r.degenerate_triangles;
            continue;
        }
        m.triangles[kept++] = m.triangles[i];
    }
    m.triangles.resize(kept);

    constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> remap(m.positions.size(), unused);
    for (const auto& t : m.triangles) {
        for (const std::uint32_t v : t) {
            remap[v] = 0;
        }
    }
    std::uint32_t next = 0;
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
        if (remap[v] == unused) {
            ++r.unreferenced_vertices;
            continue;
        }
        remap[v] = next;
        m.positions[next++] = m.positions[v];
    }
    m.positions.resize(next);
    for (auto& t : m.triangles) {
        for (std::uint32_t& v : t) {
            v = remap[v];
        }
    }
    return r;
}

}  // namespace rtlab
