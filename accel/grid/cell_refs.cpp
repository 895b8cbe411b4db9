// The CSR invariants shared by Grid::validate and TwoLevelGrid::validate.
#include "accel/grid/cell_refs.h"

namespace rtlab {

std::size_t present_count(const std::vector<bool>& prim_present) {
    return static_cast<std::size_t>(std::count(prim_present.begin(), prim_present.end(), true));
}

std::string check_csr_cells(std::span<const std::uint32_t> start,
                            std::span<const std::uint32_t> values,
                            const std::vector<bool>& prim_present) {
    if (start.empty() || start.front() != 0 || start.back() != values.size()) {
        return "CSR offsets do not match the cell and reference counts";
    }
    std::vector<bool> seen(prim_present.size());
    for (std::size_t c = 0; c + 1 < start.size(); ++c) {
        if (start[c] > start[c + 1] || start[c + 1] > values.size()) {
            return "CSR offsets decrease or pass the references at cell " + std::to_string(c);
        }
        for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
            const std::uint32_t id = values[k];
            if (id >= prim_present.size() || !prim_present[id]) {
                return "cell " + std::to_string(c) + " references missing primitive " +
                       std::to_string(id);
            }
            seen[id] = true;
        }
    }
    for (std::size_t id = 0; id < prim_present.size(); ++id) {
        if (prim_present[id] && !seen[id]) {
            return "primitive " + std::to_string(id) + " is in no cell";
        }
    }
    return {};
}

void add_cell_costs(AccelInfo& info,
                    std::span<const std::uint32_t> start,
                    std::size_t first,
                    std::size_t count,
                    double p) {
    for (std::size_t c = first; c < first + count; ++c) {
        const std::uint32_t n = start[c + 1] - start[c];
        info.leaves += n > 0 ? 1 : 0;
        info.sah_cost += p * (1.0 + 1.5 * static_cast<double>(n));
    }
}

void set_per_prim_figures(AccelInfo& info,
                          std::size_t refs,
                          const std::vector<bool>& prim_present) {
    const std::size_t present = present_count(prim_present);
    if (present > 0) {
        info.bytes_per_prim = static_cast<double>(info.bytes) / static_cast<double>(present);
        info.refs_per_prim = static_cast<double>(refs) / static_cast<double>(present);
    }
}

}  // namespace rtlab
