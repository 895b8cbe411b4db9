#pragma once
// Axis-aligned box objects (solids): one primitive each; entry `BoxPrim` of the primitive type
// table (scene.h).

#include "intersect/bounds.h"

#include <cmath>
#include <cstdint>
#include <string_view>

namespace rtlab {

/// An axis-aligned box (lo <= hi on every axis).
struct BoxObject {
    Bounds3f bounds;
    std::uint32_t material = 0;
    friend bool operator==(const BoxObject&, const BoxObject&) = default;
};

/// Normal of the box face nearest to `local` (a point relative to the centre of a box of half
/// extents `half`): the axis where the point is relatively furthest from the centre.
inline Vec3f box_face_normal(const Vec3f& local, const Vec3f& half) {
    std::size_t best = 0;
    float best_v = -1;
    for (std::size_t a = 0; a < 3; ++a) {
        const float v = half[a] > 0 ? std::abs(local[a]) / half[a] : std::abs(local[a]);
        if (v > best_v) {
            best_v = v;
            best = a;
        }
    }
    Vec3f n{0, 0, 0};
    n[best] = local[best] < 0 ? -1.0f : 1.0f;
    return n;
}

/// Everything the code knows about boxes (the table entry contract is in scene.h).
struct BoxPrim {
    using Object = BoxObject;
    static constexpr std::string_view name = "box";

    /// The scene's set of boxes.
    template <class S>
    static auto& objects(S& s) {
        return s.boxes;
    }
    /// Primitives per object.
    static std::uint32_t count(const Object&) { return 1; }
    /// Box of the whole object.
    static Bounds3f bounds(const Object& o) { return o.bounds; }
    /// Box of primitive `local` (the object's one primitive).
    static Bounds3f prim_bounds(const Object& o, std::uint32_t) { return o.bounds; }
    /// Calls emit(shape, global id) for the tracer; `id` is the object's first global id.
    template <class Emit>
    static void shapes(const Object& o, std::uint32_t id, Emit&& emit) {
        emit(o.bounds, id);
    }
    /// Outward normal of the face nearest to surface point p.
    static Vec3f normal(const Object& o, std::uint32_t, const Vec3f& p) {
        return box_face_normal(p - o.bounds.center(), o.bounds.diagonal() * 0.5f);
    }
    /// A solid: the box in its own frame, with the ray origin and direction moved into that frame
    /// (an axis-aligned box is its own frame).
    static Bounds3f solid_frame(const Object& o, Vec3f&, Vec3f&) { return o.bounds; }

    /// Reads the object's fields (not its material) through a scene_io reader.
    template <class In>
    static Object read(In& in) {
        in.keys({"type", "material", "min", "max"});
        Object o;
        o.bounds.lo = in.vec3("min");
        o.bounds.hi = in.vec3("max");
        return o;
    }
    /// Writes the object's fields (not type and material) through a scene_io writer.
    template <class Out>
    static void write(const Object& o, Out& out) {
        out.vec3("min", o.bounds.lo);
        out.vec3("max", o.bounds.hi);
    }
    /// Fails at the offending field's path when the object breaks an invariant.
    template <class Path>
    static void check(const Object& o, const Path& at) {
        if (!is_finite(o.bounds.lo) || !is_finite(o.bounds.hi)) {
            at.fail("non-finite corner");
        }
        if (o.bounds.empty()) {
            (at / "max").fail("must be >= min on every axis");
        }
    }
};

}  // namespace rtlab
