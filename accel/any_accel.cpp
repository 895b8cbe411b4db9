// Registry look-ups, building from specs, and the visitors over AnyAccel.

#include "accel/any_accel.h"

namespace rtlab {

const AccelEntry* find_accel(std::string_view name) {
    for (const AccelEntry& e : accel_registry()) {
        if (e.name == name) {
            return &e;
        }
    }
    return nullptr;
}

AccelSpec default_spec(const AccelEntry& e) {
    AccelSpec s;
    s.entry = &e;
    for (const ParamSpec& p : e.params) {
        s.values.push_back(p.default_value);
    }
    return s;
}

AnyAccel build_accel(const AccelSpec& spec, const BuildInput& in) {
    return spec.entry->build(in, spec);
}

AnyAccel build_accel(std::string_view spec, const BuildInput& in) {
    return build_accel(parse_accel_spec(spec), in);
}

AccelInfo accel_info(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) { return s.info(); });
}

std::string accel_validate(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) { return s.validate(); });
}

Bounds3f accel_bounds(const AnyAccel& a) {
    return visit_accel(a, [](const auto& s) { return s.bounds(); });
}

}  // namespace rtlab
