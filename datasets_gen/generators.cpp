// The generator registry, size and memory checks, and flattening a scene into one mesh.
#include "datasets_gen/generators.h"

#include "base/error.h"
#include "datasets_gen/memory_guard.h"
#include "datasets_gen/scene_parts.h"

#include <string>
#include <type_traits>
#include <vector>

namespace rtlab::gen {

std::span<const Generator> generators() {
    static const std::vector<Generator> table = [] {
        std::vector<Generator> t = spd_generators();
        for (const Generator& g :
             {flake_generator(), terrain_generator(), spiral_generator(), gearbox_generator(),
              soup_generator(), soup_clustered_generator(), stadium_generator(),
              slivers_generator(), intgrid_generator(), far_generator(), scales_generator(),
              coplanar_generator(), nested_generator()}) {
            t.push_back(g);
        }
        return t;
    }();
    return table;
}

const Generator* find_generator(std::string_view name) {
    for (const Generator& g : generators()) {
        if (g.name == name) {
            return &g;
        }
    }
    return nullptr;
}

std::uint64_t estimate_bytes(const GenCounts& c) {
    // Measured peaks of `rtlab gen` (debug build): ~900 B per sphere and ~2.4 KiB per 23-vertex
    // polygon, dominated by the JSON document save_scene builds; ~48 B per mesh triangle.
    std::uint64_t b = saturating_mul(saturating_add(c.spheres, c.cones), 1024);
    b = saturating_add(b, saturating_mul(c.triangles, 64));
    b = saturating_add(b, saturating_mul(c.polygons, 256));
    return saturating_add(b, saturating_mul(c.polygon_vertices, 96));
}

Scene generate(const Generator& g, GenOptions o) {
    if (o.size < 0) {
        o.size = g.default_size;
    }
    if (o.size < g.min_size || o.size > g.max_size) {
        throw Error(std::string(g.name) + ": --size " + std::to_string(o.size) +
                    " is out of range [" + std::to_string(g.min_size) + ", " +
                    std::to_string(g.max_size) + "]");
    }
    const std::uint64_t limit = o.memory_limit != 0 ? o.memory_limit : default_memory_limit();
    check_memory(std::string(g.name) + " --size " + std::to_string(o.size) +
                     (o.as_mesh ? " --tess " + o.tess.to_string() : std::string()),
                 estimate_bytes(g.counts(o)), limit);
    return g.make(o);
}

Scene generate(std::string_view name, const GenOptions& o) {
    const Generator* g = find_generator(name);
    if (g == nullptr) {
        std::string names;
        for (const Generator& row : generators()) {
            names += (names.empty() ? "" : ", ") + std::string(row.name);
        }
        throw Error("unknown generator '" + std::string(name) + "' (known: " + names + ")");
    }
    return generate(*g, o);
}

namespace {

// Appends a polygon as a fan around its vertex centroid.
void append_polygon(TriangleMesh& out, const std::vector<Vec3f>& v) {
    Vec3d mid;
    for (const Vec3f& p : v) {
        mid += Vec3d(p);
    }
    mid = mid / static_cast<double>(v.size());
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    out.positions.insert(out.positions.end(), v.begin(), v.end());
    out.positions.push_back(Vec3f(mid));
    const auto n = static_cast<std::uint32_t>(v.size());
    for (std::uint32_t i = 0; i < n; ++i) {
        out.triangles.push_back({base + n, base + i, base + (i + 1) % n});
    }
}

// Appends object o as triangles; false when its type has no tessellation.
template <class O>
bool append_object(TriangleMesh& out, const O& o, const SphereTess& tess) {
    if constexpr (std::is_same_v<O, MeshObject>) {
        append_mesh(out, o.mesh);
    } else if constexpr (std::is_same_v<O, SphereObject>) {
        append_sphere(out, Vec3d(o.center), static_cast<double>(o.radius), tess);
    } else if constexpr (std::is_same_v<O, PolygonObject>) {
        append_polygon(out, o.vertices);
    } else if constexpr (std::is_same_v<O, ConeObject>) {
        append_cone(out, Vec3d(o.base), static_cast<double>(o.base_radius), Vec3d(o.apex),
                    static_cast<double>(o.apex_radius), has_cap(o.caps, ConeCaps::base),
                    has_cap(o.caps, ConeCaps::apex), tess.u);
    } else {
        return false;
    }
    return true;
}

}  // namespace

TriangleMesh scene_to_mesh(const Scene& s, const SphereTess& tess) {
    TriangleMesh out;
    for (const ObjectRef& r : s.order) {
        const bool done =
            visit_object(s, r, [&]<class P>(const auto& o) { return append_object(out, o, tess); });
        if (!done) {
            throw Error(std::string("scene_to_mesh: ")
                            .append(to_string(r.type))
                            .append(" primitives cannot be tessellated (spheres, meshes and "
                                    "polygons can)"));
        }
    }
    return out;
}

}  // namespace rtlab::gen
