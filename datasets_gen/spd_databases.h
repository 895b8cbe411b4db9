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

}  // namespace rtlab::gen::spd
