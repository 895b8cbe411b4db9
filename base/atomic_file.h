#pragma once
// Writing output files completely or not at all: write a temporary file beside the target, then
// rename it over the target (rename is atomic within one file system).

#include "base/error.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>
#include <system_error>

namespace rtlab {

/// Calls write(path_of_temporary) and renames the temporary over `file` when it returns; on an
/// exception the temporary is removed, the target is left untouched, and the exception passes on.
inline void write_atomically(const std::filesystem::path& file,
                             const std::function<void(const std::filesystem::path&)>& write) {
    std::filesystem::path tmp = file;
    tmp += ".tmp-rtlab";
    try {
        write(tmp);
        std::error_code ec;
        std::filesystem::rename(tmp, file, ec);
        if (ec) {
            throw Error(file.string() + ": cannot write (" + ec.message() + ")");
        }
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw;
    }
}

/// Writes `bytes` to `file` completely or not at all; throws rtlab::Error naming the file.
inline void write_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
    write_atomically(file, [&](const std::filesystem::path& tmp) {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw Error(file.string() + ": cannot open for writing");
        }
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        out.close();
        if (!out) {
            throw Error(file.string() + ": write failed (disk full?)");
        }
    });
}

}  // namespace rtlab
