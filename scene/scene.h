#pragma once
// Scene: one primitive set per primitive type, plus camera, lights and materials. Objects keep the
// order of the scene file; global primitive ids follow that order (see primitive_id_base).

#include "intersect/bounds.h"
#include "intersect/method.h"
#include "intersect/vec.h"
#include "scene/prim_box.h"
#include "scene/prim_cone.h"
#include "scene/prim_implicit.h"
#include "scene/prim_mesh.h"
#include "scene/prim_obb.h"
#include "scene/prim_polygon.h"
#include "scene/prim_sphere.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtlab {

/// Pinhole camera looking from `from` to `at`; fov_deg is the vertical field of view in degrees.
struct Camera {
    Vec3f from{0, 0, 5};
    Vec3f at{0, 0, 0};
    Vec3f up{0, 1, 0};
    float fov_deg = 45;  ///< vertical, in (0, 180)
    int width = 512;     ///< pixels, 1..16384
    int height = 512;    ///< pixels, 1..16384
    friend bool operator==(const Camera&, const Camera&) = default;
};

/// Kind of light source.
enum class LightKind { point, directional };

/// A light. Point: `position` is where it is. Directional: `position` is the direction towards the
/// light (a point at infinity; need not be unit length). No falloff with distance.
struct Light {
    LightKind kind = LightKind::point;
    Vec3f position{0, 0, 0};
    Vec3f color{1, 1, 1};  ///< radiance scale per channel, >= 0
    friend bool operator==(const Light&, const Light&) = default;
};

/// Kind of procedural texture.
enum class TextureKind { none, checker };

/// Procedural texture modulating the material colour: checker alternates `color` and `color2` in
/// a 3-D grid of cell size `scale` (world units) - the seed notes' 3-D checkerboard.
struct Texture {
    TextureKind kind = TextureKind::none;
    Vec3f color2{0, 0, 0};
    float scale = 1;  ///< > 0
    friend bool operator==(const Texture&, const Texture&) = default;
};

/// Whitted/Phong material: I = ambient*color + sum over lights (diffuse*color*(N.L) +
/// specular*(R.V)^shininess) + reflect*I_mirror + transmit*I_refracted. Coefficients are >= 0.
struct Material {
    std::string name = "default";
    Vec3f color{0.8f, 0.8f, 0.8f};
    float ambient = 0.1f;
    float diffuse = 0.9f;
    float specular = 0;
    float shininess = 32;
    float reflect = 0;          ///< mirror weight k_r
    float transmit = 0;         ///< transmission weight k_t (> 0 makes it refractive)
    float ior = 1.5f;           ///< index of refraction (only used when transmit > 0), >= 1
    bool fresnel = false;       ///< weight reflect/transmit by the exact Fresnel term
    Vec3f absorption{0, 0, 0};  ///< Beer-Lambert coefficient per channel, per unit length
    float dispersion = 0;       ///< Cauchy B in um^2 (n(l) = ior + B / l^2); 0 = none
    Texture texture;
    friend bool operator==(const Material&, const Material&) = default;
};

/// Primitive types a scene can hold, in the order of the PrimTypes table below.
enum class PrimType : std::uint8_t { sphere, mesh, polygon, box, obb, implicit, cone };

/// The primitive type table: one entry per PrimType, in enumerator order. An entry is a stateless
/// struct in its own header (scene/prim_*.h) holding everything the code knows about the type:
/// `Object` (its scene object), `name` (as in scene files), `objects(scene)` (its set in Scene),
/// `count(o)` (global primitives per object), `bounds(o)` and `prim_bounds(o, local)`,
/// `shapes(o, first_id, emit)` (world shapes for the tracer), `normal(o, local, p)` (unnormalised
/// surface normal for the renderer), `read`/`write`/`check` (JSON through scene_io's reader,
/// writer and path) and, for solids only, `solid_frame(o, org, dir)`. Code that depends on the
/// type iterates this table (for_each_type) or dispatches through visit_prim_type/visit_object.
using PrimTypes =
    std::tuple<SpherePrim, MeshPrim, PolygonPrim, BoxPrim, ObbPrim, ImplicitPrim, ConePrim>;

/// Number of primitive types.
inline constexpr std::size_t prim_type_count = std::tuple_size_v<PrimTypes>;

/// Lower-case name of a primitive type as used in scene files ("sphere", "mesh", ...).
std::string_view to_string(PrimType t);

namespace detail {

/// Position of the entry whose Object is O in the list Ps (sizeof...(Ps) when there is none).
template <class O, class... Ps>
constexpr std::size_t object_index(std::tuple<Ps...>*) {
    constexpr bool match[] = {std::is_same_v<O, typename Ps::Object>...};
    for (std::size_t i = 0; i < sizeof...(Ps); ++i) {
        if (match[i]) {
            return i;
        }
    }
    return sizeof...(Ps);
}

}  // namespace detail

/// Position in PrimTypes of the entry whose Object is O (prim_type_count when there is none).
template <class O>
inline constexpr std::size_t prim_index_v =
    detail::object_index<O>(static_cast<PrimTypes*>(nullptr));

/// The table entry of scene object type O.
template <class O>
using PrimOf = std::tuple_element_t<prim_index_v<O>, PrimTypes>;

