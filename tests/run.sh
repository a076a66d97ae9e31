#!/bin/sh
# run.sh - runs test programs and sums their results.
#
#   tests/run.sh PROG... [-- 'shell command'...]
#
# Each PROG is a test binary built on tests/testlib.h: it prints its failures
# and ends with "<name>: N passed, M failed". Anything after "--" is a shell
# command: if it prints such a line its counts are summed, otherwise it is
# one check, passed if it exits 0. A program that exits
# non-zero without failures of its own (a crash, a sanitizer report) counts
# one failure more. The last line of output is exactly "N passed, M failed";
# the exit status is non-zero if anything failed. Each item's wall time is
# printed after it ("[time] 12.3 s: ITEM"), and the slowest ten at the end, so
# that a CI run over its time budget says where the time went.
passed=0
failed=0
mode=prog
tmp=$(mktemp) || exit 2
times=$(mktemp) || exit 2
trap 'rm -f "$tmp" "$times"' EXIT INT TERM

# Milliseconds since the epoch (GNU date).
now_ms() { echo $(($(date +%s%N) / 1000000)); }
# Prints and records how long ITEM took since $t0.
took() {
    ms=$(($(now_ms) - t0))
    line=$(printf '%d.%d s: %s' $((ms / 1000)) $((ms % 1000 / 100)) "$1")
    echo "[time] $line"
    printf '%d %s\n' "$ms" "$line" >>"$times"
}

for arg in "$@"; do
    if [ "$arg" = "--" ]; then
        mode=cmd
        continue
    fi
    t0=$(now_ms)
    if [ "$mode" = cmd ]; then
        sh -c "$arg" >"$tmp" 2>&1
        rc=$?
        cat "$tmp"
        took "$arg"
        # A command that reports its own counts (a test script, a nested
        # run.sh) is summed like a program; otherwise it is one check.
        line=$(grep -E '(^|: )[0-9]+ passed, [0-9]+ failed' "$tmp" | tail -n 1)
        if [ -n "$line" ]; then
            p=$(echo "$line" | sed -E 's/^(.*: )?([0-9]+) passed, ([0-9]+) failed.*/\2/')
            f=$(echo "$line" | sed -E 's/^(.*: )?([0-9]+) passed, ([0-9]+) failed.*/\3/')
            passed=$((passed + p))
            failed=$((failed + f))
            if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
                echo "FAIL: command exited with status $rc after reporting no failures: $arg"
                failed=$((failed + 1))
            fi
        elif [ "$rc" -eq 0 ]; then
            passed=$((passed + 1))
        else
            echo "FAIL: command exited with status $rc: $arg"
            failed=$((failed + 1))
        fi
        continue
    fi
    "$arg" >"$tmp" 2>&1
    rc=$?
    cat "$tmp"
    took "$arg"
    line=$(grep -E ': [0-9]+ passed, [0-9]+ failed$' "$tmp" | tail -n 1)
    if [ -z "$line" ]; then
        echo "FAIL: $arg exited with status $rc and printed no summary (crashed?)"
        failed=$((failed + 1))
        continue
    fi
    p=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed$/\1/')
    f=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed, ([0-9]+) failed$/\2/')
    passed=$((passed + p))
    failed=$((failed + f))
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "FAIL: $arg exited with status $rc after reporting no failures"
        failed=$((failed + 1))
    fi
done

echo "the slowest:"
sort -rn "$times" | head -n 10 | cut -d' ' -f2- | sed 's/^/    /'
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
