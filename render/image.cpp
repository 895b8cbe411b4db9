// Image output through OpenImageIO, in the rtlab_oiio module loaded on first use
// (render/oiio_writer.h): the format comes from the target's extension, the bytes go to a
// temporary file beside it (base/atomic_file.h), so a failure never leaves a partial image.
#include "render/image.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "render/oiio_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <dlfcn.h>
#include <string>
#include <utility>
#include <vector>

namespace rtlab {

namespace {

std::string lower_extension(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::uint8_t quantise(float v) {
    const float c = std::clamp(v, 0.0f, 1.0f);
    return static_cast<std::uint8_t>(std::lround(c * 255.0f));
}

/// The module's write function, loaded once: the installed module (lib/rtlab under the running
/// executable's prefix, which has it in bin/), else the build tree's; an Error naming `file`
/// when neither loads.
RtlabOiioWrite* oiio_writer(const std::filesystem::path& file) {
    static const std::pair<RtlabOiioWrite*, std::string> loaded = [] {
        std::vector<std::string> paths;
        std::error_code ec;
        const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec && exe.is_absolute()) {  // never a path relative to the working directory
            paths.push_back(
                (exe.parent_path().parent_path() / RTLAB_OIIO_MODULE_INSTALLED).string());
        }
        paths.emplace_back(RTLAB_OIIO_MODULE_BUILT);
        std::string why;
        for (const std::string& path : paths) {
            if (void* lib = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
                if (void* f = ::dlsym(lib, "rtlab_oiio_write")) {
                    return std::pair{reinterpret_cast<RtlabOiioWrite*>(f), std::string()};
                }
            }
            const char* e = ::dlerror();
            why += (why.empty() ? "" : "; ") + (e != nullptr ? std::string(e) : path);
        }
        return std::pair{static_cast<RtlabOiioWrite*>(nullptr), why};
    }();
    if (loaded.first == nullptr) {
        throw Error(file.string() + ": cannot load the OpenImageIO writer module (" +
                    loaded.second + ")");
    }
    return loaded.first;
}

}  // namespace

float linear_to_srgb(float v) {
    const float c = std::clamp(v, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::size_t clear_non_finite(Image& img) {
    std::size_t n = 0;
    for (Vec3f& p : img.pixels) {
        if (!is_finite(p)) {
            ++n;
            for (std::size_t c = 0; c < 3; ++c) {
                p[c] = std::isfinite(p[c]) ? p[c] : 0.0f;
            }
        }
    }
    return n;
}

void load_image_writer(const std::filesystem::path& file) {
    oiio_writer(file);
}

bool is_supported_image(const std::filesystem::path& file) {
    const std::string ext = lower_extension(file);
    return ext == ".png" || ext == ".exr";
}

void write_image(const Image& img, const std::filesystem::path& file, bool srgb) {
    const std::string ext = lower_extension(file);
    if (!is_supported_image(file)) {
        throw Error(file.string() + ": unsupported image extension '" + ext +
                    "' (use .png or .exr)");
    }
    if (img.width <= 0 || img.height <= 0 ||
        img.pixels.size() !=
            static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height)) {
        throw Error(file.string() + ": empty or inconsistent image");
    }
    const bool png = ext == ".png";
    RtlabOiioWrite* const write = oiio_writer(file);
    // EXR takes the pixels as they are (three packed floats each); PNG their 8-bit values.
    static_assert(sizeof(Vec3f) == 3 * sizeof(float));
    std::vector<std::uint8_t> bytes;
    if (png) {
        bytes.reserve(img.pixels.size() * 3);
        for (const Vec3f& p : img.pixels) {
            for (std::size_t c = 0; c < 3; ++c) {
                bytes.push_back(quantise(srgb ? linear_to_srgb(p[c]) : p[c]));
            }
        }
    }
    const void* pixels = png ? static_cast<const void*>(bytes.data()) : img.pixels.data();
    write_atomically(file, [&](const std::filesystem::path& tmp) {
        // The temporary's extension is not an image one, so the format is named explicitly.
        char error[512];
        if (write(tmp.c_str(), png ? 1 : 0, srgb ? 1 : 0, img.width, img.height, pixels, error,
                  sizeof error) != 0) {
            throw Error(file.string() + ": " + error);
        }
    });
}

}  // namespace rtlab