/// The PrimType of table entry P.
template <class P>
inline constexpr auto prim_type_v = static_cast<PrimType>(prim_index_v<typename P::Object>);

/// Calls f.template operator()<P>() for the table entry P of type t and returns its result (a
/// default-constructed result for a t outside the table). Every entry must return the same type.
template <class F>
decltype(auto) visit_prim_type(PrimType t, F&& f) {
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
        using R = decltype(f.template operator()<std::tuple_element_t<0, PrimTypes>>());
        const auto i = static_cast<std::size_t>(t);
        if constexpr (std::is_void_v<R>) {
            (void)((i == I ? (f.template operator()<std::tuple_element_t<I, PrimTypes>>(), true)
                           : false) ||
                   ...);
        } else {
            R out{};
            (void)((i == I
                        ? (out = f.template operator()<std::tuple_element_t<I, PrimTypes>>(), true)
                        : false) ||
                   ...);
            return out;
        }
    }
    (std::make_index_sequence<prim_type_count>{});
}

/// One object in file order: its type and its index into that type's set.
struct ObjectRef {
    PrimType type = PrimType::sphere;
    std::uint32_t index = 0;
    friend bool operator==(const ObjectRef&, const ObjectRef&) = default;
};

/// A whole scene. Every object's `material` indexes `materials`; `order` lists every object exactly
/// once in file order.
struct Scene {
    Camera camera;
    Vec3f background{0, 0, 0};
    std::vector<Light> lights;
    std::vector<Material> materials;
    std::vector<SphereObject> spheres;
    std::vector<MeshObject> meshes;
    std::vector<PolygonObject> polygons;
    std::vector<BoxObject> boxes;
    std::vector<ObbObject> obbs;
    std::vector<ImplicitObject> implicits;
    std::vector<ConeObject> cones;
    std::vector<ObjectRef> order;

    /// Appends an object to its type's set and to `order`; returns its reference.
    template <class O>
    requires(prim_index_v<O> < prim_type_count) ObjectRef add(O o) {
        auto& set = PrimOf<O>::objects(*this);
        set.push_back(std::move(o));
        const ObjectRef r{prim_type_v<PrimOf<O>>, static_cast<std::uint32_t>(set.size() - 1)};
        order.push_back(r);
        return r;
    }
    /// Index of the material called `name`, or -1 when there is none.
    int find_material(std::string_view name) const;

    friend bool operator==(const Scene&, const Scene&) = default;
};

/// Calls f.template operator()<P>(object) for the object r refers to, P its table entry, and
/// returns the result (see visit_prim_type).
template <class F>
decltype(auto) visit_object(const Scene& s, ObjectRef r, F&& f) {
    return visit_prim_type(r.type, [&]<class P>() -> decltype(auto) {
        return f.template operator()<P>(P::objects(s)[r.index]);
    });
}

/// Number of global primitives an object contributes: a mesh's triangle count, 1 otherwise.
std::uint32_t primitive_count(const Scene& s, ObjectRef r);

/// First global primitive id of each object, parallel to s.order, plus one final entry holding the
/// total. Contract: objects in file order; a mesh's triangles in file (fan) order.
std::vector<std::uint32_t> primitive_id_base(const Scene& s);

/// Where a global primitive id lives: the object (position in s.order) and the primitive within it.
struct PrimitiveLocation {
    std::uint32_t object = 0;  ///< index into Scene::order
    std::uint32_t local = 0;   ///< triangle index for meshes, 0 otherwise
};

/// Inverse of primitive_id_base: locates `id` (< bases.back()) by binary search over `bases`.
PrimitiveLocation locate_primitive(const std::vector<std::uint32_t>& bases, std::uint32_t id);

/// Material index of one object.
std::uint32_t object_material(const Scene& s, ObjectRef r);

/// Bounding box of one object (an implicit's box encloses its whole surface).
Bounds3f object_bounds(const Scene& s, ObjectRef r);

/// One box per global primitive, in global id order.
std::vector<Bounds3f> primitive_bounds(const Scene& s);

/// Box around every object (empty when the scene has none).
Bounds3f scene_bounds(const Scene& s);

/// What a scene needs from a renderer: primitive types present and shading paths used by the
/// materials of actual objects and by the lights.
struct SceneFeatures {
    std::array<bool, prim_type_count> prims{};  ///< indexed by PrimType
    bool shadows = false;                       ///< any light
    bool reflection = false;                    ///< any used material with reflect > 0
    bool refraction = false;                    ///< any used material with transmit > 0
    bool fresnel = false;     ///< any used reflective/refractive material with fresnel
    bool absorption = false;  ///< any used refractive material with absorption > 0
    bool dispersion = false;  ///< any used refractive material with dispersion > 0
    bool textures = false;    ///< any used material with a texture
    friend bool operator==(const SceneFeatures&, const SceneFeatures&) = default;
};

/// The features of s (see SceneFeatures).
SceneFeatures features(const Scene& s);

/// Names of the enabled features in a fixed order: primitive types first ("sphere", "mesh", ...),
/// then "shadows", "reflection", "refraction", "fresnel", "absorption", "dispersion", "textures".
std::vector<std::string> feature_names(const SceneFeatures& f);

}  // namespace rtlab
