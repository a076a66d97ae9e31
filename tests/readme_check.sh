#!/bin/sh
# readme_check.sh - tests/README.md lists every test file, and only files that exist.
#
#   sh tests/readme_check.sh
#
# A test file is any .c, .h, .sh or .py under tests/ (programs, helpers,
# emulated devices, references): the README must name it in backquotes by its
# path from tests/ (`linuxhal/test_drm.c`), so a newcomer finds every test and
# what it holds to account. A name the README gives in backquotes with one of
# those endings must exist, in tests/ or from the top of the tree. One check
# per file; the last line is `readme_check: N passed, M failed`.
TL_NAME=readme_check
. "$(dirname "$0")/testlib.sh"
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
tl_summary
