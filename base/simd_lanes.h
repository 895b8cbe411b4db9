#pragma once
// The float lanes of every SIMD level (base/simd_lanes.inc), each in its target region of
// base/simd.h: rtlab::simd_sse2, simd_avx2 and simd_avx512 hold L4, L8 (from AVX2 up), max_lanes
// and LanesOf<W>. Kernels reopen these namespaces inside the same regions (see
// accel/bvh/wide_kernels.h) and pick a namespace per call by simd_level().

#include "base/simd.h"

#include <immintrin.h>

namespace rtlab::simd_sse2 {
#define RTLAB_LANES_LEVEL 0
#include "base/simd_lanes.inc"
#undef RTLAB_LANES_LEVEL
}  // namespace rtlab::simd_sse2

RTLAB_SIMD_BEGIN_AVX2
namespace rtlab::simd_avx2 {
#define RTLAB_LANES_LEVEL 1
#include "base/simd_lanes.inc"
#undef RTLAB_LANES_LEVEL
}  // namespace rtlab::simd_avx2
RTLAB_SIMD_END

RTLAB_SIMD_BEGIN_AVX512
namespace rtlab::simd_avx512 {
#define RTLAB_LANES_LEVEL 2
#include "base/simd_lanes.inc"
#undef RTLAB_LANES_LEVEL
}  // namespace rtlab::simd_avx512
RTLAB_SIMD_END
