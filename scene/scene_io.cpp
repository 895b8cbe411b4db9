// Scene JSON reading (format: docs/scene-format.md) and scene loading by file type. Every error
// names the file and the JSON path of the offending field. Checks shared with validate_scene:
// scene/scene_validate.cpp; writing: scene/scene_write.cpp.
#include "scene/scene_io.h"

#include "mesh/mesh_io.h"
#include "scene/nff_io.h"
#include "scene/scene_json.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <vector>

namespace rtlab {

using namespace scene_json;

namespace {

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

}  // namespace

namespace {

/// Largest accepted JSON nesting depth (a scene needs 5; this bounds the parser's work).
constexpr std::size_t max_json_depth = 64;

/// A first, streaming pass over the JSON text (nlohmann's SAX interface): rejects duplicate keys
/// (nlohmann's DOM would keep one silently) and nesting deeper than max_json_depth, naming the JSON
/// path; syntax errors are thrown as nlohmann reports them. A separate pass because nlohmann's
/// parser callback rescans the enclosing container at every object's end (quadratic: 66 s for the
/// 597,872 objects of the SF 6 flake).
class KeyChecker final : public nlohmann::json_sax<Json> {
public:
    explicit KeyChecker(JsonPath root) : root_(std::move(root)) {}

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return start(true); }
    bool start_array(std::size_t) override { return start(false); }
    bool end_object() override { return end(); }
    bool end_array() override { return end(); }
    bool key(string_t& k) override {
        Frame& f = frames_.back();
        f.key = k;
        if (!f.keys.insert(k).second) {
            path().fail("duplicate key");
        }
        return true;
    }
    bool parse_error(std::size_t,
                     const std::string&,
                     const nlohmann::detail::exception& e) override {
        throw e;  // a parse_error: parse_scene's handler words it
    }

private:
    struct Frame {
        bool is_object;
        std::set<std::string> keys;
        std::string key;
        std::size_t index;
    };
    bool start(bool is_object) {
        if (frames_.size() >= max_json_depth) {
            path(2).fail("JSON nested deeper than " + std::to_string(max_json_depth) + " levels");
        }
        frames_.push_back({is_object, {}, {}, 0});
        return true;
    }
    bool end() {
        frames_.pop_back();
        return value();
    }
    /// A value ended: the next one in an array has the next index.
    bool value() {
        if (!frames_.empty() && !frames_.back().is_object) {
            ++frames_.back().index;
        }
        return true;
    }
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
        Json::sax_parse(json_text, &keys);
        doc = Json::parse(json_text);
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

}  // namespace rtlab
