#pragma once
// Lists the tests read from the registry instead of writing them by hand, so a new row reaches
// every test that iterates them.

#include "accel/any_accel.h"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace rtlab::test {

/// The binary BVH builders a layout row converts (the choices of bvh8's `from`, in order).
inline std::vector<std::string> from_choices() {
    const AccelEntry* e = find_accel("bvh8");
    REQUIRE(e != nullptr);
    for (const ParamSpec& p : e->params) {
        if (p.key == "from") {
            return {p.choices.begin(), p.choices.end()};
        }
    }
    FAIL("bvh8 has no `from` parameter");
    return {};
}

}  // namespace rtlab::test
