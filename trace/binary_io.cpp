// Ray and hit files: raw little-endian records (see binary_io.h).
#include "trace/binary_io.h"

#include "base/atomic_file.h"
#include "base/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

namespace rtlab {

namespace {

static_assert(std::endian::native == std::endian::little,
              "ray and hit files are little-endian; add byte swapping for this host");
static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559);

constexpr std::size_t ray_record = 8 * sizeof(float);
constexpr std::size_t hit_record = 4 * sizeof(float);

std::string read_all(const std::filesystem::path& file, std::size_t record, const char* what) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(file, ec);
    if (st.type() == std::filesystem::file_type::not_found) {
        throw Error(file.string() + ": no such " + what + " file");
    }
    if (st.type() == std::filesystem::file_type::directory) {
        throw Error(file.string() + ": is a folder, not a " + what + " file");
    }
    if (st.type() != std::filesystem::file_type::regular) {
        throw Error(file.string() + ": not a regular file (a " + what + " file is read whole)");
    }
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) {
        throw Error(file.string() + ": cannot read");
    }
    if (bytes.size() % record != 0) {
        throw Error(file.string() + ": size " + std::to_string(bytes.size()) +
                    " bytes is not a multiple of the " + std::to_string(record) + "-byte " + what +
                    " record");
    }
    return bytes;
}

}  // namespace

std::vector<Rayf> load_rays(const std::filesystem::path& file) {
    const std::string bytes = read_all(file, ray_record, "ray");
    std::vector<Rayf> rays(bytes.size() / ray_record);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        float v[8];
        std::memcpy(v, bytes.data() + i * ray_record, ray_record);
        Rayf& r = rays[i];
        r.org = {v[0], v[1], v[2]};
        r.dir = {v[3], v[4], v[5]};
        r.tmin = v[6];
        r.tmax = v[7];
        const char* problem = nullptr;
        if (!is_finite(r.org)) {
            problem = "origin is not finite";
        } else if (!is_finite(r.dir)) {
            problem = "direction is not finite";
        } else if (max_component(abs(r.dir)) < std::numeric_limits<float>::min()) {
            problem = "direction is zero or denormal";
        } else if (std::isnan(r.tmin) || std::isnan(r.tmax)) {
            problem = "tmin or tmax is NaN";
        } else if (r.tmin > r.tmax) {
            problem = "tmin > tmax";
        }
        if (problem != nullptr) {
            throw Error(file.string() + ": ray " + std::to_string(i) + ": " + problem);
        }
    }
    return rays;
}

namespace {

/// Writes n records of `record` bytes, produced by fill(i, bytes) for record i, in chunks of
/// 64 Ki records, through write_atomically (the temporary grows as records are converted).
template <class Fill>
void save_records(const std::filesystem::path& file,
                  std::size_t n,
                  std::size_t record,
                  Fill&& fill) {
    write_atomically(file, [&](const std::filesystem::path& path) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw Error(file.string() + ": cannot open for writing");
        }
        constexpr std::size_t chunk = std::size_t{1} << 16;
        std::string bytes;
        for (std::size_t start = 0; start < n && out; start += chunk) {
            const std::size_t end = std::min(n, start + chunk);
            bytes.assign((end - start) * record, '\0');
            for (std::size_t i = start; i < end; ++i) {
                fill(i, bytes.data() + (i - start) * record);
            }
            out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        }
        out.close();
        if (!out) {
            throw Error(file.string() + ": write failed (disk full?)");
        }
    });
}

}  // namespace

void save_rays(const std::filesystem::path& file, std::span<const Rayf> rays) {
    save_records(file, rays.size(), ray_record, [&](std::size_t i, char* p) {
        const Rayf& r = rays[i];
        const float v[8] = {r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax};
        std::memcpy(p, v, ray_record);
    });
}

void save_hits(const std::filesystem::path& file, std::span<const Hit> hits) {
    save_records(file, hits.size(), hit_record, [&](std::size_t i, char* p) {
        const Hit& h = hits[i];
        std::memcpy(p, &h.t, 4);
        std::memcpy(p + 4, &h.prim, 4);
        std::memcpy(p + 8, &h.u, 4);
        std::memcpy(p + 12, &h.v, 4);
    });
}

std::vector<Hit> load_hits(const std::filesystem::path& file) {
    const std::string bytes = read_all(file, hit_record, "hit");
    std::vector<Hit> hits(bytes.size() / hit_record);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const char* p = bytes.data() + i * hit_record;
        std::memcpy(&hits[i].t, p, 4);
        std::memcpy(&hits[i].prim, p + 4, 4);
        std::memcpy(&hits[i].u, p + 8, 4);
        std::memcpy(&hits[i].v, p + 12, 4);
    }
    return hits;
}

}  // namespace rtlab
