// Scene helpers: adding objects, the global primitive id contract, bounds and features.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>

namespace rtlab {

std::string_view to_string(PrimType t) {
    const std::string_view name =
        visit_prim_type(t, []<class P>() { return std::string_view(P::name); });
    return name.empty() ? "?" : name;
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

int Scene::find_material(std::string_view name) const {
    for (std::size_t i = 0; i < materials.size(); ++i) {
        if (materials[i].name == name) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

std::uint32_t primitive_count(const Scene& s, ObjectRef r) {
    return visit_object(s, r, []<class P>(const auto& o) { return P::count(o); });
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

Bounds3f object_bounds(const Scene& s, ObjectRef r) {
    return visit_object(s, r, []<class P>(const auto& o) { return P::bounds(o); });
}

std::vector<Bounds3f> primitive_bounds(const Scene& s) {
    std::vector<Bounds3f> out;
    out.reserve(primitive_id_base(s).back());
    for (const ObjectRef& r : s.order) {
        visit_object(s, r, [&]<class P>(const auto& o) {
            for (std::uint32_t i = 0; i < P::count(o); ++i) {
                out.push_back(P::prim_bounds(o, i));
            }
        });
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

std::uint32_t object_material(const Scene& s, ObjectRef r) {
    return visit_object(s, r, []<class P>(const auto& o) { return o.material; });
}

SceneFeatures features(const Scene& s) {
    SceneFeatures f;
    std::vector<bool> used(s.materials.size(), false);
    for (const ObjectRef& r : s.order) {
        if (primitive_count(s, r) == 0) {
            continue;
        }
        f.prims[static_cast<std::size_t>(r.type)] = true;
        const std::uint32_t m = object_material(s, r);
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
