#pragma once
// Scene: one primitive set per primitive type, plus camera, lights and materials. Objects keep the
// order of the scene file; global primitive ids follow that order (see primitive_id_base).

#include "intersect/bounds.h"
#include "intersect/vec.h"
#include "mesh/triangle_mesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
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

/// Primitive types a scene can hold.
enum class PrimType : std::uint8_t { sphere, mesh, polygon, box, obb, implicit };

/// Number of primitive types.
inline constexpr std::size_t prim_type_count = 6;

/// Lower-case name of a primitive type as used in scene files ("sphere", "mesh", ...).
std::string_view to_string(PrimType t);

/// A sphere object.
struct SphereObject {
    Vec3f center;
    float radius = 1;  ///< > 0
    std::uint32_t material = 0;
    friend bool operator==(const SphereObject&, const SphereObject&) = default;
};

/// A triangle mesh object; `file` is where it came from (relative to the scene file), may be empty.
struct MeshObject {
    TriangleMesh mesh;
    std::string file;
    std::uint32_t material = 0;
    friend bool operator==(const MeshObject&, const MeshObject&) = default;
};

/// A planar polygon (>= 3 vertices, assumed planar; may be concave), one primitive.
struct PolygonObject {
    std::vector<Vec3f> vertices;
    std::uint32_t material = 0;
    friend bool operator==(const PolygonObject&, const PolygonObject&) = default;
};

/// An axis-aligned box (lo <= hi on every axis).
struct BoxObject {
    Bounds3f bounds;
    std::uint32_t material = 0;
    friend bool operator==(const BoxObject&, const BoxObject&) = default;
};

/// An oriented box: centre, three orthonormal axes and the half extent along each (> 0).
struct ObbObject {
    Vec3f center;
    std::array<Vec3f, 3> axes{Vec3f{1, 0, 0}, Vec3f{0, 1, 0}, Vec3f{0, 0, 1}};
    Vec3f half{1, 1, 1};
    std::uint32_t material = 0;
    friend bool operator==(const ObbObject&, const ObbObject&) = default;
};

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
    std::vector<ObjectRef> order;

    /// Appends an object to its set and to `order`; returns its reference.
    ObjectRef add(SphereObject o);
    /// Appends a mesh object (see add(SphereObject)).
    ObjectRef add(MeshObject o);
    /// Appends a polygon object (see add(SphereObject)).
    ObjectRef add(PolygonObject o);
    /// Appends a box object (see add(SphereObject)).
    ObjectRef add(BoxObject o);
    /// Appends an oriented box object (see add(SphereObject)).
    ObjectRef add(ObbObject o);
    /// Appends an implicit surface object (see add(SphereObject)).
    ObjectRef add(ImplicitObject o);
    /// Index of the material called `name`, or -1 when there is none.
    int find_material(std::string_view name) const;

    friend bool operator==(const Scene&, const Scene&) = default;
};

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
