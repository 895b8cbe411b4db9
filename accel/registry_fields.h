#pragma once
// How the registry declares a parameter once: a Config member together with its ParamSpec (key,
// range, default taken from the Config, help), and a choice together with the values its names
// stand for. Parsing, canonical specs, `rtlab list` and the tests read the ParamSpec; the build
// reads the member or the value through the same declaration, so a key is never spelled twice
// and a choice is never read by its index. Included by accel/registry.cpp only.

#include "accel/spec.h"

#include <cmath>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtlab::registry {

template <class>
struct MemberOf;
template <class C, class M>
struct MemberOf<M C::*> {
    using Config = C;
    using Value = M;
};

/// A choice parameter and the value each of its names stands for (values[i] for choice i).
template <class E>
struct Choice {
    ParamSpec param;
    std::vector<E> values;

    /// The value the spec chose.
    E of(const AccelSpec& s) const {
        return values.at(static_cast<std::size_t>(s.value(param.key)));
    }
    /// The value the spec chose, or `absent` for a row without the key or where it takes no
    /// effect (AccelSpec::value_or).
    E of_or(const AccelSpec& s, E absent) const {
        const double v = s.value_or(param.key, -1.0);
        return v < 0.0 ? absent : values.at(static_cast<std::size_t>(v));
    }
};

/// A choice of `key` among (name, value) pairs, the default the one named `default_name`.
template <class E>
Choice<E> choice(std::string_view key,
                 std::string_view default_name,
                 std::initializer_list<std::pair<std::string_view, E>> named,
                 std::string_view help) {
    std::vector<std::string_view> names;
    Choice<E> c;
    std::size_t default_index = 0;
    for (const auto& [name, value] : named) {
        default_index = name == default_name ? names.size() : default_index;
        names.push_back(name);
        c.values.push_back(value);
    }
    c.param = choice_param(key, default_index, std::move(names), help);
    return c;
}

/// One Config member a spec may set: its parameter, and how a parsed value is stored in it.
template <class Config>
struct Field {
    ParamSpec param;
    std::function<void(Config&, double)> store;
};

/// The field of member P declared by p; the parsed value is converted to the member's type.
template <auto P>
Field<typename MemberOf<decltype(P)>::Config> field(ParamSpec p) {
    using C = typename MemberOf<decltype(P)>::Config;
    using V = typename MemberOf<decltype(P)>::Value;
    return {std::move(p), [](C& c, double v) { c.*P = static_cast<V>(v); }};
}

/// The field of member P set by the choice ch: the member takes the value the chosen name stands
/// for.
template <auto P>
Field<typename MemberOf<decltype(P)>::Config> field(
    const Choice<typename MemberOf<decltype(P)>::Value>& ch) {
    using C = typename MemberOf<decltype(P)>::Config;
    return {ch.param, [values = ch.values](C& c, double v) {
                c.*P = values.at(static_cast<std::size_t>(v));
            }};
}

/// A Config with every field the spec's row declares and that takes effect stored; the others
/// keep the Config's defaults.
template <class Config>
Config config_from(const AccelSpec& s, std::initializer_list<const Field<Config>*> fields) {
    Config c;
    constexpr double absent = std::numeric_limits<double>::quiet_NaN();
    for (const Field<Config>* f : fields) {
        const double v = s.value_or(f->param.key, absent);
        if (!std::isnan(v)) {
            f->store(c, v);
        }
    }
    return c;
}

}  // namespace rtlab::registry
