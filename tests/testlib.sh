# testlib.sh - the shell tests' harness, on the contract of testlib.h.
#
#   TL_NAME=cli_stream
#   . "$(dirname "$0")/testlib.sh"
#
# ok counts a passed check; bad MESSAGE a failed one, printing
# "<name>: FAIL MESSAGE"; check DESCRIPTION COMMAND... runs the command and
# counts whether it succeeded (with TL_CHECK_LOG=FILE its output goes to
# FILE, whose last lines follow a failure). tl_summary prints the last line,
# "<name>: N passed, M failed", which tests/run.sh sums, and returns non-zero
# if anything failed. Sourced, not run: the counters are the script's own.
pass=0
fail=0

ok() { pass=$((pass + 1)); }

bad() {
    fail=$((fail + 1))
    echo "$TL_NAME: FAIL $*"
}

check() {
    tl_what=$1
    shift
    if [ -n "${TL_CHECK_LOG:-}" ]; then
        if "$@" >"$TL_CHECK_LOG" 2>&1; then ok; else bad "$tl_what"; tail -5 "$TL_CHECK_LOG"; fi
    elif "$@"; then
        ok
    else
        bad "$tl_what"
    fi
}

tl_summary() {
    echo "$TL_NAME: $pass passed, $fail failed"
    [ "$fail" -eq 0 ]
}
