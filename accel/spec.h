#pragma once
// Structure specs: `NAME[,key=value]...`, e.g. `bvh:binned,max_leaf=8,bins=32`. Each registry row
// declares its parameters (key, kind, default, range, help); one parser serves the command line,
// the benchmarks, the tests and sweep files, and every output names the canonical spec (all
// parameters, defaults included) so a result always says exactly what ran.

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

    /// The value written as `text` (a choice: its index); throws std::invalid_argument with one
    /// line naming `spec` and the key when text is malformed, not finite, not whole for an
    /// integer, outside [min, max] or not one of the choices.
    double parse(std::string_view spec, std::string_view text) const;
    /// The value v as the canonical spec writes it ("8", "1.5", "binned").
    std::string format(double v) const;
    /// The valid range or choices, as `rtlab list` shows them ("[1, 255]", "median|binned").
    std::string range_text() const;
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

struct AccelEntry;

/// A parsed spec: the registry row plus one value per declared parameter (declaration order).
struct AccelSpec {
    const AccelEntry* entry = nullptr;  ///< the row; never null after parse_accel_spec
    std::vector<double> values;         ///< values[i] belongs to entry->params[i]

    /// `name,key=value,...` with every parameter in declaration order, defaults included.
    std::string canonical() const;
    /// The value of parameter `key`; throws std::logic_error when the row has no such key.
    double value(std::string_view key) const;
    /// value(key) when the row declares `key`, else `fallback`.
    double value_or(std::string_view key, double fallback) const;
};

/// Parses `NAME[,key=value]...` against the registry. Throws std::invalid_argument with one line
/// naming the spec and the key for an unknown name (listing the known ones), an unknown key
/// (listing the row's keys), a repeated key, a malformed or non-finite value, a non-integer for
/// an integer key and a value outside the declared range.
AccelSpec parse_accel_spec(std::string_view text);

}  // namespace rtlab
