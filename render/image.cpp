// Image output through OpenImageIO: the format comes from the target's extension, the bytes go to
// a temporary file beside it (mesh/atomic_file.h), so a failure never leaves a partial image.
#include "render/image.h"

#include "base/atomic_file.h"
#include "base/error.h"

#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>

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
    write_atomically(file, [&](const std::filesystem::path& tmp) {
        // The temporary's extension is not an image one, so name the format explicitly.
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(png ? "png" : "openexr");
        if (!out) {
            throw Error(file.string() + ": no OpenImageIO writer (" + OIIO::geterror() + ")");
        }
        const OIIO::TypeDesc type = png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
        OIIO::ImageSpec spec(img.width, img.height, 3, type);
        spec.attribute("oiio:ColorSpace", png && srgb ? "sRGB" : "Linear");
        if (!out->open(tmp.string(), spec)) {
            throw Error(file.string() + ": cannot write (" + out->geterror() + ")");
        }
        bool ok = false;
        if (png) {
            std::vector<std::uint8_t> bytes;
            bytes.reserve(img.pixels.size() * 3);
            for (const Vec3f& p : img.pixels) {
                for (std::size_t c = 0; c < 3; ++c) {
                    bytes.push_back(quantise(srgb ? linear_to_srgb(p[c]) : p[c]));
                }
            }
            ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
        } else {
            std::vector<float> values;
            values.reserve(img.pixels.size() * 3);
            for (const Vec3f& p : img.pixels) {
                values.insert(values.end(), {p.x, p.y, p.z});
            }
            ok = out->write_image(OIIO::TypeDesc::FLOAT, values.data());
        }
        ok = out->close() && ok;
        if (!ok) {
            throw Error(file.string() + ": write failed (" + out->geterror() + ")");
        }
    });
}

}  // namespace rtlab
