// Scene checks shared by reading a scene file and validate_scene (scene/scene_json.h), the
// automatic camera, and validate_scene itself. Every error names the file and the JSON path.
#include "scene/scene_json.h"

#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <vector>

namespace rtlab {

namespace scene_json {

void check_camera(const Camera& c, const JsonPath& at) {
    if (!is_finite(c.from) || !is_finite(c.at) || !is_finite(c.up)) {
        at.fail("non-finite vector");
    }
    if (!(c.fov_deg > 0 && c.fov_deg < 180)) {
        (at / "fov_deg").fail("must be in (0, 180)");
    }
    if (c.width < 1 || c.width > max_image_side) {
        (at / "width").fail("must be in 1.." + std::to_string(max_image_side));
    }
    if (c.height < 1 || c.height > max_image_side) {
        (at / "height").fail("must be in 1.." + std::to_string(max_image_side));
    }
    const Vec3f dir = c.at - c.from;
    if (!is_finite(dir)) {
        (at / "at").fail("too far from 'from' for float precision ('at' - 'from' overflows)");
    }
    if (length_squared(dir) == 0) {
        (at / "at").fail("must differ from 'from'");
    }
    if (length_squared(cross(dir, c.up)) == 0) {
        (at / "up").fail("must not be zero or parallel to the view direction");
    }
    // The frame the renderer and ray generator build (trace/camera.h), in float: it must be
    // orthonormal, or every eye ray is NaN.
    const auto unit = [](const Vec3f& v) {
        return is_finite(v) && std::abs(length(v) - 1.0f) < 1e-3f;
    };
    const Vec3f forward = normalize(dir);
    if (!unit(forward)) {
        (at / "at").fail(
            "the view direction 'at' - 'from' cannot be normalised in float precision "
            "(too long or too short)");
    }
    if (!unit(normalize(cross(forward, c.up)))) {
        (at / "up").fail(
            "cannot be used in float precision (too long, too short or nearly parallel "
            "to the view direction)");
    }
}

Camera framing_camera(const Scene& s, const JsonPath& at) {
    const Bounds3f b = scene_bounds(s);
    const Camera c = camera_framing(b);
    const Vec3f dir = c.at - c.from;
    const Vec3f forward = normalize(dir);
    if (!is_finite(c.from) || !is_finite(c.at) || !is_finite(forward) ||
        std::abs(length(forward) - 1.0f) >= 1e-3f) {
        at.fail(
            "no camera given, and none can be framed automatically: the scene's extent "
            "overflows float precision (add a \"camera\")");
    }
    return c;
}

void check_material(const Material& m, const JsonPath& at) {
    require_non_negative(m.color, at / "color");
    require_non_negative(m.ambient, at / "ambient");
    require_non_negative(m.diffuse, at / "diffuse");
    require_non_negative(m.specular, at / "specular");
    require_non_negative(m.shininess, at / "shininess");
    require_non_negative(m.reflect, at / "reflect");
    require_non_negative(m.transmit, at / "transmit");
    require_positive(m.ior, at / "ior");
    require_non_negative(m.absorption, at / "absorption");
    require_non_negative(m.dispersion, at / "dispersion");
    require_non_negative(m.texture.color2, at / "texture" / "color2");
    require_positive(m.texture.scale, at / "texture" / "scale");
}

void check_light(const Light& l, const JsonPath& at) {
    if (!is_finite(l.position)) {
        at.fail("non-finite vector");
    }
    if (l.kind == LightKind::directional && length_squared(l.position) == 0) {
        (at / "direction").fail("must not be zero");
    }
    require_non_negative(l.color, at / "color");
}

namespace {

void check_material_index(std::uint32_t m, const Scene& s, const JsonPath& at) {
    if (m >= s.materials.size()) {
        (at / "material").fail("material index out of range");
    }
}

}  // namespace

void check_object(const Scene& s, ObjectRef r, const JsonPath& at) {
    visit_object(s, r, [&]<class P>(const auto& o) {
        P::check(o, at);
        check_material_index(o.material, s, at);
    });
}

}  // namespace scene_json

using scene_json::JsonPath;

Camera camera_framing(const Bounds3f& b, float fov_deg, int width, int height) {
    Camera c;
    c.fov_deg = fov_deg;
    c.width = width;
    c.height = height;
    if (b.empty()) {
        return c;
    }
    const Vec3f center = b.center();
    float radius = 0.5f * length(b.diagonal());
    if (!(radius > 0)) {
        radius = 1;
    }
    // The bounding sphere fits the vertical field of view (and the horizontal one when wider).
    const float half = 0.5f * fov_deg * std::numbers::pi_v<float> / 180.0f;
    const float distance = radius / std::sin(half);
    c.at = center;
    c.from = center + Vec3f{0, 0, distance};
    c.up = {0, 1, 0};
    return c;
}

void validate_scene(const Scene& s, std::string_view what) {
    const JsonPath root(std::string(what), "");
    scene_json::check_camera(s.camera, root / "camera");
    if (!is_finite(s.background) || !(min_component(s.background) >= 0)) {
        (root / "background").fail("components must be finite and >= 0");
    }
    for (std::size_t i = 0; i < s.lights.size(); ++i) {
        scene_json::check_light(s.lights[i], (root / "lights")[i]);
    }
    std::set<std::string> names;
    for (const Material& m : s.materials) {
        if (!names.insert(m.name).second) {
            (root / "materials" / m.name).fail("duplicate material name");
        }
        scene_json::check_material(m, root / "materials" / m.name);
    }
    std::size_t sizes[prim_type_count] = {};
    for_each_type<PrimTypes>(
        [&]<class P>() { sizes[static_cast<std::size_t>(prim_type_v<P>)] = P::objects(s).size(); });
    std::size_t total = 0;
    for (const std::size_t n : sizes) {
        total += n;
    }
    std::vector<std::vector<bool>> seen(prim_type_count);
    for (std::size_t t = 0; t < prim_type_count; ++t) {
        seen[t].assign(sizes[t], false);
    }
    if (s.order.size() != total) {
        (root / "objects")
            .fail("order lists " + std::to_string(s.order.size()) + " objects, sets hold " +
                  std::to_string(total));
    }
    for (std::size_t i = 0; i < s.order.size(); ++i) {
        const ObjectRef r = s.order[i];
        const auto t = static_cast<std::size_t>(r.type);
        if (t >= prim_type_count || r.index >= sizes[t] || seen[t][r.index]) {
            (root / "objects")[i].fail("bad or repeated object reference");
        }
        seen[t][r.index] = true;
        scene_json::check_object(s, r, (root / "objects")[i]);
    }
    if (primitive_id_base(s).back() == 0xFFFFFFFFu) {
        root.fail("too many primitives for 32-bit ids");
    }
}

}  // namespace rtlab
