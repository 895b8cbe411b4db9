#pragma once
// Planar polygon objects: one primitive each; entry `PolygonPrim` of the primitive type table
// (scene.h).

#include "intersect/bounds.h"
#include "intersect/polygon/polygon.h"

#include <cstdint>
#include <string_view>
#include <vector>

namespace rtlab {

/// A planar polygon (>= 3 vertices, assumed planar; may be concave), one primitive. `normals` is
/// empty or holds one shading normal per vertex (NFF `pp`), interpolated by the renderer.
struct PolygonObject {
    std::vector<Vec3f> vertices;
    std::uint32_t material = 0;
    std::vector<Vec3f> normals;
    friend bool operator==(const PolygonObject&, const PolygonObject&) = default;
};

/// Everything the code knows about polygons (the table entry contract is in scene.h).
struct PolygonPrim {
    using Object = PolygonObject;
    static constexpr std::string_view name = "polygon";

    /// The scene's set of polygons.
    template <class S>
    static auto& objects(S& s) {
        return s.polygons;
    }
    /// Primitives per object.
    static std::uint32_t count(const Object&) { return 1; }
    /// Box of the whole object.
    static Bounds3f bounds(const Object& o) {
        Bounds3f b;
        for (const Vec3f& v : o.vertices) {
            b.extend(v);
        }
        return b;
    }
    /// Box of primitive `local` (the object's one primitive).
    static Bounds3f prim_bounds(const Object& o, std::uint32_t) { return bounds(o); }
    /// Calls emit(shape, global id) for the tracer; `id` is the object's first global id.
    template <class Emit>
    static void shapes(const Object& o, std::uint32_t id, Emit&& emit) {
        emit(Polygon<float>{o.vertices}, id);
    }
    /// Unnormalised normal at p: the geometric one (Newell's method, winding order), or with
    /// vertex normals their barycentric interpolation over the fan triangle (0, i, i+1) holding p
    /// (the geometric normal when that interpolation vanishes).
    static Vec3f normal(const Object& o, std::uint32_t, const Vec3f& p) {
        const Vec3f g = detail::newell_normal(o.vertices);
        if (o.normals.size() != o.vertices.size()) {
            return g;
        }
        const std::vector<Vec3f>& v = o.vertices;
        const float g2 = dot(g, g);
        for (std::size_t i = 1; i + 1 < v.size(); ++i) {
            // Barycentrics by signed sub-areas along g; p is inside when all are >= 0.
            const float b0 = dot(cross(v[i] - p, v[i + 1] - p), g) / g2;
            const float b1 = dot(cross(v[i + 1] - p, v[0] - p), g) / g2;
            const float b2 = dot(cross(v[0] - p, v[i] - p), g) / g2;
            const float sum = b0 + b1 + b2;
            if (i + 2 == v.size() || (b0 >= 0 && b1 >= 0 && b2 >= 0)) {
                const Vec3f n =
                    (o.normals[0] * b0 + o.normals[i] * b1 + o.normals[i + 1] * b2) / sum;
                return dot(n, n) > 1e-12f ? n : g;
            }
        }
        return g;
    }

    /// Reads the object's fields (not its material) through a scene_io reader.
    template <class In>
    static Object read(In& in) {
        in.keys({"type", "material", "vertices", "normals"});
        Object o;
        o.vertices = in.vec3_array("vertices");
        if (in.has("normals")) {
            o.normals = in.vec3_array("normals", o.vertices.size());
        }
        return o;
    }
    /// Writes the object's fields (not type and material) through a scene_io writer.
    template <class Out>
    static void write(const Object& o, Out& out) {
        out.vec3_array("vertices", o.vertices);
        if (!o.normals.empty()) {
            out.vec3_array("normals", o.normals);
        }
    }
    /// Fails at the offending field's path when the object breaks an invariant.
    template <class Path>
    static void check(const Object& o, const Path& at) {
        if (o.vertices.size() < 3) {
            (at / "vertices").fail("needs at least 3 vertices");
        }
        for (std::size_t i = 0; i < o.vertices.size(); ++i) {
            if (!is_finite(o.vertices[i])) {
                (at / "vertices")[i].fail("non-finite vector");
            }
        }
        if (!o.normals.empty() && o.normals.size() != o.vertices.size()) {
            (at / "normals").fail("needs one normal per vertex");
        }
        for (std::size_t i = 0; i < o.normals.size(); ++i) {
            if (!is_finite(o.normals[i])) {
                (at / "normals")[i].fail("non-finite vector");
            }
        }
    }
};

}  // namespace rtlab
