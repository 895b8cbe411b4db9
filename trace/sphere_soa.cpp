// SphereSoA: building in slot order.

#include "trace/sphere_soa.h"

#include "accel/accel.h"

namespace rtlab {

SphereSoA make_sphere_soa(std::span<const PreparedSphere<float>> prims,
                          std::span<const std::uint32_t> slot_ids,
                          std::span<const std::uint32_t> ids) {
    SphereSoA q;
    q.slots = static_cast<std::uint32_t>(slot_ids.size());
    const std::size_t groups = (slot_ids.size() + SphereSoA::group - 1) / SphereSoA::group;
    q.data.assign((groups + 1) * SphereSoA::group_floats, 0.0f);  // + the zero padding group
    for (std::size_t s = 0; s < slot_ids.size(); ++s) {
        if (slot_ids[s] == padding_slot) {
            continue;  // zeros: in no leaf, never tested
        }
        const PreparedSphere<float>& p = prims[slot_ids[s]];
        float* const g = q.data.data() + s / SphereSoA::group * SphereSoA::group_floats;
        const std::size_t lane = s % SphereSoA::group;
        for (std::size_t k = 0; k < 3; ++k) {
            g[k * SphereSoA::group + lane] = p.center[k];
        }
        g[3 * SphereSoA::group + lane] = p.radius2;
        const std::uint32_t id = ids.empty() ? slot_ids[s] : ids[slot_ids[s]];
        g[SphereSoA::id_row * SphereSoA::group + lane] = std::bit_cast<float>(id);
    }
    return q;
}

}  // namespace rtlab
