#pragma once
// --method for `rtlab trace` and `rtlab render`: the tracer set-up from --accel, --method and
// --robust, and the command-line wording of the method checks of trace/method_check.h (which
// `rtlab sweep` applies to its cases too).

#include "base/error.h"
#include "base/split.h"
#include "trace/method_check.h"
#include "trace/scene_tracer.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::app {

/// The tracer set-up for a parsed --accel spec, --method (comma-separated, at most one per
/// family: checked here, before the build) and --robust.
inline TraceSetup checked_setup(const AccelSpec& accel, const std::string& method, bool robust) {
    TraceSetup setup;
    setup.accel = accel;
    setup.methods = split_commas(method);
    check_one_method_per_family(setup.methods, "--method");
    setup.robust = robust;
    return setup;
}

/// When no method named by --method is used (the scene has no primitive of its families), throws
/// Error; when only some are unused (a list naming one method per family for many scenes), prints
/// one line on stderr saying which are ignored and what is used.
inline void check_methods_used(const SceneTracer& tracer,
                               const std::vector<std::string>& methods,
                               std::string_view command) {
    const MethodUse use = method_use(tracer_families(tracer), methods);
    if (use.unused.empty()) {
        return;
    }
    const std::string names = fmt::format("{}", fmt::join(use.unused, ","));
    const std::string families = fmt::format("{}", fmt::join(use.unused_families, "/"));
    if (use.none_used) {
        throw Error(
            fmt::format("--method {}: the scene has no {} primitives, so nothing would use "
                        "it (omit --method or pick a method of a family in the scene)",
                        names, families));
    }
    std::cerr << fmt::format(
        "rtlab {}: --method {} ignored (no {} primitives in the scene); using {}\n", command, names,
        families, fmt::join(tracer.set_methods(), ", "));
}

}  // namespace rtlab::app
