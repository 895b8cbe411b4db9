#pragma once
// Plan-time checks of a sweep's cases against their scenes, through the checks `rtlab trace`
// applies to its options (trace/method_check.h), so a case never measures something other than
// what its row names. Each scene is made once; nothing is built or traced.

#include "sweep/plan.h"
#include "sweep/sweep_file.h"

#include <string>
#include <vector>

namespace rtlab::sweep {

/// Checks every trace and render case of `cases` against its scene: a method list naming a method
/// whose family has no primitive in the scene is refused (trace refuses a list of which none is
/// used and warns for one of which some are; a sweep row must say what ran, so a case refuses
/// both). Throws rtlab::Error with one line naming `where` (the sweep file) and the places in the
/// file that make the case, e.g. "sweep.json: scenes[1] x methods[0]: method 'watertight' matches
/// no primitive of scene 'flake4-spheres' (sphere, polygon)"; a scene that cannot be made is
/// "sweep.json: scenes[1]: ...".
void check_cases(const SweepFile& s, const std::vector<Case>& cases, const std::string& where);

}  // namespace rtlab::sweep
