#pragma once
// What scene/scene_io.cpp (reading), scene/scene_validate.cpp and scene/scene_write.cpp share:
// the JSON type, paths into the document for error messages ("objects[3].radius"), and the checks
// that reading a file and validate_scene both run. Internal to scene/.

#include "scene/scene_io.h"

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace rtlab::scene_json {

using Json = nlohmann::ordered_json;

/// Largest accepted image side in pixels.
inline constexpr int max_image_side = 16384;

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

inline void require_positive(float v, const JsonPath& at) {
    if (!(v > 0)) {
        at.fail("must be > 0");
    }
}

inline void require_non_negative(float v, const JsonPath& at) {
    if (!(v >= 0)) {
        at.fail("must be >= 0");
    }
}

inline void require_non_negative(const Vec3f& v, const JsonPath& at) {
    if (!(min_component(v) >= 0)) {
        at.fail("components must be >= 0");
    }
}

/// The camera's vectors, field of view and image size, and that the renderer's frame is
/// orthonormal in float.
void check_camera(const Camera& c, const JsonPath& at);
/// The camera framing the scene's bounds when the file gives none; fails naming the reason when
/// the bounds are too large (or empty) to frame in float precision.
Camera framing_camera(const Scene& s, const JsonPath& at);
/// Non-negative colours and coefficients, positive index of refraction and texture scale.
void check_material(const Material& m, const JsonPath& at);
/// A finite position (a non-zero direction) and a non-negative colour.
void check_light(const Light& l, const JsonPath& at);
/// The object's own check (P::check) and its material index.
void check_object(const Scene& s, ObjectRef r, const JsonPath& at);

}  // namespace rtlab::scene_json
