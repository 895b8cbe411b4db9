#pragma once
// Looking up a row of a cross-check's results (crosscheck/checks.h) in the oracle tests.

#include "crosscheck/checks.h"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace rtlab::test {

/// The row of method, precision and ray set (by default the "all" row); fails the test when
/// there is none.
inline const xcheck::Row& find_row(const std::vector<xcheck::Row>& rows,
                                   const std::string& method,
                                   const std::string& precision,
                                   const std::string& set = "all") {
    for (const xcheck::Row& r : rows) {
        if (r.method == method && r.precision == precision && r.set == set) {
            return r;
        }
    }
    FAIL("no row " << method << " " << precision << " " << set);
    return rows.front();
}

}  // namespace rtlab::test
