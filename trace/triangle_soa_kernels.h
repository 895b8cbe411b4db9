#pragma once
// The TriangleSoA leaf kernels (trace/triangle_soa_kernels.inc) compiled once per SIMD level of
// base/simd.h: namespaces simd_sse2, simd_avx2 and simd_avx512, each in its own target region with
// that level's lanes (base/simd_lanes.h). trace/leaf_kernel.h picks one per call by
// simd_level(); trace/wide_soa.h inlines them into the wide BVH traversal of the same level.

#include "base/simd_lanes.h"
#include "trace/leaf_soa.h"
#include "trace/triangle_soa.h"

#include <cstdint>
#include <optional>

namespace rtlab {

/// One chunk of at most 8 slots: `cand` has a bit per lane that may hit (it passed every test
/// against the window the chunk started with, which only shrinks); `fallback` marks watertight
/// lanes with an exact zero edge function, which the scalar method decides. Per lane: t, u, v,
/// and for watertight the scaled distance ts and |det| of its window test.
struct SoaChunk {
    unsigned cand = 0;
    unsigned fallback = 0;
    alignas(32) float t[8];
    alignas(32) float u[8];
    alignas(32) float v[8];
    alignas(32) float ts[8];
    alignas(32) float ad[8];
};

}  // namespace rtlab

#define RTLAB_SIMD_KERNELS "trace/triangle_soa_kernels.inc"
#include "base/simd_each_level.inc"
