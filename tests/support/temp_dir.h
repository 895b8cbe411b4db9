#pragma once
// Scratch folders and small file helpers for tests that write and read files.

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <system_error>

namespace rtlab::test {

/// A fresh folder temp_directory_path()/(prefix + random number), removed with everything in it
/// at scope exit.
struct TempDir {
    std::filesystem::path path;  ///< the folder

    /// Creates the folder; prefix names the test that owns it (e.g. "rtlab_mesh_test_").
    explicit TempDir(const std::string& prefix) {
        std::random_device rd;
        path = std::filesystem::temp_directory_path() / (prefix + std::to_string(rd()));
        std::filesystem::create_directories(path);
    }
    /// Removes the folder and its contents; errors are ignored.
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

/// Writes s to the file p, byte for byte (replacing it).
inline void write_text(const std::filesystem::path& p, const std::string& s) {
    std::ofstream out(p, std::ios::binary);
    out << s;
}

}  // namespace rtlab::test
