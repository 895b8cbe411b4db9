// TriangleSoA: building in slot order.

#include "trace/triangle_soa.h"

#include "accel/accel.h"

#include <cassert>

namespace rtlab {

VertexTriangleMethod<float>::Prepared TriangleSoA::vertices(std::uint32_t s) const {
    assert(layout == SoaLayout::vertices);
    return {{at(s, 0), at(s, 1), at(s, 2)},
            {at(s, 3), at(s, 4), at(s, 5)},
            {at(s, 6), at(s, 7), at(s, 8)}};
}

TriangleSoA make_triangle_soa(std::span<const VertexTriangleMethod<float>::Prepared> prims,
                              std::span<const std::uint32_t> slot_ids,
                              SoaLayout layout,
                              std::span<const std::uint32_t> ids) {
    TriangleSoA q;
    q.layout = layout;
    q.slots = static_cast<std::uint32_t>(slot_ids.size());
    const std::size_t groups = (slot_ids.size() + TriangleSoA::group - 1) / TriangleSoA::group;
    q.data.assign((groups + 1) * TriangleSoA::group_floats, 0.0f);  // + the zero padding group
    for (std::size_t s = 0; s < slot_ids.size(); ++s) {
        if (slot_ids[s] == padding_slot) {
            continue;  // zeros: in no leaf, never tested
        }
        const auto& p = prims[slot_ids[s]];
        // The edges exactly as MollerTrumbore computes them.
        const Vec3f b = layout == SoaLayout::edges ? p.p1 - p.p0 : p.p1;
        const Vec3f c = layout == SoaLayout::edges ? p.p2 - p.p0 : p.p2;
        float* const g = q.data.data() + s / TriangleSoA::group * TriangleSoA::group_floats;
        const std::size_t lane = s % TriangleSoA::group;
        for (std::size_t k = 0; k < 3; ++k) {
            g[k * TriangleSoA::group + lane] = p.p0[k];
            g[(3 + k) * TriangleSoA::group + lane] = b[k];
            g[(6 + k) * TriangleSoA::group + lane] = c[k];
        }
        const std::uint32_t id = ids.empty() ? slot_ids[s] : ids[slot_ids[s]];
        g[9 * TriangleSoA::group + lane] = std::bit_cast<float>(id);
    }
    return q;
}

}  // namespace rtlab
