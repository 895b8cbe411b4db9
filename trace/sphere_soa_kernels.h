#pragma once
// The SphereSoA leaf kernels (trace/sphere_soa_kernels.inc) compiled once per SIMD level of
// base/simd.h: namespaces simd_sse2, simd_avx2 and simd_avx512, each in its own target region with
// that level's lanes (base/simd_lanes.h). trace/leaf_kernel.h picks one per call by
// simd_level(); trace/wide_soa.h inlines them into the wide BVH traversal of the same level.

#include "base/simd_lanes.h"
#include "trace/leaf_soa.h"
#include "trace/sphere_soa.h"

#include <cstdint>
#include <optional>

namespace rtlab {

/// One chunk of at most 8 slots: `cand` has a bit per lane whose sphere detail::pick_root hits
/// with the window the chunk started with (which only shrinks), t each lane's picked root.
struct SphereChunk {
    unsigned cand = 0;
    alignas(32) float t[8];
};

}  // namespace rtlab

#define RTLAB_SIMD_KERNELS "trace/sphere_soa_kernels.inc"
#include "base/simd_each_level.inc"
