#pragma once
// Float RGB images and writing them through OpenImageIO (in a module loaded on first use,
// render/oiio_writer.h): PNG as 8-bit sRGB, EXR as linear float, chosen by the file extension;
// complete file or none.

#include "intersect/vec.h"

#include <filesystem>
#include <vector>

namespace rtlab {

/// A width x height RGB image, rows top to bottom, linear float values.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<Vec3f> pixels;  ///< width * height, row-major from the top left

    /// A black image of the given size (sizes >= 0).
    Image(int w, int h)
        : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h)) {}
    Image() = default;

    /// Pixel (x, y); 0 <= x < width, 0 <= y < height.
    Vec3f& at(int x, int y) {
        return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                      static_cast<std::size_t>(x)];
    }
    /// Pixel (x, y), read only.
    const Vec3f& at(int x, int y) const {
        return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                      static_cast<std::size_t>(x)];
    }
};

/// The sRGB encoding of a linear value, clamped to [0, 1] (IEC 61966-2-1 piecewise curve).
float linear_to_srgb(float v);

/// Replaces NaN and infinite pixel components by 0 (black), so no image holds them; returns the
/// number of pixels changed.
std::size_t clear_non_finite(Image& img);

/// True for the extensions write_image accepts (.png, .exr; case-insensitive).
bool is_supported_image(const std::filesystem::path& file);

/// Loads the OpenImageIO writer module (image_oiio/) if it is not loaded yet; write_image does
/// this itself, a command calls it to fail before its work. Throws rtlab::Error naming `file` when
/// the module cannot be loaded.
void load_image_writer(const std::filesystem::path& file);

/// Writes img to `file`: .png as 8-bit (sRGB-encoded when srgb, else values clamped to [0, 1] and
/// quantised as they are), .exr as 32-bit float linear values. Writes a temporary file beside the
/// target and renames it, so the target is complete or untouched. Throws rtlab::Error naming the
/// file for other extensions or any I/O failure.
void write_image(const Image& img, const std::filesystem::path& file, bool srgb);

}  // namespace rtlab
