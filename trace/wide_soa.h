#pragma once
// Wide BVHs over a method's leaf data with its hand-written SIMD leaf kernel (trace/leaf_kernel.h,
// simd = true) inlined into traversal: one function per SIMD level (trace/wide_soa.inc) holds the
// node tests and the leaf tests of that level, so a leaf costs no call and no level look-up; it
// traces a whole block of rays, so the level, the node layout and the call are chosen once per
// block, not per ray. The answers are those of WideBvh::intersect_leaves / occluded_leaves with
// kernel_closest / kernel_any as the leaf callback (same order of visits, same counts).

#include "accel/bvh/wide_bvh.h"
#include "trace/leaf_kernel.h"

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>

namespace rtlab {

/// What a wide_soa_trace query finds: the closest hit's slot and hit, or any hit's slot.
template <bool IsAnyHit>
using SoaFound = std::conditional_t<IsAnyHit, std::optional<std::uint32_t>, std::optional<SlotHit>>;

}  // namespace rtlab

#define RTLAB_SIMD_KERNELS "trace/wide_soa.inc"
#include "base/simd_each_level.inc"

namespace rtlab {

/// A block of rays for wide_leaf_trace_block: rays [begin, end) of a
/// batch; take(i, ray) sets ray i's ray and window (false: skip it), put(i, found) takes its
/// answer (the closest hit's SlotHit, or any hit's slot; called only when there is one) and
/// stats(i) is the StatsSink its traversal counts into.
template <class B>
concept RayBlock = requires(B& b, std::size_t i, Rayf& ray) {
    { b.begin } -> std::convertible_to<std::size_t>;
    { b.end } -> std::convertible_to<std::size_t>;
    { b.take(i, ray) } -> std::same_as<bool>;
    b.stats(i);
};

/// What a traversal of an empty structure does for a block: counts each valid ray it takes
/// (WideBvh::visit's count), finds nothing.
template <RayBlock B>
void count_rays_of_empty(B& block) {
    for (std::size_t i = block.begin; i != block.end; ++i) {
        Rayf ray;
        if (block.take(i, ray) && is_valid(ray)) {
            block.stats(i).count_ray();
        }
    }
}

/// Closest hit (IsAnyHit false: block.put(i, SlotHit), the nearest slot and its hit) or any hit
/// (block.put(i, slot), the first blocking slot found) of every ray of the block through bvh with
/// method M's leaf data q in its slot order, M's per-ray set-up made per ray. The SIMD level and
/// node layout are chosen once per block. The answers and counts are those of
/// WideBvh::intersect_leaves / occluded_leaves with kernel_closest / kernel_any as the leaf
/// callback.
template <bool IsAnyHit, bool IsRobust, class M, unsigned N, RayBlock B>
void wide_leaf_trace_block(const WideBvh<N>& bvh, const LeafData<M>& q, B& block) {
    static_assert(LeafKernel<M>::simd, "the generic kernel is inlined ray by ray (batch_loop.h)");
    if (bvh.nodes.empty()) {
        count_rays_of_empty(block);
        return;
    }
    bvh.visit_view([&](const auto& view) {
        switch (simd_level()) {
        case SimdLevel::avx512:
            simd_avx512::wide_leaf_trace_block<IsAnyHit, IsRobust, M>(view, q, block);
            return;
        case SimdLevel::avx2:
            simd_avx2::wide_leaf_trace_block<IsAnyHit, IsRobust, M>(view, q, block);
            return;
        case SimdLevel::sse2:
            break;
        }
        simd_sse2::wide_leaf_trace_block<IsAnyHit, IsRobust, M>(view, q, block);
    });
}

}  // namespace rtlab
