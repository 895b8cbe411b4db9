#!/usr/bin/env bash
# Command-line contracts of the rtlab executable: help works, bad input is one line on stderr and a
# non-zero exit. Run by CTest with RTLAB set to the executable.
set -uo pipefail
: "${RTLAB:?set RTLAB to the rtlab executable}"
fail=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

expect_ok() {  # expect_ok DESCRIPTION ARGS...
    local what=$1; shift
    if ! "$RTLAB" "$@" >"$tmp/out" 2>"$tmp/err"; then
        echo "FAIL ($what): rtlab $* exited non-zero: $(head -c 300 "$tmp/err")"; fail=1
    fi
}
expect_error() {  # expect_error DESCRIPTION ARGS...: non-zero exit, exactly one line on stderr
    local what=$1; shift
    "$RTLAB" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    local lines
    lines=$(wc -l <"$tmp/err")
    if [[ $rc -eq 0 ]]; then
        echo "FAIL ($what): rtlab $* exited 0"; fail=1
    elif [[ $rc -ge 128 ]]; then
        echo "FAIL ($what): rtlab $* died with signal $((rc - 128))"; fail=1
    elif [[ $lines -ne 1 ]]; then
        echo "FAIL ($what): rtlab $* printed $lines lines on stderr:"; cat "$tmp/err"; fail=1
    fi
}

expect_ok "top-level help" --help
expect_ok "version" --version
expect_error "no subcommand"
expect_error "unknown subcommand" frobnicate
expect_error "unknown flag" crosscheck --prim triangle --bogus
expect_error "missing --prim" crosscheck
expect_error "bad --prim" crosscheck --prim teapot
expect_error "bad --precision" crosscheck --prim triangle --precision half
expect_error "zero rays" crosscheck --prim triangle --rays 0
expect_error "non-numeric rays" crosscheck --prim triangle --rays lots
expect_error "unknown method" crosscheck --prim triangle --method nope --rays 10
for sub in crosscheck; do
    expect_ok "$sub help" "$sub" --help
done

# Extra contracts registered by other subcommands' test scripts.
for extra in "$(dirname "$0")"/cli/*.sh; do
    [[ -f $extra ]] && source "$extra"
done

[[ $fail -eq 0 ]] && echo "cli contracts: all passed"
exit $fail
