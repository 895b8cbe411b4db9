// Scene JSON writing (format: docs/scene-format.md): floats in their shortest decimal form, meshes
// beside the scene file, every write through a temporary file and a rename.
#include "base/atomic_file.h"
#include "mesh/mesh_io.h"
#include "scene/scene_json.h"

#include <charconv>
#include <string>
#include <system_error>
#include <vector>

namespace rtlab {

namespace {

using scene_json::Json;

/// A float as the double whose shortest decimal form reads back as the same float, so files show
/// "0.8" rather than "0.800000011920929" and still round-trip exactly.
double tidy(float f) {
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), f);
    double d = static_cast<double>(f);
    if (ec == std::errc()) {
        std::from_chars(buf, end, d);
    }
    return d;
}

Json vec_json(const Vec3f& v) {
    return Json::array({tidy(v.x), tidy(v.y), tidy(v.z)});
}

/// What a table entry's `write` sees of one object being written: JSON fields in call order,
/// and the mesh files beside the scene file.
class ObjectWriter {
public:
    ObjectWriter(const std::filesystem::path& scene_path, bool write_meshes, std::uint32_t index)
        : scene_path_(scene_path), write_meshes_(write_meshes), index_(index) {}
    /// Field `key` = v.
    void vec3(std::string_view key, const Vec3f& v) { j_[std::string(key)] = vec_json(v); }
    /// Field `key` = f (shortest decimal form).
    void number(std::string_view key, float f) { j_[std::string(key)] = tidy(f); }
    /// Field `key` = text.
    void string(std::string_view key, const std::string& text) { j_[std::string(key)] = text; }
    /// Field `key` = array of vectors.
    void vec3_array(std::string_view key, const std::vector<Vec3f>& vs) {
        Json a = Json::array();
        for (const Vec3f& v : vs) {
            a.push_back(vec_json(v));
        }
        j_[std::string(key)] = a;
    }
    /// File name a mesh is referenced by: written beside the scene file as
    /// "<stem>.mesh<index>.ply" with write_meshes, else its own `file` (which must be non-empty).
    std::string external_mesh(const TriangleMesh& mesh, const std::string& file) const {
        if (write_meshes_) {
            const std::string name =
                scene_path_.stem().string() + ".mesh" + std::to_string(index_) + ".ply";
            save_mesh(mesh, scene_path_.parent_path() / name);
            return name;
        }
        if (file.empty()) {
            throw Error(scene_path_.string() + ": meshes[" + std::to_string(index_) +
                        "] has no file name; save with write_meshes");
        }
        return file;
    }
    /// The object written so far.
    const Json& json() const { return j_; }

private:
    Json j_ = Json::object();
    const std::filesystem::path& scene_path_;
    bool write_meshes_;
    std::uint32_t index_;
};

}  // namespace

void save_scene(const Scene& s, const std::filesystem::path& path, bool write_meshes) {
    validate_scene(s, path.string());
    Json doc;
    doc["camera"] = Json{{"from", vec_json(s.camera.from)}, {"at", vec_json(s.camera.at)},
                         {"up", vec_json(s.camera.up)},     {"fov_deg", tidy(s.camera.fov_deg)},
                         {"width", s.camera.width},         {"height", s.camera.height}};
    doc["background"] = vec_json(s.background);
    doc["lights"] = Json::array();
    for (const Light& l : s.lights) {
        const bool point = l.kind == LightKind::point;
        doc["lights"].push_back(Json{{"type", point ? "point" : "directional"},
                                     {point ? "position" : "direction", vec_json(l.position)},
                                     {"color", vec_json(l.color)}});
    }
    doc["materials"] = Json::object();
    for (const Material& m : s.materials) {
        Json jm{{"color", vec_json(m.color)},
                {"ambient", tidy(m.ambient)},
                {"diffuse", tidy(m.diffuse)},
                {"specular", tidy(m.specular)},
                {"shininess", tidy(m.shininess)},
                {"reflect", tidy(m.reflect)},
                {"transmit", tidy(m.transmit)},
                {"ior", tidy(m.ior)},
                {"fresnel", m.fresnel},
                {"absorption", vec_json(m.absorption)},
                {"dispersion", tidy(m.dispersion)}};
        if (m.texture.kind != TextureKind::none) {
            jm["texture"] = Json{{"type", "checker"},
                                 {"color2", vec_json(m.texture.color2)},
                                 {"scale", tidy(m.texture.scale)}};
        }
        doc["materials"][m.name] = jm;
    }
    doc["objects"] = Json::array();
    for (const ObjectRef& r : s.order) {
        ObjectWriter out(path, write_meshes, r.index);
        out.string("type", std::string(to_string(r.type)));
        visit_object(s, r, [&]<class P>(const auto& o) {
            P::write(o, out);
            out.string("material", s.materials[o.material].name);
        });
        doc["objects"].push_back(out.json());
    }
    write_file_atomically(path, doc.dump(2) + "\n");  // base/atomic_file.h
}

}  // namespace rtlab
