// libFuzzer target: parse_scene on arbitrary text. Mesh `file` references resolve in an empty
// scratch folder. Rejections must be rtlab::Error; an accepted scene must pass validate_scene.
#include "fuzz/fuzz_file.h"
#include "scene/scene_io.h"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const rtlab::Scene scene = rtlab::parse_scene(text, rtlab::fuzz::scratch_dir(), "fuzz");
        rtlab::validate_scene(scene, "fuzz");  // what parse_scene promises
    } catch (const rtlab::Error&) {
    }
    return 0;
}
