// libFuzzer target: the ray-file (RTLAB_FUZZ_RAYS) or hit-file (RTLAB_FUZZ_HITS) reader on
// arbitrary bytes. Rejections must be rtlab::Error; accepted rays must be finite with tmin <= tmax.
#include "fuzz/fuzz_file.h"
#include "trace/binary_io.h"

#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path file = rtlab::fuzz::write_input(data, size, ".bin");
    try {
#ifdef RTLAB_FUZZ_RAYS
        for (const rtlab::Rayf& r : rtlab::load_rays(file)) {
            if (!rtlab::is_finite(r.org) || !rtlab::is_finite(r.dir) || !(r.tmin <= r.tmax)) {
                std::abort();  // load_rays promised a usable ray
            }
        }
#else
        if (rtlab::load_hits(file).size() * 16 != size) {
            std::abort();  // one hit per 16-byte record
        }
#endif
    } catch (const rtlab::Error&) {
    }
    return 0;
}
