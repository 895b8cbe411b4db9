// NFF documents to and from Scenes.
#include "base/error.h"
#include "scene/nff_io.h"

#include <cmath>
#include <type_traits>

namespace rtlab::nff {

namespace {

Material fill_material(const Fill& f, std::size_t index) {
    Material m;
    m.name = std::string("nff").append(std::to_string(index));
    m.color = Vec3f(f.color);
    m.diffuse = static_cast<float>(f.kd);
    m.specular = static_cast<float>(f.ks);
    m.shininess = static_cast<float>(f.shine);
    m.reflect = static_cast<float>(f.ks);
    m.transmit = static_cast<float>(f.t);
    m.ior = static_cast<float>(std::max(1.0, f.ior));
    return m;
}

std::vector<Vec3f> to_float(const std::vector<Vec3d>& v) {
    std::vector<Vec3f> out;
    out.reserve(v.size());
    for (const Vec3d& p : v) {
        out.push_back(Vec3f(p));
    }
    return out;
}

}  // namespace

Scene to_scene(const Document& d, std::string_view what) {
    Scene s;
    bool has_view = false;
    std::size_t plain_lights = 0;
    for (const Record& r : d.records) {
        if (const auto* l = std::get_if<Light>(&r); l != nullptr && !l->has_color) {
            ++plain_lights;
        }
    }
    const float intensity =
        plain_lights > 0 ? static_cast<float>(1.0 / std::sqrt(static_cast<double>(plain_lights)))
                         : 1.0f;
    int material = -1;
    const auto current_material = [&] {
        if (material < 0) {  // primitives before any fill: NFF's default white matte
            s.materials.push_back(fill_material(Fill{}, s.materials.size()));
            material = static_cast<int>(s.materials.size()) - 1;
        }
        return static_cast<std::uint32_t>(material);
    };
    for (const Record& r : d.records) {
        std::visit(
            [&](const auto& rec) {
                using R = std::decay_t<decltype(rec)>;
                if constexpr (std::is_same_v<R, View>) {
                    has_view = true;
                    s.camera.from = Vec3f(rec.from);
                    s.camera.at = Vec3f(rec.at);
                    s.camera.up = Vec3f(rec.up);
                    s.camera.fov_deg = static_cast<float>(rec.angle);
                    s.camera.width = rec.width;
                    s.camera.height = rec.height;
                } else if constexpr (std::is_same_v<R, Background>) {
                    s.background = Vec3f(rec.color);
                } else if constexpr (std::is_same_v<R, Light>) {
                    Light l = rec;
                    rtlab::Light out;
                    out.position = Vec3f(l.position);
                    out.color =
                        l.has_color ? Vec3f(l.color) : Vec3f{intensity, intensity, intensity};
                    s.lights.push_back(out);
                } else if constexpr (std::is_same_v<R, Fill>) {
                    s.materials.push_back(fill_material(rec, s.materials.size()));
                    material = static_cast<int>(s.materials.size()) - 1;
                } else if constexpr (std::is_same_v<R, Sphere>) {
                    s.add(SphereObject{Vec3f(rec.center), static_cast<float>(rec.radius),
                                       current_material()});
                } else if constexpr (std::is_same_v<R, Cone>) {
                    ConeObject c;
                    c.base = Vec3f(rec.base);
                    c.base_radius = static_cast<float>(rec.base_radius);
                    c.apex = Vec3f(rec.apex);
                    c.apex_radius = static_cast<float>(rec.apex_radius);
                    c.caps = ConeCaps::none;  // NFF cones are open
                    c.material = current_material();
                    s.add(c);
                } else {
                    s.add(PolygonObject{to_float(rec.vertices), current_material(),
                                        to_float(rec.normals)});
                }
            },
            r);
    }
    if (!has_view) {
        throw Error(std::string(what) + ": no view ('v' record)");
    }
    if (s.order.empty()) {
        throw Error(std::string(what) + ": no sphere, cone or polygon");
    }
    return s;
}

Document from_scene(const Scene& s) {
    Document d;
    d.records.push_back(Background{Vec3d(s.background)});
    View v;
    v.from = Vec3d(s.camera.from);
    v.at = Vec3d(s.camera.at);
    v.up = Vec3d(s.camera.up);
    v.angle = double(s.camera.fov_deg);
    v.width = s.camera.width;
    v.height = s.camera.height;
    d.records.push_back(v);
    const double rule = s.lights.empty() ? 1.0 : 1.0 / std::sqrt(double(s.lights.size()));
    for (const rtlab::Light& l : s.lights) {
        if (l.kind != LightKind::point) {
            throw Error("NFF has no directional lights");
        }
        Light out;
        out.position = Vec3d(l.position);
        const Vec3f c = l.color;
        const auto f = static_cast<float>(rule);
        out.has_color = !(c.x == f && c.y == f && c.z == f);
        out.color = Vec3d(c);
        d.records.push_back(out);
    }
    int last = -1;
    const auto fill = [&](std::uint32_t m) {
        if (static_cast<int>(m) == last) {
            return;
        }
        last = static_cast<int>(m);
        const Material& mat = s.materials[m];
        Fill f;
        f.color = Vec3d(mat.color);
        f.kd = double(mat.diffuse);
        f.ks = double(mat.specular);
        f.shine = double(mat.shininess);
        f.t = double(mat.transmit);
        f.ior = double(mat.ior);
        d.records.push_back(f);
    };
    for (const ObjectRef& r : s.order) {
        visit_object(s, r, [&]<class P>(const auto& o) {
            using O = std::decay_t<decltype(o)>;
            if constexpr (std::is_same_v<O, SphereObject>) {
                fill(o.material);
                d.records.push_back(Sphere{Vec3d(o.center), double(o.radius)});
            } else if constexpr (std::is_same_v<O, PolygonObject>) {
                fill(o.material);
                Polygon p;
                for (const Vec3f& q : o.vertices) {
                    p.vertices.push_back(Vec3d(q));
                }
                for (const Vec3f& q : o.normals) {
                    p.normals.push_back(Vec3d(q));
                }
                d.records.push_back(std::move(p));
            } else if constexpr (std::is_same_v<O, ConeObject>) {
                if (o.caps != ConeCaps::none) {
                    throw Error("NFF cones have no caps");
                }
                fill(o.material);
                d.records.push_back(Cone{Vec3d(o.base), double(o.base_radius), Vec3d(o.apex),
                                         double(o.apex_radius)});
            } else if constexpr (std::is_same_v<O, MeshObject>) {
                fill(o.material);
                for (const auto& t : o.mesh.triangles) {
                    Polygon p;
                    for (const std::uint32_t i : t) {
                        p.vertices.push_back(Vec3d(o.mesh.positions[i]));
                    }
                    d.records.push_back(std::move(p));
                }
            } else {
                throw Error(std::string("NFF has no ").append(P::name).append(" primitive"));
            }
        });
    }
    return d;
}

Scene load_scene_nff(const std::filesystem::path& path) {
    return to_scene(load(path), path.string());
}

}  // namespace rtlab::nff
