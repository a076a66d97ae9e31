#!/bin/sh
# check_core_symbols.sh NM OBJDUMP OBJ... - fails if the freestanding core needs
# anything from outside itself, or keeps mutable state.
#
# Every undefined symbol of the core's objects must be defined by another
# core object: a reference to memcpy, sqrtf, __stack_chk_fail or any other
# libc/libm symbol fails the build. A symbol in .data or .bss (nm types
# sections .data*, .bss*, COMMON) is a mutable global and fails it too;
# constant tables live in .rodata, or .data.rel.ro when position independent
# code needs relocated pointers (read-only after loading).
set -eu
nm_tool=$1
objdump_tool=$2
shift 2
defined=$(mktemp)
undefined=$(mktemp)
trap 'rm -f "$defined" "$undefined"' EXIT
"$nm_tool" --defined-only "$@" | awk 'NF==3 {print $3}' | sort -u >"$defined"
"$nm_tool" --undefined-only "$@" | awk '{print $NF}' | grep -v -e ':$' -e '^$' | sort -u >"$undefined"
status=0
outside=$(comm -23 "$undefined" "$defined")
if [ -n "$outside" ]; then
    echo "core references symbols from outside the core (libc/libm?):" >&2
    echo "$outside" | sed 's/^/  /' >&2
    status=1
fi
mutable=$("$objdump_tool" -t "$@" | awk '$NF != "" && ($0 ~ / \.(data|bss|sdata|sbss)([.\t ]|$)/ || $0 ~ /\*COM\*/) && $0 !~ /\.data\.rel\.ro/ && $0 !~ / l    df / {print $NF}' | grep -v '^\.' | sort -u || true)
if [ -n "$mutable" ]; then
    echo "core has mutable globals (.data/.bss):" >&2
    echo "$mutable" | sed 's/^/  /' >&2
    status=1
fi
[ $status -eq 0 ] && echo "core symbols: self-contained, no mutable globals ($# objects, $nm_tool)"
exit $status
