#pragma once
// Implicit surface objects f(p - center) = 0 (torus, tangle cube): one primitive each; entry
// `ImplicitPrim` of the primitive type table (scene.h).

#include "intersect/bounds.h"
#include "intersect/implicit/tangle_cube.h"
#include "intersect/implicit/torus.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace rtlab {

/// Implicit surfaces f(p - center) = 0.
enum class ImplicitKind : std::uint8_t {
    torus,      ///< (|q|^2 + R^2 - r^2)^2 - 4 R^2 (qx^2 + qy^2), axis z; R = major, r = minor
    tanglecube  ///< s = q/scale: sx^4 - 5 sx^2 + sy^4 - 5 sy^2 + sz^4 - 5 sz^2 + 11.8
};

/// Lower-case name of an implicit surface kind ("torus", "tanglecube").
std::string_view to_string(ImplicitKind k);

/// An implicit surface object; which parameters apply depends on the kind.
struct ImplicitObject {
    ImplicitKind kind = ImplicitKind::torus;
    Vec3f center;
    float major = 1;      ///< torus: distance from the centre to the tube centre, > minor
    float minor = 0.25f;  ///< torus: tube radius, > 0
    float scale = 1;      ///< tanglecube: uniform scale, > 0
    std::uint32_t material = 0;
    friend bool operator==(const ImplicitObject&, const ImplicitObject&) = default;
};

/// Everything the code knows about implicit surfaces (the table entry contract is in scene.h).
struct ImplicitPrim {
    using Object = ImplicitObject;
    static constexpr std::string_view name = "implicit";

    /// The scene's set of implicit surfaces.
    template <class S>
    static auto& objects(S& s) {
        return s.implicits;
    }
    /// Primitives per object.
    static std::uint32_t count(const Object&) { return 1; }
    /// Box of the whole surface, from the kind's analytic extent.
    static Bounds3f bounds(const Object& o) {
        Vec3f half;
        switch (o.kind) {
        case ImplicitKind::torus:
            half = Vec3f{o.major + o.minor, o.major + o.minor, o.minor};
            break;
        case ImplicitKind::tanglecube:
            // Along an axis the surface reaches x^4 - 5x^2 - 0.7 = 0 (other coordinates at the
            // minimum of t^4 - 5t^2), x = 2.2663...; 2.27 covers it.
            half = Vec3f{2.27f, 2.27f, 2.27f} * o.scale;
            break;
        }
        return {o.center - half, o.center + half};
    }
    /// Box of primitive `local` (the object's one primitive).
    static Bounds3f prim_bounds(const Object& o, std::uint32_t) { return bounds(o); }
    /// Calls emit(surface, global id) for the tracer (a Torus or a TangleCube).
    template <class Emit>
    static void shapes(const Object& o, std::uint32_t id, Emit&& emit) {
        if (o.kind == ImplicitKind::torus) {
            emit(Torus<float>{o.center, o.major, o.minor}, id);
        } else {
            emit(TangleCube<float>{o.center, o.scale}, id);
        }
    }
    /// Unnormalised normal at surface point p: the gradient of f.
    static Vec3f normal(const Object& o, std::uint32_t, const Vec3f& p) {
        return o.kind == ImplicitKind::torus ? Torus<float>{o.center, o.major, o.minor}.gradient(p)
                                             : TangleCube<float>{o.center, o.scale}.gradient(p);
    }

    /// Reads the object's fields (not its material); the keys allowed depend on `surface`.
    template <class In>
    static Object read(In& in) {
        Object o;
        const std::string surface = in.string("surface");
        if (surface == "torus") {
            in.keys({"type", "material", "surface", "center", "major", "minor"});
            o.kind = ImplicitKind::torus;
            in.opt_number("major", o.major);
            in.opt_number("minor", o.minor);
        } else if (surface == "tanglecube") {
            in.keys({"type", "material", "surface", "center", "scale"});
            o.kind = ImplicitKind::tanglecube;
            in.opt_number("scale", o.scale);
        } else {
            (in.path() / "surface")
                .fail("unknown implicit surface '" + surface + "' (torus, tanglecube)");
        }
        in.opt_vec3("center", o.center);
        return o;
    }
    /// Writes the object's fields (not type and material) through a scene_io writer.
    template <class Out>
    static void write(const Object& o, Out& out) {
        out.string("surface", std::string(to_string(o.kind)));
        out.vec3("center", o.center);
        if (o.kind == ImplicitKind::torus) {
            out.number("major", o.major);
            out.number("minor", o.minor);
        } else {
            out.number("scale", o.scale);
        }
    }
    /// Fails at the offending field's path when the object breaks an invariant.
    template <class Path>
    static void check(const Object& o, const Path& at) {
        if (!is_finite(o.center)) {
            (at / "center").fail("non-finite vector");
        }
        if (o.kind == ImplicitKind::torus) {
            if (!(o.minor > 0)) {
                (at / "minor").fail("must be > 0");
            }
            if (!(o.major > o.minor)) {
                (at / "major").fail("must be > minor");
            }
        } else if (!(o.scale > 0)) {
            (at / "scale").fail("must be > 0");
        }
    }
};

}  // namespace rtlab
