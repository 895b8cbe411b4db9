#pragma once
// Triangle mesh objects: one primitive per triangle, global ids in the mesh's triangle order;
// entry `MeshPrim` of the primitive type table (scene.h).

#include "intersect/bounds.h"
#include "intersect/triangle/triangle.h"
#include "mesh/mesh_io.h"
#include "mesh/triangle_mesh.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace rtlab {

/// A triangle mesh object; `file` is where it came from (relative to the scene file), may be empty.
struct MeshObject {
    TriangleMesh mesh;
    std::string file;
    std::uint32_t material = 0;
    friend bool operator==(const MeshObject&, const MeshObject&) = default;
};

/// Everything the code knows about meshes (the table entry contract is in scene.h).
struct MeshPrim {
    using Object = MeshObject;
    static constexpr std::string_view name = "mesh";

    /// The scene's set of meshes.
    template <class S>
    static auto& objects(S& s) {
        return s.meshes;
    }
    /// Primitives per object: the triangle count.
    static std::uint32_t count(const Object& o) {
        return static_cast<std::uint32_t>(o.mesh.triangle_count());
    }
    /// Box of the whole mesh.
    static Bounds3f bounds(const Object& o) { return o.mesh.bounds(); }
    /// Box of triangle `local`.
    static Bounds3f prim_bounds(const Object& o, std::uint32_t local) {
        return o.mesh.triangle_bounds(local);
    }
    /// Calls emit(triangle, global id) for every triangle; `id` is the first triangle's id.
    template <class Emit>
    static void shapes(const Object& o, std::uint32_t id, Emit&& emit) {
        const TriangleMesh& m = o.mesh;
        for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
            const auto& f = m.triangles[t];
            emit(Triangle<float>{m.positions[f[0]], m.positions[f[1]], m.positions[f[2]]}, id + t);
        }
    }
    /// Unnormalised geometric normal of triangle `local` (winding order).
    static Vec3f normal(const Object& o, std::uint32_t local, const Vec3f&) {
        const auto& f = o.mesh.triangles[local];
        const Vec3f& a = o.mesh.positions[f[0]];
        return cross(o.mesh.positions[f[1]] - a, o.mesh.positions[f[2]] - a);
    }

    /// Reads the object's fields (not its material): loads `file` relative to the scene file.
    template <class In>
    static Object read(In& in) {
        in.keys({"type", "material", "file"});
        Object o;
        o.file = in.string("file");
        if (o.file.empty()) {
            (in.path() / "file").fail("must not be empty");
        }
        try {
            o.mesh = load_mesh(in.base_dir() / o.file);
        } catch (const Error& e) {
            (in.path() / "file").fail(e.what());
        }
        return o;
    }
    /// Writes the mesh's file name (the writer saves the mesh itself when asked to).
    template <class Out>
    static void write(const Object& o, Out& out) {
        out.string("file", out.external_mesh(o.mesh, o.file));
    }
    /// Fails (naming the mesh file) when the mesh breaks an invariant.
    template <class Path>
    static void check(const Object& o, const Path& at) {
        validate_mesh(o.mesh, at.what() + ": " + std::string("mesh ") + o.file);
    }
};

}  // namespace rtlab
