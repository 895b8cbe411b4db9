#pragma once
// Sphere objects: one primitive each; entry `SpherePrim` of the primitive type table (scene.h).

#include "intersect/bounds.h"
#include "intersect/sphere/sphere.h"

#include <cmath>
#include <cstdint>
#include <string_view>

namespace rtlab {

/// A sphere object.
struct SphereObject {
    Vec3f center;
    float radius = 1;  ///< > 0
    std::uint32_t material = 0;
    friend bool operator==(const SphereObject&, const SphereObject&) = default;
};

/// Everything the code knows about spheres (the table entry contract is in scene.h).
struct SpherePrim {
    using Object = SphereObject;
    static constexpr std::string_view name = "sphere";

    /// The scene's set of spheres.
    template <class S>
    static auto& objects(S& s) {
        return s.spheres;
    }
    /// Primitives per object.
    static std::uint32_t count(const Object&) { return 1; }
    /// Box of the whole object.
    static Bounds3f bounds(const Object& o) {
        const Vec3f h{o.radius, o.radius, o.radius};
        return {o.center - h, o.center + h};
    }
    /// Box of primitive `local` (the object's one primitive).
    static Bounds3f prim_bounds(const Object& o, std::uint32_t) { return bounds(o); }
    /// Calls emit(shape, global id) for the tracer; `id` is the object's first global id.
    template <class Emit>
    static void shapes(const Object& o, std::uint32_t id, Emit&& emit) {
        emit(Sphere<float>{o.center, o.radius}, id);
    }
    /// Unnormalised outward normal at surface point p.
    static Vec3f normal(const Object& o, std::uint32_t, const Vec3f& p) { return p - o.center; }

    /// Reads the object's fields (not its material) through a scene_io reader.
    template <class In>
    static Object read(In& in) {
        in.keys({"type", "material", "center", "radius"});
        Object o;
        o.center = in.vec3("center");
        o.radius = in.number("radius");
        if (!(o.radius > 0)) {
            (in.path() / "radius").fail("must be > 0");
        }
        return o;
    }
    /// Writes the object's fields (not type and material) through a scene_io writer.
    template <class Out>
    static void write(const Object& o, Out& out) {
        out.vec3("center", o.center);
        out.number("radius", o.radius);
    }
    /// Fails at the offending field's path when the object breaks an invariant.
    template <class Path>
    static void check(const Object& o, const Path& at) {
        if (!is_finite(o.center)) {
            (at / "center").fail("non-finite vector");
        }
        if (!(o.radius > 0) || !std::isfinite(o.radius)) {
            (at / "radius").fail("must be finite and > 0");
        }
    }
};

}  // namespace rtlab
