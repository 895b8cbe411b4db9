#pragma once
// Ray and hit files: raw little-endian float32/uint32 records, no header.
//   ray: ox oy oz dx dy dz tmin tmax   (32 bytes; dir need not be unit; t in units of dir)
//   hit: t (+inf on a miss; 0 for an occluded any-hit ray), prim id (0xFFFFFFFF on a miss), u, v
//        (16 bytes)

#include "intersect/hit.h"
#include "intersect/ray.h"

#include <filesystem>
#include <span>
#include <vector>

namespace rtlab {

/// Reads a ray file. Throws rtlab::Error naming the file and the problem: unreadable, size not a
/// multiple of 32 bytes, or a record with a non-finite origin or direction, a zero direction, a
/// NaN tmin/tmax or tmin > tmax (the record's index is in the message).
std::vector<Rayf> load_rays(const std::filesystem::path& file);

/// Writes a ray file atomically (temporary file, then rename); throws rtlab::Error on failure.
void save_rays(const std::filesystem::path& file, std::span<const Rayf> rays);

/// Writes a hit file atomically, one 16-byte record per ray in ray order.
void save_hits(const std::filesystem::path& file, std::span<const Hit> hits);

/// Reads a hit file (for tests and comparisons); throws rtlab::Error on a bad size.
std::vector<Hit> load_hits(const std::filesystem::path& file);

}  // namespace rtlab
