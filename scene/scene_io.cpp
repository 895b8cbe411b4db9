// Scene JSON reading and writing (format: docs/scene-format.md). Every error names the file and the
// JSON path of the offending field; every write goes through a temporary file and a rename.
#include "scene/scene_io.h"

#include "base/atomic_file.h"
#include "mesh/mesh_io.h"
#include "scene/nff_io.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace rtlab {

namespace {

using Json = nlohmann::ordered_json;

/// Largest accepted image side in pixels.
constexpr int max_image_side = 16384;

/// A position in the JSON document, for error messages ("objects[3].radius").
class JsonPath {
public:
    JsonPath(std::string what, std::string path) : what_(std::move(what)), path_(std::move(path)) {}
    JsonPath operator/(std::string_view key) const {
        return {what_, path_.empty() ? std::string(key) : path_ + "." + std::string(key)};
    }
    JsonPath operator[](std::size_t i) const {
        return {what_, path_ + "[" + std::to_string(i) + "]"};
    }
    [[noreturn]] void fail(const std::string& problem) const {
        throw Error(what_ + ": " + (path_.empty() ? std::string("(top level)") : path_) + ": " +
                    problem);
    }
    const std::string& what() const { return what_; }

private:
    std::string what_;
    std::string path_;
};

void require_object(const Json& j, const JsonPath& at) {
    if (!j.is_object()) {
        at.fail("must be an object");
    }
}

/// Rejects keys outside `allowed` (the first unknown one is named).
void check_keys(const Json& j,
                const JsonPath& at,
                std::initializer_list<std::string_view> allowed) {
    require_object(j, at);
    for (const auto& [key, value] : j.items()) {
        bool ok = false;
        for (std::string_view a : allowed) {
            ok = ok || a == key;
        }
        if (!ok) {
            (at / key).fail("unknown key");
        }
    }
}

const Json* find(const Json& j, std::string_view key) {
    const auto it = j.find(std::string(key));
    return it == j.end() ? nullptr : &*it;
}

const Json& required(const Json& j, const JsonPath& at, std::string_view key) {
    const Json* v = find(j, key);
    if (v == nullptr) {
        at.fail("missing required key '" + std::string(key) + "'");
    }
    return *v;
}

float to_float(const Json& j, const JsonPath& at) {
    if (!j.is_number()) {
        at.fail("must be a number");
    }
    const double d = j.get<double>();
    if (!std::isfinite(d) || std::abs(d) > double(std::numeric_limits<float>::max())) {
        at.fail("must be a finite number");
    }
    return static_cast<float>(d);
}

Vec3f to_vec3(const Json& j, const JsonPath& at) {
    if (!j.is_array() || j.size() != 3) {
        at.fail("must be an array of 3 numbers");
    }
    return {to_float(j[0], at[0]), to_float(j[1], at[1]), to_float(j[2], at[2])};
}

/// Reads optional number `key` into `out`, keeping the default when absent.
void opt_float(const Json& j, const JsonPath& at, std::string_view key, float& out) {
    if (const Json* v = find(j, key)) {
        out = to_float(*v, at / key);
    }
}

void opt_vec3(const Json& j, const JsonPath& at, std::string_view key, Vec3f& out) {
    if (const Json* v = find(j, key)) {
        out = to_vec3(*v, at / key);
    }
}

std::string to_string_value(const Json& j, const JsonPath& at) {
    if (!j.is_string()) {
        at.fail("must be a string");
    }
    return j.get<std::string>();
}

void require_positive(float v, const JsonPath& at) {
    if (!(v > 0)) {
        at.fail("must be > 0");
    }
}

void require_non_negative(float v, const JsonPath& at) {
    if (!(v >= 0)) {
        at.fail("must be >= 0");
    }
}

void require_non_negative(const Vec3f& v, const JsonPath& at) {
    if (!(min_component(v) >= 0)) {
        at.fail("components must be >= 0");
    }
}

int to_image_side(const Json& j, const JsonPath& at) {
    if (!j.is_number_integer()) {
        at.fail("must be an integer");
    }
    const auto v = j.get<std::int64_t>();
    if (v < 1 || v > max_image_side) {
        at.fail("must be in 1.." + std::to_string(max_image_side));
    }
    return static_cast<int>(v);
}

// ---- validation shared by parsing and validate_scene ------------------------------------------

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

/// The camera framing the scene's bounds when the file gives none; fails naming the reason when
/// the bounds are too large (or empty) to frame in float precision.
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

void check_material_index(std::uint32_t m, const Scene& s, const JsonPath& at) {
    if (m >= s.materials.size()) {
        (at / "material").fail("material index out of range");
    }
}

void check_object(const Scene& s, ObjectRef r, const JsonPath& at) {
    visit_object(s, r, [&]<class P>(const auto& o) {
        P::check(o, at);
        check_material_index(o.material, s, at);
    });
}

// ---- parsing ----------------------------------------------------------------------------------

Camera parse_camera(const Json& j, const JsonPath& at) {
    check_keys(j, at, {"from", "at", "up", "fov_deg", "width", "height"});
    Camera c;
    c.from = to_vec3(required(j, at, "from"), at / "from");
    c.at = to_vec3(required(j, at, "at"), at / "at");
    opt_vec3(j, at, "up", c.up);
    opt_float(j, at, "fov_deg", c.fov_deg);
    if (const Json* v = find(j, "width")) {
        c.width = to_image_side(*v, at / "width");
    }
    if (const Json* v = find(j, "height")) {
        c.height = to_image_side(*v, at / "height");
    }
    check_camera(c, at);
    return c;
}

Light parse_light(const Json& j, const JsonPath& at) {
    require_object(j, at);
    Light l;
    const std::string type = to_string_value(required(j, at, "type"), at / "type");
    if (type == "point") {
        check_keys(j, at, {"type", "position", "color"});
        l.kind = LightKind::point;
        l.position = to_vec3(required(j, at, "position"), at / "position");
    } else if (type == "directional") {
        check_keys(j, at, {"type", "direction", "color"});
        l.kind = LightKind::directional;
        l.position = to_vec3(required(j, at, "direction"), at / "direction");
    } else {
        (at / "type").fail("unknown light type '" + type + "' (point, directional)");
    }
    opt_vec3(j, at, "color", l.color);
    check_light(l, at);
    return l;
}

Material parse_material(const std::string& name, const Json& j, const JsonPath& at) {
    check_keys(j, at,
               {"color", "ambient", "diffuse", "specular", "shininess", "reflect", "transmit",
                "ior", "fresnel", "absorption", "dispersion", "texture"});
    Material m;
    m.name = name;
    opt_vec3(j, at, "color", m.color);
    opt_float(j, at, "ambient", m.ambient);
    opt_float(j, at, "diffuse", m.diffuse);
    opt_float(j, at, "specular", m.specular);
    opt_float(j, at, "shininess", m.shininess);
    opt_float(j, at, "reflect", m.reflect);
    opt_float(j, at, "transmit", m.transmit);
    opt_float(j, at, "ior", m.ior);
    if (const Json* v = find(j, "fresnel")) {
        if (!v->is_boolean()) {
            (at / "fresnel").fail("must be true or false");
        }
        m.fresnel = v->get<bool>();
    }
    opt_vec3(j, at, "absorption", m.absorption);
    opt_float(j, at, "dispersion", m.dispersion);
    if (const Json* t = find(j, "texture")) {
        const JsonPath tat = at / "texture";
        check_keys(*t, tat, {"type", "color2", "scale"});
        const std::string type = to_string_value(required(*t, tat, "type"), tat / "type");
        if (type == "checker") {
            m.texture.kind = TextureKind::checker;
        } else if (type != "none") {
            (tat / "type").fail("unknown texture type '" + type + "' (none, checker)");
        }
        opt_vec3(*t, tat, "color2", m.texture.color2);
        opt_float(*t, tat, "scale", m.texture.scale);
    }
    check_material(m, at);
    return m;
}

/// Index of the object's material (by name; "default" when absent, created on first use).
std::uint32_t object_material(const Json& j, const JsonPath& at, Scene& s) {
    std::string name = "default";
    if (const Json* v = find(j, "material")) {
        name = to_string_value(*v, at / "material");
    }
    int index = s.find_material(name);
    if (index < 0) {
        if (name != "default") {
            (at / "material").fail("unknown material '" + name + "'");
        }
        s.materials.push_back(Material{});
        index = static_cast<int>(s.materials.size() - 1);
    }
    return static_cast<std::uint32_t>(index);
}

/// What a table entry's `read` sees of one object in the JSON document.
class ObjectReader {
public:
    ObjectReader(const Json& j, const JsonPath& at, const std::filesystem::path& base_dir)
        : j_(j), at_(at), base_dir_(base_dir) {}
    /// Rejects keys outside `allowed`.
    void keys(std::initializer_list<std::string_view> allowed) const {
        check_keys(j_, at_, allowed);
    }
    /// Required 3-vector.
    Vec3f vec3(std::string_view key) const { return to_vec3(required(j_, at_, key), at_ / key); }
    /// Required number.
    float number(std::string_view key) const { return to_float(required(j_, at_, key), at_ / key); }
    /// Required string.
    std::string string(std::string_view key) const {
        return to_string_value(required(j_, at_, key), at_ / key);
    }
    /// True when the object has the key.
    bool has(std::string_view key) const { return find(j_, key) != nullptr; }
    /// Optional number (out keeps its value when absent).
    void opt_number(std::string_view key, float& out) const { opt_float(j_, at_, key, out); }
    /// Optional 3-vector (out keeps its value when absent).
    void opt_vec3(std::string_view key, Vec3f& out) const { rtlab::opt_vec3(j_, at_, key, out); }
    /// Required array of 3-vectors; of exactly `count` of them when count > 0.
    std::vector<Vec3f> vec3_array(std::string_view key, std::size_t count = 0) const {
        const Json& vs = required(j_, at_, key);
        const JsonPath vat = at_ / key;
        if (count == 0 && !vs.is_array()) {
            vat.fail("must be an array of [x, y, z]");
        }
        if (count > 0 && (!vs.is_array() || vs.size() != count)) {
            vat.fail("must be an array of " + std::to_string(count) + " vectors");
        }
        std::vector<Vec3f> out;
        for (std::size_t i = 0; i < vs.size(); ++i) {
            out.push_back(to_vec3(vs[i], vat[i]));
        }
        return out;
    }
    /// The object's path, for errors.
    const JsonPath& path() const { return at_; }
    /// Folder that relative file names start from.
    const std::filesystem::path& base_dir() const { return base_dir_; }

private:
    const Json& j_;
    const JsonPath& at_;
    const std::filesystem::path& base_dir_;
};

void parse_object(const Json& j,
                  const JsonPath& at,
                  const std::filesystem::path& base_dir,
                  Scene& s) {
    require_object(j, at);
    const std::string type = to_string_value(required(j, at, "type"), at / "type");
    std::optional<ObjectRef> r;
    std::string names;
    for_each_type<PrimTypes>([&]<class P>() {
        names += (names.empty() ? "" : ", ") + std::string(P::name);
        if (!r && type == P::name) {
            ObjectReader in(j, at, base_dir);
            typename P::Object o = P::read(in);
            o.material = object_material(j, at, s);
            r = s.add(std::move(o));
        }
    });
    if (!r) {
        (at / "type").fail("unknown object type '" + type + "' (" + names + ")");
    }
    check_object(s, *r, at);
}

std::string read_text(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        throw Error(path.string() + ": no such file");
    }
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw Error(path.string() + ": not a regular file");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error(path.string() + ": cannot open for reading");
    }
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// ---- writing ----------------------------------------------------------------------------------

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
    check_camera(s.camera, root / "camera");
    if (!is_finite(s.background) || !(min_component(s.background) >= 0)) {
        (root / "background").fail("components must be finite and >= 0");
    }
    for (std::size_t i = 0; i < s.lights.size(); ++i) {
        check_light(s.lights[i], (root / "lights")[i]);
    }
    std::set<std::string> names;
    for (const Material& m : s.materials) {
        if (!names.insert(m.name).second) {
            (root / "materials" / m.name).fail("duplicate material name");
        }
        check_material(m, root / "materials" / m.name);
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
        check_object(s, r, (root / "objects")[i]);
    }
    if (primitive_id_base(s).back() == 0xFFFFFFFFu) {
        root.fail("too many primitives for 32-bit ids");
    }
}

