#pragma once
// Run-time choice of the SIMD instruction set. Kernels are compiled once per level (sse2: the
// x86-64 baseline; avx2; avx512: F, VL, DQ, BW) inside GCC target regions (RTLAB_SIMD_BEGIN_*),
// so one binary built without -march carries every path; each call then takes the highest level
// the CPU supports (__builtin_cpu_supports), lowered by the RTLAB_SIMD environment variable
// (sse2|avx2|avx512) or by set_simd_cap() so tests and benchmarks can compare every path.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string_view>

namespace rtlab {

/// The SIMD instruction sets kernels are compiled for, lowest first.
enum class SimdLevel : std::uint8_t {
    sse2,    ///< x86-64 baseline: 4 floats per register
    avx2,    ///< 8 floats per register
    avx512,  ///< AVX-512 F/VL/DQ/BW: mask registers, 16 floats per register
};

/// Every level, lowest first.
inline constexpr SimdLevel simd_levels[] = {SimdLevel::sse2, SimdLevel::avx2, SimdLevel::avx512};

/// "sse2", "avx2" or "avx512".
constexpr std::string_view simd_name(SimdLevel l) {
    return l == SimdLevel::avx512 ? "avx512" : l == SimdLevel::avx2 ? "avx2" : "sse2";
}

/// The level called `name`, or nullopt.
constexpr std::optional<SimdLevel> parse_simd_level(std::string_view name) {
    for (const SimdLevel l : simd_levels) {
        if (simd_name(l) == name) {
            return l;
        }
    }
    return std::nullopt;
}

/// The highest level this CPU runs.
inline SimdLevel simd_supported() {
    static const SimdLevel level = [] {
        __builtin_cpu_init();
        if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
            __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw")) {
            return SimdLevel::avx512;
        }
        if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi2")) {
            return SimdLevel::avx2;
        }
        return SimdLevel::sse2;
    }();
    return level;
}

namespace detail {
/// RTLAB_SIMD's level, or the highest level when it is unset or unknown.
inline SimdLevel env_simd_cap() {
    const char* env = std::getenv("RTLAB_SIMD");
    const auto l = env != nullptr ? parse_simd_level(env) : std::nullopt;
    return l.value_or(SimdLevel::avx512);
}

/// The cap set by set_simd_cap, and the level in use (the lower of the cap and the CPU's), kept
/// beside it so that simd_level(), run by every query, is one load. Namespace-scope variables,
/// not function-local statics, for the same reason (no guard check per call); a call before their
/// dynamic initialisation would see sse2 (zero), a slower path, never a wrong one. simd_in_use is
/// defined after simd_cap in every translation unit, so it is initialised after it.
inline std::atomic<SimdLevel> simd_cap{env_simd_cap()};
inline std::atomic<SimdLevel> simd_in_use{std::min(simd_cap.load(), simd_supported())};
}  // namespace detail

/// Limits every later kernel call to `cap` (or lower when the CPU lacks it); returns the old cap.
inline SimdLevel set_simd_cap(SimdLevel cap) {
    const SimdLevel old = detail::simd_cap.exchange(cap);
    detail::simd_in_use.store(std::min(cap, simd_supported()));
    return old;
}

/// The level kernels use now: the lower of the CPU's and the cap.
inline SimdLevel simd_level() {
    return detail::simd_in_use.load(std::memory_order_relaxed);
}

/// Sets a cap for the lifetime of the object (tests), restoring the previous one after.
class ScopedSimdCap {
public:
    explicit ScopedSimdCap(SimdLevel cap) : old_(set_simd_cap(cap)) {}
    ~ScopedSimdCap() { set_simd_cap(old_); }
    ScopedSimdCap(const ScopedSimdCap&) = delete;
    ScopedSimdCap& operator=(const ScopedSimdCap&) = delete;

private:
    SimdLevel old_;
};

}  // namespace rtlab

// Target regions: functions (and templates) defined between BEGIN and END are compiled for that
// instruction set whatever the build's -march; callers must check simd_level() first. Code
// without a target (the caller's lambdas) inlines into them. No "fma": results stay bit-identical
// across levels (the build also sets -ffp-contract=off).
#define RTLAB_SIMD_BEGIN_AVX2 \
    _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,bmi,bmi2,popcnt,lzcnt\")")
#define RTLAB_SIMD_BEGIN_AVX512 \
    _Pragma("GCC push_options") \
        _Pragma("GCC target(\"avx512f,avx512vl,avx512dq,avx512bw,avx2,bmi,bmi2,popcnt,lzcnt\")")
#define RTLAB_SIMD_END _Pragma("GCC pop_options")
