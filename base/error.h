#pragma once
// The one exception type of rtlab's file-facing code (mesh/, scene/, datasets_gen/, trace/ and
// render/ file I/O, apps/): a small base library every layer may use.

#include <stdexcept>

namespace rtlab {

/// A user-facing failure (bad file, bad parameter): what() is one line naming the file or the
/// field and the problem.
struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace rtlab
