#pragma once
// Building blocks of the grid builders: primitive references to cells gathered in parallel (TBB
// over fixed blocks of ids, concatenated in id order, so the result never depends on the thread
// count), and their counting sort into CSR form (stable: ids stay ascending within a cell).

#include <algorithm>
#include <cstdint>
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
template <class T>
void refs_to_csr(const std::vector<std::pair<std::uint32_t, T>>& refs,
                 std::size_t cells,
                 std::vector<std::uint32_t>& start,
                 std::vector<T>& values) {
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

}  // namespace rtlab
