// libFuzzer target: nff::parse on arbitrary text. Rejections must be rtlab::Error. An accepted
// document must survive its own round trip (write, parse again, write the same text) and, when
// it becomes a scene, the scene must pass validate_scene.
#include "base/error.h"
#include "scene/nff_io.h"
#include "scene/scene_io.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    rtlab::nff::Document doc;
    try {
        doc = rtlab::nff::parse(text, "fuzz");
    } catch (const rtlab::Error&) {
        return 0;
    }
    // What write promises: its text parses, and parsing it back loses nothing more.
    const std::string once = rtlab::nff::write(doc);
    const std::string twice = rtlab::nff::write(rtlab::nff::parse(once, "fuzz (written)"));
    if (once != twice) {
        std::fprintf(stderr, "rtlab fuzz: NFF write/parse round trip changed the text\n");
        std::abort();
    }
    try {
        const rtlab::Scene scene = rtlab::nff::to_scene(doc, "fuzz");
        rtlab::validate_scene(scene, "fuzz");  // what to_scene promises
    } catch (const rtlab::Error&) {
    }
    return 0;
}
