#pragma once
// Structure specs: `NAME[,key=value]...`, e.g. `bvh:binned,max_leaf=8,bins=32`. Each registry row
// declares its parameters (key, kind, default, range, help, and the setting of the row under
// which each takes effect, e.g. bins only with from=pbinned|binned|sbvh); one parser serves the
// command line, the benchmarks, the tests and sweep files, and every output names the canonical
// spec (every parameter that takes effect, defaults included; none that does not) so a result
// always says exactly what ran, and two specs of one structure are one text.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab {

/// How a parameter's value is written and checked.
enum class ParamKind : std::uint8_t {
    integer,  ///< a whole number in [min, max]
    real,     ///< a finite number in [min, max], stored as float by the builders
    choice,   ///< one of `choices`, stored as its index
};

/// One parameter a registry row declares.
struct ParamSpec {
    std::string_view key;                   ///< name in the spec, e.g. "max_leaf"
    ParamKind kind = ParamKind::integer;    ///< how values are parsed and printed
    double default_value = 0;               ///< used when the spec does not name the key
    double min = 0;                         ///< smallest valid value (integer and real)
    double max = 0;                         ///< largest valid value (integer and real)
    std::string_view help;                  ///< one line for `rtlab list`
    std::vector<std::string_view> choices;  ///< the names of a choice parameter, in index order
    /// The choice parameter of the same row this one depends on; empty: it always takes effect.
    std::string_view needs;
    /// The values of `needs` under which this parameter takes effect (otherwise it has none).
    std::vector<std::string_view> needs_values;
    /// True when the value changes only how the structure is built (threads), never what.
    bool build_only = false;
    /// True when the value changes only how a tracer uses the structure, never the structure.
    bool tracer_only = false;

    /// The value written as `text` (a choice: its index); throws std::invalid_argument with one
    /// line naming `spec` and the key when text is malformed, not finite, not whole for an
    /// integer, outside [min, max] or not one of the choices.
    double parse(std::string_view spec, std::string_view text) const;
    /// The value v as the canonical spec writes it ("8", "1.5", "binned").
    std::string format(double v) const;
    /// The valid range or choices, as `rtlab list` shows them ("[1, 255]", "median|binned").
    std::string range_text() const;
    /// Where the parameter takes effect, as `rtlab list` shows it ("from=pbinned|binned"); empty
    /// when it always does.
    std::string needs_text() const;
};

/// An integer parameter with its default, inclusive range and help line.
ParamSpec integer_param(
    std::string_view key, double default_value, double min, double max, std::string_view help);

/// A real parameter (stored as float) with its default, inclusive range and help line.
ParamSpec real_param(
    std::string_view key, double default_value, double min, double max, std::string_view help);

/// A choice parameter: one of `choices` (stored as its index), default choices[default_index].
ParamSpec choice_param(std::string_view key,
                       std::size_t default_index,
                       std::vector<std::string_view> choices,
                       std::string_view help);

/// p taking effect only while the choice parameter `key` of its row has one of `values`.
ParamSpec only_with(ParamSpec p, std::string_view key, std::vector<std::string_view> values);

/// p marked as changing only how a structure is built, never what is built.
ParamSpec build_only(ParamSpec p);

/// p marked as changing only how a tracer uses a structure, never the structure.
ParamSpec tracer_only(ParamSpec p);

struct AccelEntry;

/// A parsed spec: the registry row plus one value per declared parameter (declaration order).
struct AccelSpec {
    const AccelEntry* entry = nullptr;  ///< the row; never null after parse_accel_spec
    std::vector<double> values;         ///< values[i] belongs to entry->params[i]

    /// `name,key=value,...` with every parameter that takes effect (applies), in declaration
    /// order, defaults included; parsing it gives the same text.
    std::string canonical() const;
    /// True when parameter i (of entry->params) takes effect with the other values: it needs no
    /// other setting, or the parameter it needs takes effect and has one of its needs_values.
    bool applies(std::size_t i) const;
    /// The value of parameter `key`; throws std::logic_error when the row has no such key.
    double value(std::string_view key) const;
    /// value(key) when the row declares `key` and it takes effect (applies), else `fallback`: a
    /// key without effect reaches no Config, so a structure records the same settings whichever
    /// row built it (bvh8,from=lbvh,max_leaf=4 collapses bvh:lbvh's tree, Config included).
    double value_or(std::string_view key, double fallback) const;
};

/// Parses `NAME[,key=value]...` against the registry. Throws std::invalid_argument with one line
/// naming the spec and the key for an unknown name (listing the known ones), an unknown key
/// (listing the row's keys), a repeated key, a malformed or non-finite value, a non-integer for
/// an integer key, a value outside the declared range and a key that has no effect with the other
/// settings (ParamSpec::needs), even when given its default.
AccelSpec parse_accel_spec(std::string_view text);

}  // namespace rtlab
