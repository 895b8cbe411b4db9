#pragma once
// The one entry point of the OpenImageIO writer module (image_oiio/), a plain C function so that
// render/image.cpp can load the module with dlopen when it first writes an image. Debian's
// OpenImageIO brings about 250 shared libraries with it (codecs, GDAL, OpenCV, ...); loading them
// at every start cost each rtlab command ~0.4 s (~0.75 s under asan) on a 2-core VM, images or not.

#include <cstddef>

extern "C" {

/// Signature of rtlab_oiio_write.
using RtlabOiioWrite = int(const char* path,
                           int png,
                           int srgb,
                           int width,
                           int height,
                           const void* pixels,
                           char* error,
                           std::size_t error_size);

/// Writes width x height RGB pixels to path: png != 0 as 8-bit PNG from `pixels` as bytes
/// (colour space tagged sRGB when srgb != 0), else as float OpenEXR from `pixels` as floats.
/// Returns 0 on success; otherwise non-zero with OpenImageIO's message in `error` (cut to
/// error_size bytes with the terminating zero).
RtlabOiioWrite rtlab_oiio_write;
}
