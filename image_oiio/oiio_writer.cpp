// The OpenImageIO writer module: the only code that links OpenImageIO (see render/oiio_writer.h).
#include "render/oiio_writer.h"

#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

namespace {

int fail(const std::string& message, char* error, std::size_t error_size) {
    if (error_size > 0) {
        const std::size_t n = std::min(message.size(), error_size - 1);
        std::memcpy(error, message.data(), n);
        error[n] = '\0';
    }
    return 1;
}

}  // namespace

extern "C" int rtlab_oiio_write(const char* path,
                                int png,
                                int srgb,
                                int width,
                                int height,
                                const void* pixels,
                                char* error,
                                std::size_t error_size) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(png ? "png" : "openexr");
    if (!out) {
        return fail("no OpenImageIO writer (" + OIIO::geterror() + ")", error, error_size);
    }
    const OIIO::TypeDesc type = png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(width, height, 3, type);
    spec.attribute("oiio:ColorSpace", png && srgb ? "sRGB" : "Linear");
    if (!out->open(path, spec)) {
        return fail("cannot write (" + out->geterror() + ")", error, error_size);
    }
    bool ok = out->write_image(type, pixels);
    ok = out->close() && ok;
    if (!ok) {
        return fail("write failed (" + out->geterror() + ")", error, error_size);
    }
    return 0;
}
