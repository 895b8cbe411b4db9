#pragma once
// Haines' Standard Procedural Databases (SPD 3.14), each written from its program's rules as the
// NFF document the program prints with `-r 1` (NFF output): same records, order, numbers and
// polygon winding. to_scene (scene/nff_io.h) turns a document into a Scene.

#include "scene/nff_io.h"

#include <cstdint>
#include <span>
#include <string_view>

namespace rtlab::gen::spd {

/// One SPD database: its name (as the SPD program), smallest and default size factor, the
/// document at a size factor, and its primitive counts (without generating).
struct Database {
    std::string_view name;
    int min_size = 1;
    int default_size = 1;
    int max_size = 1;
    nff::Document (*document)(int sf);
    nff::Counts (*counts)(int sf);
};

/// Every SPD database implemented so far, in the SPD's alphabetical order.
[[nodiscard]] std::span<const Database> databases();

/// The database called `name`, or nullptr.
[[nodiscard]] const Database* find_database(std::string_view name);

// The databases of polygons (spd_polygons.cpp, spd_teapot.cpp), listed in databases().
[[nodiscard]] nff::Document gears(int sf);
[[nodiscard]] nff::Counts gears_counts(int sf);
[[nodiscard]] nff::Document mount(int sf);
[[nodiscard]] nff::Counts mount_counts(int sf);
[[nodiscard]] nff::Document sombrero(int sf);
[[nodiscard]] nff::Counts sombrero_counts(int sf);
[[nodiscard]] nff::Document teapot(int sf);
[[nodiscard]] nff::Counts teapot_counts(int sf);
[[nodiscard]] nff::Document tetra(int sf);
[[nodiscard]] nff::Counts tetra_counts(int sf);

namespace detail {
inline constexpr double pi = 3.141592653589793238462643383279502884;
inline const Vec3d sky_blue{0.078, 0.361, 0.753};  ///< "UNC sky blue", the usual SPD background
/// b^e in integers.
[[nodiscard]] inline std::uint64_t ipow(std::uint64_t b, int e) {
    std::uint64_t r = 1;
    for (int i = 0; i < e; ++i) {
        r *= b;
    }
    return r;
}
}  // namespace detail

}  // namespace rtlab::gen::spd
