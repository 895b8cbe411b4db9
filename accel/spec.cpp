// Structure specs: parsing `NAME[,key=value]...` against the registry rows and writing the
// canonical form.

#include "accel/spec.h"

#include "accel/any_accel.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace rtlab {

namespace {

/// Shortest text that reads back as the same float (values of real parameters are floats).
std::string shortest_float(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof(buf), static_cast<float>(v));
    return std::string(buf, r.ptr);
}

std::string join_keys(const AccelEntry& e) {
    if (e.params.empty()) {
        return "no parameters";
    }
    std::string out = "takes ";
    for (const ParamSpec& p : e.params) {
        out += fmt::format("{}{}", &p == e.params.data() ? "" : ", ", p.key);
    }
    return out;
}

std::string known_names() {
    std::string out;
    for (const AccelEntry& e : accel_registry()) {
        out += fmt::format("{}{}", out.empty() ? "" : ", ", e.name);
    }
    return out;
}

[[noreturn]] void fail(std::string_view spec, const std::string& what) {
    throw std::invalid_argument(fmt::format("--accel '{}': {}", spec, what));
}

/// The index of parameter `key` in row e; throws std::logic_error when the row has none.
std::size_t param_index(const AccelEntry& e, std::string_view key) {
    for (std::size_t i = 0; i < e.params.size(); ++i) {
        if (e.params[i].key == key) {
            return i;
        }
    }
    throw std::logic_error(fmt::format("{} has no parameter {}", e.name, key));
}

/// Why parameter i of s has no effect (s.applies(i) is false), in one line.
std::string no_effect_reason(const AccelSpec& s, std::size_t i) {
    const ParamSpec& p = s.entry->params[i];
    const std::size_t j = param_index(*s.entry, p.needs);
    const ParamSpec& q = s.entry->params[j];
    if (!s.applies(j)) {
        return fmt::format("'{}' has no effect: it applies with {}, and '{}' has none here", p.key,
                           p.needs_text(), q.key);
    }
    return fmt::format("'{}' has no effect with {}={} (it applies with {})", p.key, q.key,
                       q.format(s.values[j]), p.needs_text());
}

}  // namespace

ParamSpec integer_param(
    std::string_view key, double default_value, double min, double max, std::string_view help) {
    ParamSpec p;
    p.key = key;
    p.kind = ParamKind::integer;
    p.default_value = default_value;
    p.min = min;
    p.max = max;
    p.help = help;
    return p;
}

ParamSpec real_param(
    std::string_view key, double default_value, double min, double max, std::string_view help) {
    ParamSpec p = integer_param(key, default_value, min, max, help);
    p.kind = ParamKind::real;
    return p;
}

ParamSpec choice_param(std::string_view key,
                       std::size_t default_index,
                       std::vector<std::string_view> choices,
                       std::string_view help) {
    ParamSpec p = integer_param(key, static_cast<double>(default_index), 0,
                                static_cast<double>(choices.size()) - 1, help);
    p.kind = ParamKind::choice;
    p.choices = std::move(choices);
    return p;
}

ParamSpec only_with(ParamSpec p, std::string_view key, std::vector<std::string_view> values) {
    p.needs = key;
    p.needs_values = std::move(values);
    return p;
}

ParamSpec tracer_only(ParamSpec p) {
    p.tracer_only = true;
    return p;
}

ParamSpec build_only(ParamSpec p) {
    p.build_only = true;
    return p;
}

double ParamSpec::parse(std::string_view spec, std::string_view text) const {
    if (kind == ParamKind::choice) {
        for (std::size_t i = 0; i < choices.size(); ++i) {
            if (choices[i] == text) {
                return static_cast<double>(i);
            }
        }
        fail(spec, fmt::format("{} must be one of {}, not '{}'", key, range_text(), text));
    }
    double v = 0;
    const char* end = text.data() + text.size();
    const auto r = std::from_chars(text.data(), end, v);
    if (text.empty() || r.ec != std::errc{} || r.ptr != end || !std::isfinite(v)) {
        fail(spec, fmt::format("{} needs a number, not '{}'", key, text));
    }
    if (kind == ParamKind::integer && v != std::floor(v)) {
        fail(spec, fmt::format("{} must be a whole number, not '{}'", key, text));
    }
    double lo = min;
    double hi = max;
    if (kind == ParamKind::real) {  // the builders store floats: compare in float
        v = static_cast<double>(static_cast<float>(v));
        lo = static_cast<double>(static_cast<float>(min));
        hi = static_cast<double>(static_cast<float>(max));
    }
    if (!(v >= lo && v <= hi)) {
        fail(spec, fmt::format("{}={} is outside {}", key, text, range_text()));
    }
    return v;
}

