// Scene helpers: adding objects, the global primitive id contract, bounds and features.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>

namespace rtlab {

std::string_view to_string(PrimType t) {
    switch (t) {
    case PrimType::sphere:
        return "sphere";
    case PrimType::mesh:
        return "mesh";
    case PrimType::polygon:
        return "polygon";
    case PrimType::box:
        return "box";
    case PrimType::obb:
        return "obb";
    case PrimType::implicit:
        return "implicit";
    }
    return "?";
}

std::string_view to_string(ImplicitKind k) {
    switch (k) {
    case ImplicitKind::torus:
        return "torus";
    case ImplicitKind::tanglecube:
        return "tanglecube";
    }
    return "?";
}

namespace {

template <class T>
ObjectRef push(std::vector<T>& set, std::vector<ObjectRef>& order, PrimType type, T o) {
    set.push_back(std::move(o));
    const ObjectRef r{type, static_cast<std::uint32_t>(set.size() - 1)};
    order.push_back(r);
    return r;
}

}  // namespace

ObjectRef Scene::add(SphereObject o) {
    return push(spheres, order, PrimType::sphere, o);
}
ObjectRef Scene::add(MeshObject o) {
    return push(meshes, order, PrimType::mesh, std::move(o));
}
ObjectRef Scene::add(PolygonObject o) {
    return push(polygons, order, PrimType::polygon, std::move(o));
}
ObjectRef Scene::add(BoxObject o) {
    return push(boxes, order, PrimType::box, o);
}
ObjectRef Scene::add(ObbObject o) {
    return push(obbs, order, PrimType::obb, o);
}
ObjectRef Scene::add(ImplicitObject o) {
    return push(implicits, order, PrimType::implicit, o);
}

int Scene::find_material(std::string_view name) const {
    for (std::size_t i = 0; i < materials.size(); ++i) {
        if (materials[i].name == name) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

std::uint32_t primitive_count(const Scene& s, ObjectRef r) {
    if (r.type == PrimType::mesh) {
        return static_cast<std::uint32_t>(s.meshes[r.index].mesh.triangle_count());
    }
    return 1;
}

std::vector<std::uint32_t> primitive_id_base(const Scene& s) {
    std::vector<std::uint32_t> bases;
    bases.reserve(s.order.size() + 1);
    std::uint32_t next = 0;
    for (const ObjectRef& r : s.order) {
        bases.push_back(next);
        next += primitive_count(s, r);
    }
    bases.push_back(next);
    return bases;
}

PrimitiveLocation locate_primitive(const std::vector<std::uint32_t>& bases, std::uint32_t id) {
    // The last base <= id whose object is non-empty: upper_bound finds the first base > id.
    const auto it = std::upper_bound(bases.begin(), bases.end() - 1, id);
    const auto object = static_cast<std::uint32_t>(it - bases.begin() - 1);
    return {object, id - bases[object]};
}

namespace {

/// Box of an implicit surface, from the kind's analytic extent.
Bounds3f implicit_bounds(const ImplicitObject& o) {
    Vec3f half;
    switch (o.kind) {
    case ImplicitKind::torus:
        half = Vec3f{o.major + o.minor, o.major + o.minor, o.minor};
        break;
    case ImplicitKind::tanglecube:
        // Along an axis the surface reaches x^4 - 5x^2 - 0.7 = 0 (other coordinates at the minimum
        // of t^4 - 5t^2), x = 2.2663...; 2.27 covers it.
        half = Vec3f{2.27f, 2.27f, 2.27f} * o.scale;
        break;
    }
    return {o.center - half, o.center + half};
}

}  // namespace

Bounds3f object_bounds(const Scene& s, ObjectRef r) {
    switch (r.type) {
    case PrimType::sphere: {
        const SphereObject& o = s.spheres[r.index];
        const Vec3f h{o.radius, o.radius, o.radius};
        return {o.center - h, o.center + h};
    }
    case PrimType::mesh:
        return s.meshes[r.index].mesh.bounds();
    case PrimType::polygon: {
        Bounds3f b;
        for (const Vec3f& v : s.polygons[r.index].vertices) {
            b.extend(v);
        }
        return b;
    }
    case PrimType::box:
        return s.boxes[r.index].bounds;
    case PrimType::obb: {
        const ObbObject& o = s.obbs[r.index];
        const Vec3f h =
            abs(o.axes[0]) * o.half.x + abs(o.axes[1]) * o.half.y + abs(o.axes[2]) * o.half.z;
        return {o.center - h, o.center + h};
    }
    case PrimType::implicit:
        return implicit_bounds(s.implicits[r.index]);
    }
    return {};
}

std::vector<Bounds3f> primitive_bounds(const Scene& s) {
    std::vector<Bounds3f> out;
    out.reserve(primitive_id_base(s).back());
    for (const ObjectRef& r : s.order) {
        if (r.type == PrimType::mesh) {
            const TriangleMesh& m = s.meshes[r.index].mesh;
            for (std::size_t i = 0; i < m.triangle_count(); ++i) {
                out.push_back(m.triangle_bounds(i));
            }
        } else {
            out.push_back(object_bounds(s, r));
        }
    }
    return out;
}

Bounds3f scene_bounds(const Scene& s) {
    Bounds3f b;
    for (const ObjectRef& r : s.order) {
        b.extend(object_bounds(s, r));
    }
    return b;
}

namespace {

std::uint32_t material_of(const Scene& s, ObjectRef r) {
    switch (r.type) {
    case PrimType::sphere:
        return s.spheres[r.index].material;
    case PrimType::mesh:
        return s.meshes[r.index].material;
    case PrimType::polygon:
        return s.polygons[r.index].material;
    case PrimType::box:
        return s.boxes[r.index].material;
    case PrimType::obb:
        return s.obbs[r.index].material;
    case PrimType::implicit:
        return s.implicits[r.index].material;
    }
    return 0;
}

}  // namespace

SceneFeatures features(const Scene& s) {
    SceneFeatures f;
    std::vector<bool> used(s.materials.size(), false);
    for (const ObjectRef& r : s.order) {
        if (r.type == PrimType::mesh && s.meshes[r.index].mesh.empty()) {
            continue;
        }
        f.prims[static_cast<std::size_t>(r.type)] = true;
        const std::uint32_t m = material_of(s, r);
        if (m < used.size()) {
            used[m] = true;
        }
    }
    f.shadows = !s.lights.empty();
    for (std::size_t i = 0; i < s.materials.size(); ++i) {
        if (!used[i]) {
            continue;
        }
        const Material& m = s.materials[i];
        const bool refractive = m.transmit > 0;
        f.reflection = f.reflection || m.reflect > 0;
        f.refraction = f.refraction || refractive;
        f.fresnel = f.fresnel || (m.fresnel && (refractive || m.reflect > 0));
        f.absorption = f.absorption || (refractive && max_component(m.absorption) > 0);
        f.dispersion = f.dispersion || (refractive && m.dispersion > 0);
        f.textures = f.textures || m.texture.kind != TextureKind::none;
    }
    return f;
}

std::vector<std::string> feature_names(const SceneFeatures& f) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < prim_type_count; ++i) {
        if (f.prims[i]) {
            out.emplace_back(to_string(static_cast<PrimType>(i)));
        }
    }
    const std::pair<bool, const char*> flags[] = {
        {f.shadows, "shadows"},  {f.reflection, "reflection"}, {f.refraction, "refraction"},
        {f.fresnel, "fresnel"},  {f.absorption, "absorption"}, {f.dispersion, "dispersion"},
        {f.textures, "textures"}};
    for (const auto& [on, name] : flags) {
        if (on) {
            out.emplace_back(name);
        }
    }
    return out;
}

}  // namespace rtlab
