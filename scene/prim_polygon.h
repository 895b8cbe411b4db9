#pragma once
// Planar polygon objects: one primitive each; entry `PolygonPrim` of the primitive type table
// (scene.h).

#include "intersect/bounds.h"
#include "intersect/polygon/polygon.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
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
        // Planarity, in double, relative to the polygon's size L (its box diagonal) and to the
        // float rounding of its coordinates (M = largest |coordinate|): the Newell normal n must
        // not vanish (|n| > 1e-12 L^2: not all vertices collinear or repeated), and every vertex
        // must lie within planarity_tolerance * L + 1e-6 * M (about 8 float ulps) of the plane
        // through vertex 0.
        std::vector<Vec3<double>> v;
        double magnitude = 0;
        for (const Vec3f& p : o.vertices) {
            v.push_back({double(p.x), double(p.y), double(p.z)});
            magnitude = std::max(magnitude, max_component(abs(v.back())));
        }
        const Bounds3f b = bounds(o);
        const Vec3f d = b.diagonal();
        const double size = length(Vec3<double>{double(d.x), double(d.y), double(d.z)});
        const Vec3<double> n = detail::newell_normal(v);
        const double n_len = length(n);
        if (!(n_len > 1e-12 * size * size)) {
            (at / "vertices")
                .fail("degenerate polygon: the vertices are collinear or repeated (zero area)");
        }
        const double tolerance = planarity_tolerance * size + 1e-6 * magnitude;
        for (std::size_t i = 1; i < v.size(); ++i) {
            const double off = std::abs(dot(n, v[i] - v[0])) / n_len;
            if (off > tolerance) {
                (at / "vertices")[i].fail("not in the polygon's plane: " + std::to_string(off) +
                                          " away, tolerance " + std::to_string(tolerance) +
                                          " (1e-4 x the polygon's size + 1e-6 x its largest "
                                          "coordinate)");
            }
        }
    }
    /// Largest distance of a vertex from the polygon's plane, relative to its box diagonal.
    static constexpr double planarity_tolerance = 1e-4;
};

}  // namespace rtlab
