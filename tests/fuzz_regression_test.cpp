// Every input in tests/fuzz_regressions/ once made a reader crash, hang or misbehave (found by
// scripts/fuzz). Each must now load cleanly or be rejected with a one-line rtlab::Error naming
// the file; the reader is chosen by the extension (.json scene, mesh extensions, .rays, .hits).
#include "mesh/mesh_io.h"
#include "scene/scene_io.h"
#include "trace/binary_io.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#ifndef RTLAB_FUZZ_REGRESSIONS
#define RTLAB_FUZZ_REGRESSIONS "tests/fuzz_regressions"
#endif

namespace {

void load_by_extension(const std::filesystem::path& f) {
    const std::string ext = f.extension().string();
    if (ext == ".rays") {
        (void)rtlab::load_rays(f);
    } else if (ext == ".hits") {
        (void)rtlab::load_hits(f);
    } else {
        (void)rtlab::load_scene(f);  // .json and every mesh extension
    }
}

}  // namespace

TEST_CASE("fuzz regressions: each past finding loads or is rejected with a one-line Error",
          "[fuzz][io]") {
    const std::filesystem::path dir(RTLAB_FUZZ_REGRESSIONS);
    REQUIRE(std::filesystem::is_directory(dir));
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (!entry.is_regular_file() || entry.path().extension() == ".md") {
            continue;
        }
        ++files;
        INFO(entry.path().string());
        try {
            load_by_extension(entry.path());
        } catch (const rtlab::Error& e) {
            const std::string msg = e.what();
            CHECK(msg.find('\n') == std::string::npos);
            CHECK(msg.rfind(entry.path().string(), 0) == 0);  // names the file first
        }
    }
    CHECK(files > 0);
}
