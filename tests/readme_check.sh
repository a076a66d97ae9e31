#!/bin/sh
# readme_check.sh - tests/README.md lists every test file, and only files that exist;
# its example test program compiles against the core and passes.
#
#   sh tests/readme_check.sh [LIBCELSCAN.a]
#
# A test file is any .c, .h, .sh or .py under tests/ (programs, helpers,
# emulated devices, references): the README must name it in backquotes by its
# path from tests/ (`linuxhal/test_drm.c`), so a newcomer finds every test and
# what it holds to account. A name the README gives in backquotes with one of
# those endings must exist, in tests/ or from the top of the tree. One check
# per file. Given the host core library, every ```c block of the README that
# has a main() is built against it and run, and must pass: two checks each. The last line is
# `readme_check: N passed, M failed`.
TL_NAME=readme_check
. "$(dirname "$0")/testlib.sh"
lib=${1:+$(cd "$(dirname "$1")" && pwd)/$(basename "$1")}
cd "$(dirname "$0")" || exit 2
for f in $(find . -type f \( -name '*.c' -o -name '*.h' -o -name '*.sh' -o -name '*.py' \) | sed 's|^\./||' | sort); do
    if grep -qF "\`$f\`" README.md; then
        ok
    else
        bad "tests/$f is not in tests/README.md (add a row: what it checks, how it runs)"
    fi
done
for f in $(grep -oE '`[A-Za-z0-9_./-]+\.(c|h|sh|py)`' README.md | tr -d '`' | sort -u); do
    if [ -e "$f" ] || [ -e "../$f" ]; then
        ok
    else
        bad "tests/README.md names $f, which is not in tests/ or the tree"
    fi
done
if [ -n "$lib" ]; then
    work=$(mktemp -d) || exit 2
    awk -v dir="$work" '/^```c$/ { n++; f = 1; next } /^```$/ { f = 0 } f { print > (dir "/example" n ".c") }' \
        README.md
    for src in "$work"/example*.c; do
        grep -q '^int main' "$src" 2>/dev/null || continue
        what="the example program of tests/README.md ($(basename "$src"))"
        if ${CC:-cc} -std=c11 -Wall -Wextra -Werror -I../core -I. "$src" "$lib" -lm -o "$src.bin" \
            >"$work/log" 2>&1; then
            ok
            TL_CHECK_LOG=$work/log check "$what passes" "$src.bin"
        else
            bad "$what does not compile"
            tail -5 "$work/log"
        fi
    done
    rm -rf "$work"
fi
tl_summary
