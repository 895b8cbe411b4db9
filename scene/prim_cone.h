#pragma once
// Truncated cone and cylinder objects (NFF `c`): one primitive each; entry `ConePrim` of the
// primitive type table (scene.h).

#include "intersect/bounds.h"
#include "intersect/cone/cone.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace rtlab {

/// Lower-case name of a caps setting as in scene files ("none", "base", "apex", "both").
constexpr std::string_view to_string(ConeCaps c) {
    switch (c) {
    case ConeCaps::base:
        return "base";
    case ConeCaps::apex:
        return "apex";
    case ConeCaps::both:
        return "both";
    case ConeCaps::none:
        break;
    }
    return "none";
}

/// A truncated cone: the lateral surface from the base disk (centre `base`, radius
/// `base_radius`) to the apex disk (`apex`, `apex_radius`); a cylinder when the radii are equal.
/// Open-ended as NFF's `c` unless `caps` adds end disks.
struct ConeObject {
    Vec3f base{0, 0, 0};
    float base_radius = 1;  ///< >= 0
    Vec3f apex{0, 0, 1};    ///< != base
    float apex_radius = 1;  ///< >= 0; not both radii 0
    ConeCaps caps = ConeCaps::none;
    std::uint32_t material = 0;
    friend bool operator==(const ConeObject&, const ConeObject&) = default;
};

/// Everything the code knows about cones (the table entry contract is in scene.h).
struct ConePrim {
    using Object = ConeObject;
    static constexpr std::string_view name = "cone";

    /// The scene's set of cones.
    template <class S>
    static auto& objects(S& s) {
        return s.cones;
    }
    /// Primitives per object.
    static std::uint32_t count(const Object&) { return 1; }
    /// The object as the shape the cone methods take.
    static Cone<float> shape(const Object& o) {
        return {o.base, o.base_radius, o.apex, o.apex_radius, o.caps};
    }
    /// Box of the whole object (both end disks).
    static Bounds3f bounds(const Object& o) {
        return detail::cone_bounds(o.base, o.base_radius, o.apex, o.apex_radius);
    }
    /// Box of primitive `local` (the object's one primitive).
    static Bounds3f prim_bounds(const Object& o, std::uint32_t) { return bounds(o); }
    /// Calls emit(shape, global id) for the tracer; `id` is the object's first global id.
    template <class Emit>
    static void shapes(const Object& o, std::uint32_t id, Emit&& emit) {
        emit(shape(o), id);
    }
    /// Unnormalised outward normal at surface point p (the lateral surface's, or a cap's when p
    /// is nearer to that cap).
    static Vec3f normal(const Object& o, std::uint32_t, const Vec3f& p) {
        return cone_normal(detail::prepare_cone(shape(o)), p);
    }

    /// Reads the object's fields (not its material) through a scene_io reader.
    template <class In>
    static Object read(In& in) {
        in.keys(
            {"type", "material", "base", "base_radius", "apex", "apex_radius", "radius", "caps"});
        Object o;
        o.base = in.vec3("base");
        o.apex = in.vec3("apex");
        if (in.has("radius")) {
            if (in.has("base_radius") || in.has("apex_radius")) {
                (in.path() / "radius").fail("give either radius or base_radius and apex_radius");
            }
            o.base_radius = o.apex_radius = in.number("radius");
        } else {
            o.base_radius = in.number("base_radius");
            o.apex_radius = in.number("apex_radius");
        }
        if (in.has("caps")) {
            const std::string caps = in.string("caps");
            bool known = false;
            for (const ConeCaps c :
                 {ConeCaps::none, ConeCaps::base, ConeCaps::apex, ConeCaps::both}) {
                if (caps == to_string(c)) {
                    o.caps = c;
                    known = true;
                }
            }
            if (!known) {
                (in.path() / "caps").fail("unknown caps '" + caps + "' (none, base, apex, both)");
            }
        }
        return o;
    }
    /// Writes the object's fields (not type and material) through a scene_io writer.
    template <class Out>
    static void write(const Object& o, Out& out) {
        out.vec3("base", o.base);
        out.number("base_radius", o.base_radius);
        out.vec3("apex", o.apex);
        out.number("apex_radius", o.apex_radius);
        if (o.caps != ConeCaps::none) {
            out.string("caps", std::string(to_string(o.caps)));
        }
    }
    /// Fails at the offending field's path when the object breaks an invariant.
    template <class Path>
    static void check(const Object& o, const Path& at) {
        if (!is_finite(o.base)) {
            (at / "base").fail("non-finite vector");
        }
        if (!is_finite(o.apex)) {
            (at / "apex").fail("non-finite vector");
        }
        if (!(length_squared(o.apex - o.base) > 0) || !std::isfinite(length(o.apex - o.base))) {
            (at / "apex").fail("must differ from base (and the axis length be finite)");
        }
        if (!(o.base_radius >= 0) || !std::isfinite(o.base_radius)) {
            (at / "base_radius").fail("must be finite and >= 0");
        }
        if (!(o.apex_radius >= 0) || !std::isfinite(o.apex_radius)) {
            (at / "apex_radius").fail("must be finite and >= 0");
        }
        if (!(o.base_radius > 0 || o.apex_radius > 0)) {
            (at / "base_radius").fail("base_radius and apex_radius must not both be 0");
        }
    }
};

}  // namespace rtlab
