#pragma once
// Oriented box objects (solids): one primitive each; entry `ObbPrim` of the primitive type table
// (scene.h).

#include "intersect/bounds.h"
#include "intersect/box/obb.h"
#include "scene/prim_box.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace rtlab {

/// An oriented box: centre, three orthonormal axes and the half extent along each (> 0).
struct ObbObject {
    Vec3f center;
    std::array<Vec3f, 3> axes{Vec3f{1, 0, 0}, Vec3f{0, 1, 0}, Vec3f{0, 0, 1}};
    Vec3f half{1, 1, 1};
    std::uint32_t material = 0;
    friend bool operator==(const ObbObject&, const ObbObject&) = default;
};

/// Everything the code knows about oriented boxes (the table entry contract is in scene.h).
struct ObbPrim {
    using Object = ObbObject;
    static constexpr std::string_view name = "obb";
    /// Orthonormality tolerance for the axes: loose enough for axes written with ~6 digits.
    static constexpr float axis_tolerance = 1e-4f;

    /// The scene's set of oriented boxes.
    template <class S>
    static auto& objects(S& s) {
        return s.obbs;
    }
    /// Primitives per object.
    static std::uint32_t count(const Object&) { return 1; }
    /// Box of the whole object.
    static Bounds3f bounds(const Object& o) {
        const Vec3f h =
            abs(o.axes[0]) * o.half.x + abs(o.axes[1]) * o.half.y + abs(o.axes[2]) * o.half.z;
        return {o.center - h, o.center + h};
    }
    /// Box of primitive `local` (the object's one primitive).
    static Bounds3f prim_bounds(const Object& o, std::uint32_t) { return bounds(o); }
    /// Calls emit(shape, global id) for the tracer; `id` is the object's first global id.
    template <class Emit>
    static void shapes(const Object& o, std::uint32_t id, Emit&& emit) {
        emit(Obb<float>{o.center, {o.axes[0], o.axes[1], o.axes[2]}, o.half}, id);
    }
    /// Outward normal of the face nearest to surface point p.
    static Vec3f normal(const Object& o, std::uint32_t, const Vec3f& p) {
        const Vec3f d = p - o.center;
        const Vec3f local{dot(d, o.axes[0]), dot(d, o.axes[1]), dot(d, o.axes[2])};
        const Vec3f ln = box_face_normal(local, o.half);
        return o.axes[0] * ln.x + o.axes[1] * ln.y + o.axes[2] * ln.z;
    }
    /// A solid: the box in its own frame (centre at the origin, axes along x, y, z), with the ray
    /// origin and direction moved into that frame.
    static Bounds3f solid_frame(const Object& o, Vec3f& org, Vec3f& dir) {
        const Vec3f rel = org - o.center;
        org = {dot(rel, o.axes[0]), dot(rel, o.axes[1]), dot(rel, o.axes[2])};
        dir = {dot(dir, o.axes[0]), dot(dir, o.axes[1]), dot(dir, o.axes[2])};
        return {-o.half, o.half};
    }

    /// Reads the object's fields (not its material) through a scene_io reader.
    template <class In>
    static Object read(In& in) {
        in.keys({"type", "material", "center", "axes", "half"});
        Object o;
        o.center = in.vec3("center");
        const auto axes = in.vec3_array("axes", 3);
        for (std::size_t i = 0; i < 3; ++i) {
            o.axes[i] = axes[i];
        }
        o.half = in.vec3("half");
        return o;
    }
    /// Writes the object's fields (not type and material) through a scene_io writer.
    template <class Out>
    static void write(const Object& o, Out& out) {
        out.vec3("center", o.center);
        out.vec3_array("axes", {o.axes[0], o.axes[1], o.axes[2]});
        out.vec3("half", o.half);
    }
    /// Fails at the offending field's path when the object breaks an invariant.
    template <class Path>
    static void check(const Object& o, const Path& at) {
        if (!is_finite(o.center)) {
            (at / "center").fail("non-finite vector");
        }
        if (!(min_component(o.half) > 0)) {
            (at / "half").fail("components must be > 0");
        }
        for (std::size_t i = 0; i < 3; ++i) {
            if (!(std::abs(length(o.axes[i]) - 1) <= axis_tolerance)) {
                (at / "axes")[i].fail("must be unit length");
            }
            for (std::size_t k = i + 1; k < 3; ++k) {
                if (!(std::abs(dot(o.axes[i], o.axes[k])) <= axis_tolerance)) {
                    (at / "axes")[k].fail("must be orthogonal to axes[" + std::to_string(i) + "]");
                }
            }
        }
    }
};

}  // namespace rtlab
