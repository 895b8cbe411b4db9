#pragma once
// --method values that would silently do nothing, and the tracer set-up from --accel, --method
// and --robust: shared by `rtlab trace` and `rtlab render`.

#include "apps/args.h"
#include "base/error.h"
#include "trace/method_families.h"
#include "trace/scene_tracer.h"

#include <algorithm>
#include <fmt/format.h>
#include <iostream>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab::app {

/// Rejects two methods of one family in --method (the tracer would use the first and silently
/// ignore the other). Call before building the tracer.
inline void check_one_method_per_family(const std::vector<std::string>& methods) {
    for (const MethodFamily& f : method_families()) {
        std::string first;
        for (const std::string& w : methods) {
            if (std::find(f.methods.begin(), f.methods.end(), w) == f.methods.end() || w == first) {
                continue;
            }
            if (!first.empty()) {
                throw Error(
                    fmt::format("--method names two methods of the {} family ('{}' and "
                                "'{}'); give at most one per family",
                                f.family, first, w));
            }
            first = w;
        }
    }
}

/// The tracer set-up for a canonical --accel spec, --method (comma-separated, at most one per
/// family: checked here, before the build) and --robust.
inline TraceSetup checked_setup(const std::string& accel, const std::string& method, bool robust) {
    TraceSetup setup;
    setup.accel = accel;
    setup.methods = split_commas(method);
    check_one_method_per_family(setup.methods);
    setup.robust = robust;
    return setup;
}

/// The methods named in `methods` that no set of the tracer uses (their families have no shapes
/// in the scene), each once, in the order given.
inline std::vector<std::string> unused_methods(const SceneTracer& tracer,
                                               const std::vector<std::string>& methods) {
    std::vector<std::string> unused;
    for (const std::string& w : methods) {
        bool used = false;
        for (const std::string& label : tracer.set_methods()) {
            used = used || label.substr(label.find('=') + 1) == w;
        }
        if (!used && std::find(unused.begin(), unused.end(), w) == unused.end()) {
            unused.push_back(w);
        }
    }
    return unused;
}

/// When no method named by --method is used (the scene has no primitive of its families), throws
/// Error; when only some are unused (a list naming one method per family for many scenes), prints
/// one line on stderr saying which are ignored and what is used.
inline void check_methods_used(const SceneTracer& tracer,
                               const std::vector<std::string>& methods,
                               std::string_view command) {
    const std::vector<std::string> unused = unused_methods(tracer, methods);
    if (unused.empty()) {
        return;
    }
    std::string names;
    std::string families;
    for (const std::string& m : unused) {
        names += (names.empty() ? "" : ",") + m;
        for (const MethodFamily& f : method_families()) {
            for (std::string_view fm : f.methods) {
                if (fm == m && families.find(f.family) == std::string::npos) {
                    families += (families.empty() ? "" : "/") + std::string(f.family);
                }
            }
        }
    }
    const std::set<std::string> distinct(methods.begin(), methods.end());
    if (unused.size() == distinct.size()) {
        throw Error(
            fmt::format("--method {}: the scene has no {} primitives, so nothing would use "
                        "it (omit --method or pick a method of a family in the scene)",
                        names, families));
    }
    std::string used;
    for (const std::string& label : tracer.set_methods()) {
        used += (used.empty() ? "" : ", ") + label;
    }
    std::cerr << fmt::format(
        "rtlab {}: --method {} ignored (no {} primitives in the scene); "
        "using {}\n",
        command, names, families, used);
}

}  // namespace rtlab::app