namespace {

/// Largest accepted JSON nesting depth (a scene needs 5; this bounds the parser's work).
constexpr int max_json_depth = 64;

/// nlohmann's parser callback: rejects duplicate keys (nlohmann would keep one silently) and
/// nesting deeper than max_json_depth, naming the JSON path.
class KeyChecker {
public:
    explicit KeyChecker(JsonPath root) : root_(std::move(root)) {}
    bool operator()(int depth, Json::parse_event_t event, Json& parsed) {
        using E = Json::parse_event_t;
        switch (event) {
        case E::object_start:
        case E::array_start:
            if (depth >= max_json_depth) {
                path(2).fail("JSON nested deeper than " + std::to_string(max_json_depth) +
                             " levels");
            }
            frames_.push_back({event == E::object_start, {}, {}, 0});
            break;
        case E::key: {
            Frame& f = frames_.back();
            f.key = parsed.get<std::string>();
            if (!f.keys.insert(f.key).second) {
                path().fail("duplicate key");
            }
            break;
        }
        case E::object_end:
        case E::array_end:
            frames_.pop_back();
            [[fallthrough]];
        case E::value:
            if (!frames_.empty() && !frames_.back().is_object) {
                ++frames_.back().index;
            }
            break;
        }
        return true;
    }

private:
    struct Frame {
        bool is_object;
        std::set<std::string> keys;
        std::string key;
        std::size_t index;
    };
    /// The current path, or its first `frames` steps followed by "..." when it is longer.
    JsonPath path(std::size_t frames = std::numeric_limits<std::size_t>::max()) const {
        JsonPath p = root_;
        for (std::size_t i = 0; i < frames_.size(); ++i) {
            const Frame& f = frames_[i];
            if (i == frames) {
                return p / "..";
            }
            p = f.is_object ? p / f.key : p[f.index];
        }
        return p;
    }
    JsonPath root_;
    std::vector<Frame> frames_;
};

}  // namespace

