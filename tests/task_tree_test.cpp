// The builders' task tree (accel/task_tree.h): a toy top-down build gives the same nodes and leaf
// lists for 1 and 2 threads and for task thresholds from 1 to beyond the input, in both layouts
// the builders use (BVH child pairs, kd-tree pre-order), and the registry's builders give the same
// tree for 1 and 2 threads.

#include "accel/task_tree.h"

#include "accel/any_accel.h"
#include "base/thread_arena.h"
#include "support/accel_fixtures.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rtlab {
namespace {

/// A toy node: a leaf lists ids[first, first + count); an inner node links its child `first`.
struct ToyNode {
    std::uint32_t first = 0, count = 0;
    friend bool operator==(const ToyNode&, const ToyNode&) = default;
};

using ToyTree = TaskTree<std::vector<ToyNode>>;

struct ToyOutput {
    std::vector<ToyNode> nodes;
    std::vector<std::uint32_t> ids;
    friend bool operator==(const ToyOutput&, const ToyOutput&) = default;
};

/// Splits [b, e) at an uneven point (from the values) until ranges of at most 3 are leaves; with
/// `pairs` the parent adds both child slots (BVH), else each child's root is added where its
/// nodes start and the node links its second child (kd-tree pre-order).
void toy_build(ToyTree& tree,
               ToyTree::Chunk& out,
               std::uint32_t slot,
               const std::vector<std::uint32_t>& v,
               std::uint32_t b,
               std::uint32_t e,
               bool pairs) {
    if (e - b <= 3) {
        out.nodes[slot] = {static_cast<std::uint32_t>(out.ids.size()), e - b};
        out.ids.insert(out.ids.end(), v.begin() + b, v.begin() + e);
        return;
    }
    const std::uint32_t m = b + 1 + v[b] % (e - b - 1);
    const auto child = [&](std::uint32_t lo, std::uint32_t hi) {
        return [&, lo, hi](ToyTree::Chunk& c, std::uint32_t at) {
            toy_build(tree, c, at, v, lo, hi, pairs);
        };
    };
    std::uint32_t first = ToyTree::append, second = ToyTree::append;
    if (pairs) {
        first = static_cast<std::uint32_t>(out.nodes.size());
        second = first + 1;
        out.nodes.resize(out.nodes.size() + 2);
    }
    const auto [l, r] = tree.fork(out, TaskBranch{first, m - b, child(b, m)},
                                  TaskBranch{second, e - m, child(m, e)});
    out.nodes[slot] = {pairs ? l : r, 0};
}

ToyOutput toy_tree(const std::vector<std::uint32_t>& v, TaskSettings s, bool pairs) {
    ToyTree tree(s, v.size());
    toy_build(tree, tree.root(), 0, v, 0, static_cast<std::uint32_t>(v.size()), pairs);
    ToyOutput out;
    tree.splice(out.nodes, &out.ids, [](ToyNode n, const auto& node_of, const auto& id_of) {
        n.first =
            static_cast<std::uint32_t>(n.count != 0 ? id_of(n.first, n.count) : node_of(n.first));
        return n;
    });
    return out;
}

TEST_CASE("task tree gives the serial tree for any threads and threshold", "[accel][task_tree]") {
    const bool pairs = GENERATE(true, false);
    const std::uint32_t count = GENERATE(1u, 2u, 17u, 3000u);
    test::Rng rng(count);
    std::vector<std::uint32_t> v(count);
    for (std::uint32_t& x : v) {
        x = rng.below(1u << 20);
    }
    const ToyOutput serial = toy_tree(v, {1, false, 0}, pairs);
    for (const std::uint32_t task_min : {1u, 2u, 5u, 100u, 1u << 30}) {
        for (const std::uint32_t threads : {1u, 2u}) {
            CAPTURE(pairs, count, task_min, threads);
            const ToyOutput t = with_threads(threads, [&] {
                return toy_tree(v, {task_min, true, 2}, pairs);
            });
            CHECK(t == serial);
        }
    }
    const TaskSettings chunks{5, true, 2, TaskLayout::chunks};
    const ToyOutput one = with_threads(1, [&] { return toy_tree(v, chunks, pairs); });
    const ToyOutput two = with_threads(2, [&] { return toy_tree(v, chunks, pairs); });
    CHECK(one == two);
    CHECK(one.nodes.size() == serial.nodes.size());
}

TEST_CASE("builders give the same tree for 1 and 2 threads", "[accel][task_tree]") {
    const std::string spec =
        GENERATE(as<std::string>{}, "bvh:binned", "bvh:pbinned", "bvh:sbvh", "bvh:sweep",
                 "bvh:median", "bvh:lbvh", "kdtree:sah", "kdtree:median", "kdtree:sah,perfect=0");
    CAPTURE(spec);
    const test::Soup soup = test::random_soup(test::SoupKind::triangles, 7, 20000);
    BuildInput in = soup.input();
    in.clip = [&soup](std::uint32_t id, const Bounds3f& box) {
        const auto& t = soup.triangles[id];
        return clip_triangle_bounds(t.p0, t.p1, t.p2, box);
    };
    const AnyAccel one = build_accel(spec + ",threads=1", in);
    const AnyAccel two = build_accel(spec + ",threads=2", in);
    if (const auto* a = std::get_if<Bvh>(&one)) {
        const Bvh& b = std::get<Bvh>(two);
        CHECK(a->nodes == b.nodes);
        CHECK(a->prim_ids == b.prim_ids);
    } else {
        const KdTree& a2 = std::get<KdTree>(one);
        const KdTree& b2 = std::get<KdTree>(two);
        CHECK(a2.nodes == b2.nodes);
        CHECK(a2.prim_ids == b2.prim_ids);
    }
}

}  // namespace
}  // namespace rtlab