std::string ParamSpec::format(double v) const {
    switch (kind) {
    case ParamKind::integer:
        return std::to_string(static_cast<long long>(v));
    case ParamKind::real:
        return shortest_float(v);
    case ParamKind::choice:
        return std::string(choices.at(static_cast<std::size_t>(v)));
    }
    return {};
}

std::string ParamSpec::range_text() const {
    if (kind == ParamKind::choice) {
        std::string out;
        for (std::string_view c : choices) {
            out += fmt::format("{}{}", out.empty() ? "" : "|", c);
        }
        return out;
    }
    return fmt::format("[{}, {}]", format(min), format(max));
}

std::string ParamSpec::needs_text() const {
    if (needs.empty()) {
        return {};
    }
    std::string out;
    for (std::string_view v : needs_values) {
        out += fmt::format("{}{}", out.empty() ? "" : "|", v);
    }
    return fmt::format("{}={}", needs, out);
}

std::string AccelSpec::canonical() const {
    std::string out(entry->name);
    for (std::size_t i = 0; i < entry->params.size(); ++i) {
        if (applies(i)) {
            out += fmt::format(",{}={}", entry->params[i].key, entry->params[i].format(values[i]));
        }
    }
    return out;
}

bool AccelSpec::applies(std::size_t i) const {
    const ParamSpec& p = entry->params.at(i);
    if (p.needs.empty()) {
        return true;
    }
    const std::size_t j = param_index(*entry, p.needs);
    const std::string_view v = entry->params[j].choices.at(static_cast<std::size_t>(values[j]));
    return applies(j) &&
           std::find(p.needs_values.begin(), p.needs_values.end(), v) != p.needs_values.end();
}

double AccelSpec::value(std::string_view key) const {
    return values[param_index(*entry, key)];
}

double AccelSpec::value_or(std::string_view key, double fallback) const {
    for (std::size_t i = 0; i < entry->params.size(); ++i) {
        if (entry->params[i].key == key) {
            return applies(i) ? values[i] : fallback;
        }
    }
    return fallback;
}

AccelSpec parse_accel_spec(std::string_view text) {
    const std::size_t comma = text.find(',');
    const std::string_view name = text.substr(0, comma);
    const AccelEntry* e = find_accel(name);
    if (e == nullptr) {
        fail(text, fmt::format("unknown structure '{}' (known: {}; see rtlab list)", name,
                               known_names()));
    }
    AccelSpec spec = default_spec(*e);
    std::vector<bool> given(e->params.size(), false);
    std::string_view rest = comma == std::string_view::npos ? "" : text.substr(comma + 1);
    if (comma != std::string_view::npos && rest.empty()) {
        fail(text, "empty parameter after ','");
    }
    while (!rest.empty()) {
        const std::size_t next = rest.find(',');
        const std::string_view item = rest.substr(0, next);
        rest = next == std::string_view::npos ? "" : rest.substr(next + 1);
        if (next != std::string_view::npos && rest.empty()) {
            fail(text, "empty parameter after ','");
        }
        const std::size_t eq = item.find('=');
        if (eq == std::string_view::npos || eq == 0) {
            fail(text, fmt::format("'{}' is not key=value", item));
        }
        const std::string_view key = item.substr(0, eq);
        std::size_t i = 0;
        while (i < e->params.size() && e->params[i].key != key) {
            ++i;
        }
        if (i == e->params.size()) {
            fail(text, fmt::format("unknown parameter '{}' ({} {})", key, e->name, join_keys(*e)));
        }
        if (given[i]) {
            fail(text, fmt::format("parameter '{}' given twice", key));
        }
        given[i] = true;
        spec.values[i] = e->params[i].parse(text, item.substr(eq + 1));
    }
    // Only now are the settings a key depends on known, wherever they stand in the text.
    for (std::size_t i = 0; i < e->params.size(); ++i) {
        if (given[i] && !spec.applies(i)) {
            fail(text, no_effect_reason(spec, i));
        }
    }
    return spec;
}

}  // namespace rtlab
