#pragma once
// The checks of a method list against a scene, shared by `rtlab trace`, `rtlab render` and
// `rtlab sweep`: a method whose family has no primitive in the scene would be silently replaced
// by nothing (its family has no set), and a second method of one family would be silently
// ignored (the tracer uses the first). Every command asks the same two questions here; each
// words the answer for its own input (a --method option, a sweep file's case).

#include "scene/scene.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rtlab {

class SceneTracer;

/// The families (method_families() names) of the scene's non-empty primitive sets, each once, in
/// table order: the families a SceneTracer over the scene builds sets for, found without
/// preparing or building anything (one pass over the objects' shapes).
std::vector<std::string_view> scene_families(const Scene& scene);

/// The families of the tracer's sets, each once, in set order.
std::vector<std::string_view> tracer_families(const SceneTracer& tracer);

/// The family of the method called `name`, or "" when no family has one of that name.
std::string_view method_family(std::string_view name);

/// Throws rtlab::Error "<what> names two methods of the F family ('a' and 'b'); give at most one
/// per family" when `methods` names two methods of one family: the tracer would use the first and
/// ignore the other. `what` says where the list came from ("--method", "sweep.json: methods[1]").
void check_one_method_per_family(const std::vector<std::string>& methods, std::string_view what);

/// How a method list meets a scene.
struct MethodUse {
    /// The methods named whose family has no primitive in the scene (nothing would use them),
    /// each once, in the order named.
    std::vector<std::string> unused;
    /// Their families, each once, in the order of `unused` ("sphere", "triangle/sphere").
    std::vector<std::string_view> unused_families;
    /// True when at least one method is named and none of them would be used.
    bool none_used = false;
};

/// Which methods of `methods` no set of a scene whose primitive families are `families`
/// (scene_families(), tracer_families()) would use. The rule every command applies: none used
/// is an error everywhere; some unused is a warning for trace and render (one list for many
/// scenes) and an error for a sweep case (its row must say what ran).
MethodUse method_use(std::span<const std::string_view> families,
                     const std::vector<std::string>& methods);

}  // namespace rtlab
