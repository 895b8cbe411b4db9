#pragma once
// Building blocks of the grid builders: primitive references to cells gathered in parallel (TBB
// over fixed blocks of ids, concatenated in id order, so the result never depends on the thread
// count), their counting sort into CSR form (stable: ids stay ascending within a cell), the
// CSR invariants both grids' validate() check, and the cell figures both grids' info() report.

#include "accel/accel.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <tbb/parallel_for.h>
#include <utility>
#include <vector>

namespace rtlab {

/// (cell, value) references of ids [0, n): fn(id, emit) calls emit(cell, value) for each cell
/// of id. Blocks of 1024 ids run as parallel tasks.
template <class T, class Fn>
std::vector<std::pair<std::uint32_t, T>> gather_cell_refs(std::uint32_t n, Fn&& fn) {
    constexpr std::uint32_t block = 1024;
    const std::uint32_t blocks = (n + block - 1) / block;
    std::vector<std::vector<std::pair<std::uint32_t, T>>> parts(blocks);
    tbb::parallel_for(std::uint32_t{0}, blocks, [&](std::uint32_t b) {
        auto& out = parts[b];
        const auto emit = [&out](std::size_t cell, const T& v) {
            out.emplace_back(static_cast<std::uint32_t>(cell), v);
        };
        for (std::uint32_t id = b * block; id < std::min(n, (b + 1) * block); ++id) {
            fn(id, emit);
        }
    });
    std::size_t total = 0;
    for (const auto& p : parts) {
        total += p.size();
    }
    std::vector<std::pair<std::uint32_t, T>> refs;
    refs.reserve(total);
    for (auto& p : parts) {
        refs.insert(refs.end(), p.begin(), p.end());
        p = {};
    }
    return refs;
}

/// CSR of refs over `cells` cells: start (size cells + 1) and the values cell by cell, in the
/// order refs lists them.
template <class T, class Starts, class Values>
void refs_to_csr(const std::vector<std::pair<std::uint32_t, T>>& refs,
                 std::size_t cells,
                 Starts& start,
                 Values& values) {
    start.assign(cells + 1, 0);
    for (const auto& r : refs) {
        ++start[r.first + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) {
        start[c + 1] += start[c];
    }
    values.resize(refs.size());
    std::vector<std::uint32_t> cursor(start.begin(), start.end() - 1);
    for (const auto& r : refs) {
        values[cursor[r.first]++] = r.second;
    }
}

/// Number of primitives marked present.
std::size_t present_count(const std::vector<bool>& prim_present);

/// Empty when `start` (size cells + 1) runs from 0 to values.size() without decreasing, every
/// value is a present primitive's id and every present primitive is in some cell; else the first
/// violation.
std::string check_csr_cells(std::span<const std::uint32_t> start,
                            std::span<const std::uint32_t> values,
                            const std::vector<bool>& prim_present);

/// Adds the CSR cells [first, first + count), each of surface-area probability p, to info: one
/// leaf per non-empty cell and p (1 + 1.5 n) per cell of n references to sah_cost (the grid's own
/// cost value: one step per cell, K_I = 1.5 per reference).
void add_cell_costs(AccelInfo& info,
                    std::span<const std::uint32_t> start,
                    std::size_t first,
                    std::size_t count,
                    double p);

/// Sets info.bytes_per_prim (from info.bytes) and info.refs_per_prim (`refs` references) per
/// present primitive; leaves both 0 when none is present.
void set_per_prim_figures(AccelInfo& info, std::size_t refs, const std::vector<bool>& prim_present);

}  // namespace rtlab
