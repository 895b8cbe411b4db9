#pragma once
// The readers under test take a path, so each fuzz input is written to one private temporary file
// (per process, with the extension that picks the reader) and read back from there.

#include "base/error.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace rtlab::fuzz {

/// A per-process scratch folder under $TMPDIR (or /tmp), removed at exit.
inline const std::filesystem::path& scratch_dir() {
    static const std::filesystem::path dir = [] {
        const char* t = std::getenv("TMPDIR");
        std::filesystem::path d = std::filesystem::path(t != nullptr ? t : "/tmp") /
                                  ("rtlab-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(scratch_dir(), ec);
        });
        return d;
    }();
    return dir;
}

/// Writes the input to scratch_dir()/input<extension> and returns that path.
inline std::filesystem::path write_input(const std::uint8_t* data,
                                         std::size_t size,
                                         const char* extension) {
    const std::filesystem::path file = scratch_dir() / (std::string("input") + extension);
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
        std::fprintf(stderr, "rtlab fuzz: cannot write %s\n", file.c_str());
        std::abort();
    }
    return file;
}

}  // namespace rtlab::fuzz
