// Bvh: size and SAH figures, the invariant check, and leaf slot alignment.

#include "accel/bvh/bvh.h"

#include "accel/bvh/build_common.h"

#include <algorithm>
#include <functional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_scan.h>
#include <vector>

namespace rtlab {

AccelInfo Bvh::info() const {
    AccelInfo i = bvh_detail::size_info(
        nodes.size(), nodes.size() * sizeof(BvhNode) + prim_ids.size() * sizeof(std::uint32_t),
        prim_count, prim_ids, unreferenced_count);
    if (nodes.empty()) {
        return i;
    }
    bvh_detail::SahTally sah(config, nodes[0].bounds());
    bvh_detail::walk_from_root([&](std::uint32_t node, std::uint32_t depth, const auto& push) {
        const BvhNode& n = nodes[node];
        if (n.is_leaf()) {
            sah.leaf(n.bounds(), n.prim_count(), depth);
        } else {
            sah.inner(n.bounds());
            push(n.first, depth + 1);
            push(n.first + 1, depth + 1);
        }
    });
    sah.finish(i, prim_ids.size());
    return i;
}

std::string bvh_detail::check_prim_ids(std::span<const std::uint32_t> prim_ids,
                                       std::uint32_t prim_count,
                                       std::uint32_t unreferenced_count) {
    std::vector<char> seen(prim_count, 0);
    std::size_t ids = 0;  // distinct ids
    for (const std::uint32_t id : prim_ids) {
        if (id == padding_slot) {
            continue;
        }
        if (id >= prim_count) {
            return "primitive id " + std::to_string(id) + " out of range";
        }
        ids += seen[id] ? 0 : 1;
        seen[id] = 1;
    }
    if (ids + unreferenced_count != prim_count) {
        return "prim_ids holds " + std::to_string(ids) + " distinct ids, expected " +
               std::to_string(prim_count - unreferenced_count);
    }
    return {};
}

std::string bvh_detail::use_leaf_slots(std::span<const std::uint32_t> prim_ids,
                                       std::vector<char>& used,
                                       std::uint32_t first,
                                       std::uint32_t count) {
    if (first > prim_ids.size() || count > prim_ids.size() - first) {
        return "leaf range outside prim_ids";
    }
    for (std::uint32_t s = first; s < first + count; ++s) {
        if (used[s]) {
            return "prim_ids slot " + std::to_string(s) + " in two leaves";
        }
        if (prim_ids[s] == padding_slot) {
            return "padding slot " + std::to_string(s) + " in a leaf";
        }
        used[s] = 1;
    }
    if (count > 1) {
        std::vector<std::uint32_t> ids(prim_ids.begin() + first, prim_ids.begin() + first + count);
        std::sort(ids.begin(), ids.end());
        if (const auto twice = std::adjacent_find(ids.begin(), ids.end()); twice != ids.end()) {
            return "primitive " + std::to_string(*twice) + " twice in one leaf";
        }
    }
    return {};
}

std::string bvh_detail::check_slots_covered(std::span<const std::uint32_t> prim_ids,
                                            const std::vector<char>& used) {
    for (std::size_t s = 0; s < prim_ids.size(); ++s) {
        if (!used[s] && prim_ids[s] != padding_slot) {
            return "prim_ids slot " + std::to_string(s) + " lies in no leaf";
        }
    }
    return {};
}

Bvh align_leaf_slots(Bvh bvh, std::uint32_t k) {
    if (k <= 1 || bvh.nodes.empty()) {
        return bvh;
    }
    // Leaves in slot order each take their count rounded up to k slots, so a leaf's new first
    // slot is its old one plus the padding of the leaves before it: an exclusive prefix sum of
    // each leaf's padding, stored at its first slot (parallel, as the rest: the wide layouts'
    // two-thread builds must keep scaling).
    const std::size_t n = bvh.prim_ids.size();
    const auto leaves = [&](auto&& f) {
        bvh_detail::for_blocks(bvh.nodes.size(), [&](std::size_t, std::size_t lo, std::size_t hi) {
            for (std::size_t i = lo; i < hi; ++i) {
                if (bvh.nodes[i].is_leaf()) {
                    f(bvh.nodes[i]);
                }
            }
        });
    };
    // Zeroed in parallel, not at construction: this runs inside the wide and pair layouts' builds.
    ScratchVector<std::uint32_t> shift(n);
    bvh_detail::for_blocks(n, [&](std::size_t, std::size_t lo, std::size_t hi) {
        std::fill(shift.begin() + static_cast<std::ptrdiff_t>(lo),
                  shift.begin() + static_cast<std::ptrdiff_t>(hi), 0u);
    });
    leaves([&](const BvhNode& l) {
        const std::uint32_t c = l.prim_count();
        shift[l.first] = (c + k - 1) / k * k - c;
    });
    // In place: each block's final pass reads a slot's padding before writing its prefix.
    const std::uint32_t total = tbb::parallel_scan(
        tbb::blocked_range<std::size_t>(0, n, bvh_detail::reduce_block), 0u,
        [&](const tbb::blocked_range<std::size_t>& r, std::uint32_t sum, bool is_final) {
            for (std::size_t s = r.begin(); s != r.end(); ++s) {
                const std::uint32_t p = shift[s];
                if (is_final) {
                    shift[s] = sum;
                }
                sum += p;
            }
            return sum;
        },
        std::plus<>());
    std::vector<std::uint32_t> ids(n + total, padding_slot);
    leaves([&](BvhNode& l) {
        const auto from = bvh.prim_ids.begin() + l.first;
        l.first += shift[l.first];
        std::copy(from, from + l.prim_count(), ids.begin() + l.first);
    });
    bvh.prim_ids = std::move(ids);
    return bvh;
}

AccelInfo bvh_detail::size_info(std::size_t nodes,
                                std::size_t bytes,
                                std::uint32_t prim_count,
                                std::span<const std::uint32_t> prim_ids,
                                std::uint32_t unreferenced_count) {
    AccelInfo i;
    i.nodes = nodes;
    i.bytes = bytes;
    i.bytes_per_prim =
        prim_count == 0 ? 0.0 : static_cast<double>(bytes) / static_cast<double>(prim_count);
    const auto refs =
        static_cast<double>(prim_ids.size() - static_cast<std::size_t>(std::count(
                                                  prim_ids.begin(), prim_ids.end(), padding_slot)));
    const std::uint32_t referenced = prim_count - unreferenced_count;
    i.refs_per_prim = referenced == 0 ? 0.0 : refs / static_cast<double>(referenced);
    return i;
}

bvh_detail::SahTally::SahTally(const Bvh::Config& cfg, const Bounds3f& root)
    : ct_(static_cast<double>(cfg.traversal_cost))
    , ci_(static_cast<double>(cfg.intersection_cost))
    , root_area_(static_cast<double>(root.surface_area())) {}

void bvh_detail::SahTally::inner(const Bounds3f& b) {
    cost_ += static_cast<double>(b.surface_area()) * ct_;
}

void bvh_detail::SahTally::leaf(const Bounds3f& b, std::uint32_t count, std::uint32_t depth) {
    ++leaves_;
    max_depth_ = std::max(max_depth_, depth);
    cost_ += static_cast<double>(b.surface_area()) * ci_ * static_cast<double>(count);
}

void bvh_detail::SahTally::finish(AccelInfo& i, std::size_t prims) const {
    i.leaves = leaves_;
    i.max_depth = max_depth_;
    i.sah_cost = root_area_ > 0 ? cost_ / root_area_ : ci_ * static_cast<double>(prims);
}

std::string bvh_detail::NodeWalk::visit(std::uint32_t node, std::uint32_t depth) {
    if (node >= seen_.size() || seen_[node]) {
        return "out of range or reached twice";
    }
    seen_[node] = 1;
    ++visited_;
    if (depth > 64) {
        return "depth " + std::to_string(depth) + " > 64";
    }
    return {};
}

std::optional<std::string> bvh_detail::check_before_nodes(std::span<const std::uint32_t> prim_ids,
                                                          std::uint32_t prim_count,
                                                          std::uint32_t unreferenced_count,
                                                          std::size_t nodes) {
    if (std::string e = check_prim_ids(prim_ids, prim_count, unreferenced_count); !e.empty()) {
        return e;
    }
    if (nodes == 0) {
        return prim_ids.empty() ? std::string{} : "primitives but no nodes";
    }
    return std::nullopt;
}

std::string bvh_detail::NodeWalk::unreached() const {
    if (visited_ == seen_.size()) {
        return {};
    }
    return std::to_string(seen_.size() - visited_) + " nodes unreachable";
}

std::string Bvh::validate() const {
    if (auto v = bvh_detail::check_before_nodes(prim_ids, prim_count, unreferenced_count,
                                                nodes.size())) {
        return *v;
    }
    std::vector<char> slot_used(prim_ids.size(), 0);
    struct Item {
        std::uint32_t node, depth;
    };
    const auto check = [&](const Item& it, const std::string& where, auto& push) -> std::string {
        const BvhNode& n = nodes[it.node];
        const Bounds3f box = n.bounds();
        if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y && box.lo.z <= box.hi.z)) {
            return where + "empty or NaN box";
        }
        if (n.is_leaf()) {
            if (n.prim_count() > config.max_leaf_size) {
                return where + "leaf of " + std::to_string(n.prim_count()) + " > max_leaf_size";
            }
            if (std::string e =
                    bvh_detail::use_leaf_slots(prim_ids, slot_used, n.first, n.prim_count());
                !e.empty()) {
                return where + e;
            }
            return {};
        }
        if (n.axis() > 2) {
            return where + "split axis > 2";
        }
        if (n.first <= it.node || n.first + 1 >= nodes.size()) {
            return where + "children not after the parent or out of range";
        }
        for (std::uint32_t c = n.first; c <= n.first + 1; ++c) {
            if (!box.contains(nodes[c].bounds())) {
                return where + "child " + std::to_string(c) + " outside its parent";
            }
            push({c, it.depth + 1});
        }
        return {};
    };
    if (std::string e = bvh_detail::check_from_root(nodes.size(), Item{0, 0}, check); !e.empty()) {
        return e;
    }
    return bvh_detail::check_slots_covered(prim_ids, slot_used);
}

}  // namespace rtlab
