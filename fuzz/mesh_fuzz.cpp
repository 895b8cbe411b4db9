// libFuzzer target: load_mesh on arbitrary bytes with the extension RTLAB_FUZZ_EXTENSION (.obj,
// .ply, .off, .stl). A rejected file must throw rtlab::Error; anything else (another exception, a
// sanitizer report, a hang) is a finding. An accepted mesh must satisfy validate_mesh.
#include "fuzz/fuzz_file.h"
#include "mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path file = rtlab::fuzz::write_input(data, size, RTLAB_FUZZ_EXTENSION);
    try {
        const rtlab::TriangleMesh mesh = rtlab::load_mesh(file);
        rtlab::validate_mesh(mesh, "fuzz");  // what load_mesh promises
    } catch (const rtlab::Error&) {
    }
    return 0;
}