Scene parse_scene(std::string_view json_text,
                  const std::filesystem::path& base_dir,
                  std::string_view what) {
    const JsonPath root(std::string(what), "");
    Json doc;
    try {
        KeyChecker keys(root);
        doc = Json::parse(json_text, std::ref(keys));
    } catch (const Json::exception& e) {
        // nlohmann's message is one line: "[json.exception.parse_error.101] parse error at line 3,
        // column 5: ...".
        std::string msg = e.what();
        const std::size_t bracket = msg.find("] ");
        throw Error(std::string(what) + ": invalid JSON: " +
                    (bracket == std::string::npos ? msg : msg.substr(bracket + 2)));
    }
    check_keys(doc, root, {"camera", "background", "lights", "materials", "objects"});
    Scene s;
    if (const Json* m = find(doc, "materials")) {
        const JsonPath mat = root / "materials";
        require_object(*m, mat);
        for (const auto& [name, value] : m->items()) {
            if (name.empty()) {
                (mat / name).fail("material name must not be empty");
            }
            s.materials.push_back(parse_material(name, value, mat / name));
        }
    }
    if (const Json* l = find(doc, "lights")) {
        const JsonPath lat = root / "lights";
        if (!l->is_array()) {
            lat.fail("must be an array");
        }
        for (std::size_t i = 0; i < l->size(); ++i) {
            s.lights.push_back(parse_light((*l)[i], lat[i]));
        }
    }
    opt_vec3(doc, root, "background", s.background);
    require_non_negative(s.background, root / "background");
    const Json& objects = required(doc, root, "objects");
    const JsonPath oat = root / "objects";
    if (!objects.is_array()) {
        oat.fail("must be an array");
    }
    for (std::size_t i = 0; i < objects.size(); ++i) {
        parse_object(objects[i], oat[i], base_dir, s);
    }
    if (const Json* c = find(doc, "camera")) {
        s.camera = parse_camera(*c, root / "camera");
    } else {
        s.camera = framing_camera(s, root / "camera");
    }
    validate_scene(s, what);
    return s;
}

Scene load_scene(const std::filesystem::path& path) {
    if (is_mesh_path(path)) {
        Scene s;
        MeshObject o;
        o.mesh = load_mesh(path);
        o.file = path.filename().string();
        s.materials.push_back(Material{});
        s.add(std::move(o));
        s.camera = framing_camera(s, JsonPath(path.string(), "camera"));
        s.lights.push_back(Light{LightKind::point, s.camera.from, {1, 1, 1}});
        return s;
    }
    std::string ext = path.extension().string();
    for (char& ch : ext) {
        ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    }
    if (ext == ".nff") {
        return nff::load_scene_nff(path);
    }
    if (ext != ".json") {
        throw Error(path.string() + ": unknown scene extension '" + path.extension().string() +
                    "' (expected .json, .nff, .obj, .ply, .off or .stl)");
    }
    const std::string text = read_text(path);
    return parse_scene(text, path.parent_path(), path.string());
}

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
