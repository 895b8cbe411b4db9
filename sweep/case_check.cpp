// check_cases: every case's method list (and exact mode) against the primitive families of its
// scene.
#include "sweep/case_check.h"

#include "base/error.h"
#include "base/split.h"
#include "trace/method_check.h"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <optional>
#include <string_view>

namespace rtlab::sweep {

void check_cases(const SweepFile& s, const std::vector<Case>& cases, const std::string& where) {
    // Cases come scene by scene (trace cases), so each scene is made, looked at and dropped once.
    std::vector<std::optional<std::vector<std::string_view>>> families(s.scenes.size());
    for (const Case& c : cases) {
        if (c.type == CaseType::crosscheck) {
            continue;  // no scene: its method is checked against its kind when the file loads
        }
        std::optional<std::vector<std::string_view>>& f = families[c.scene];
        if (!f) {
            try {
                f = scene_families(make_scene(s.scenes[c.scene]));
            } catch (const std::exception& e) {
                throw Error(fmt::format("{}: scenes[{}]: {}", where, c.scene, e.what()));
            }
        }
        const auto other = [](std::string_view family) { return family != "triangle"; };
        if (s.exact && std::any_of(f->begin(), f->end(), other)) {
            throw Error(
                fmt::format("{}: scenes[{}]: exact mode certifies triangle hits only, and "
                            "scene '{}' holds {} primitives",
                            where, c.scene, s.scenes[c.scene].label, fmt::join(*f, ", ")));
        }
        const MethodUse use = method_use(*f, split_commas(c.methods));
        if (use.unused.empty()) {
            continue;
        }
        // Only trace cases name methods; their list is one entry of the file's "methods".
        const auto m = std::find(s.methods.begin(), s.methods.end(), c.methods);
        const std::string present =
            f->empty() ? "no primitives" : fmt::format("{}", fmt::join(*f, ", "));
        throw Error(fmt::format(
            "{}: scenes[{}] x methods[{}]: method{} '{}' match{} no primitive of scene '{}' ({})",
            where, c.scene, m - s.methods.begin(), use.unused.size() > 1 ? "s" : "",
            fmt::join(use.unused, "', '"), use.unused.size() > 1 ? "" : "es",
            s.scenes[c.scene].label, present));
    }
}

}  // namespace rtlab::sweep
