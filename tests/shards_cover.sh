#!/usr/bin/env bash
# The CTest shards of the Catch2 suite (tests/CMakeLists.txt) cover it: the test cases the union
# of their file-tag specs selects are exactly those rtlab_tests runs without a spec.
# Usage: shards_cover.sh RTLAB_TESTS SPEC
set -euo pipefail
names() {  # Catch2 2's --list-* exits with the number of tests listed, not 0
    "$@" --list-test-names-only | sed '/^$/d' | sort || true
}
all=$(names "$1")
sharded=$(names "$1" -# "$2")
[[ -n "$all" ]] || { echo "FAIL: $1 lists no test cases"; exit 1; }
if [[ "$all" != "$sharded" ]]; then
    echo "FAIL: the shards' specs and the whole suite differ:"
    diff <(echo "$all") <(echo "$sharded") | head -20
    exit 1
fi
echo "shards cover all $(echo "$all" | wc -l) test cases"
