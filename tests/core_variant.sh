#!/bin/sh
# core_variant.sh - the two builds of the core in the host programs
# (tools/core_variant.h, mk/variant.mk) render the same bytes: every scene of
# scenes/ and scenes/bench/ at its canvas size in four AA modes, as the panel's
# CRC, a 16-bit linear PNG and an 8-bit sRGB PNG (the x86-64-v3 build writes
# 8-bit runs with SSSE3 shuffles of its own: cs_pixfmt.c), with --core baseline
# and --core x86-64-v3, and four scenes at five odd sizes as 8-bit PNGs;
# and the choice is refused or overridden as documented. The baseline build is
# the one the other tests hold to their references. On a CPU without
# x86-64-v3 (or a host that is not x86-64) the comparisons are skipped, and
# the refusal to select it is what is checked.
#
#   sh tests/core_variant.sh build/host/celsim
TL_NAME=core_variant
. "$(dirname "$0")/testlib.sh"

celsim=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The frame of scene $1 in mode $2 by build $3: CRC line, then the PNGs' bytes.
render() {
    "$celsim" render "$1" --aa "$2" --core "$3" --threads 1 --crc --encoding linear \
        -o "$tmp/$3.png" >"$tmp/$3.crc" 2>"$tmp/$3.err" &&
        "$celsim" render "$1" --aa "$2" --core "$3" --threads 1 -o "$tmp/$3-8.png" \
            2>>"$tmp/$3.err"
}

if "$celsim" render scenes/demo.json --crc --core x86-64-v3 >/dev/null 2>"$tmp/v3.err"; then
    for s in scenes/*.json scenes/bench/*.json; do
        for aa in none 5 16 exact; do
            if ! render "$s" "$aa" baseline || ! render "$s" "$aa" x86-64-v3; then
                bad "$s --aa $aa did not render: $(cat "$tmp"/*.err)"
            elif cmp -s "$tmp/baseline.crc" "$tmp/x86-64-v3.crc" &&
                cmp -s "$tmp/baseline.png" "$tmp/x86-64-v3.png" &&
                cmp -s "$tmp/baseline-8.png" "$tmp/x86-64-v3-8.png"; then
                ok
            else
                bad "$s --aa $aa: x86-64-v3 $(cat "$tmp/x86-64-v3.crc")," \
                    "baseline $(cat "$tmp/baseline.crc")"
            fi
        done
    done
    # The display pass of the v3 build writes runs ahead in blocks of 32
    # pixels and clamps its last blocks to the line (cs_line.c): odd widths,
    # narrower and wider than a block, put every run end and line end
    # against those blocks; the 8-bit PNGs hold the bytes it wrote.
    for size in 17x9 45x13 97x41 333x19 1021x7; do
        for s in scenes/demo.json scenes/sign.json scenes/bench/blobs.json scenes/bench/thin.json; do
            for aa in 5 exact; do
                for b in baseline x86-64-v3; do
                    "$celsim" render "$s" --size "$size" --aa "$aa" --core "$b" --threads 1 \
                        -o "$tmp/$b-w.png" 2>"$tmp/$b.err"
                done
                check "$s $size --aa $aa: the same 8-bit bytes from both builds" \
                    cmp -s "$tmp/baseline-w.png" "$tmp/x86-64-v3-w.png"
            done
        done
    done
    # Bands on threads of the v3 build give the baseline's single-thread bytes.
    render scenes/bench/blobs.json exact baseline
    "$celsim" render scenes/bench/blobs.json --aa exact --core x86-64-v3 --threads 3 --crc \
        >"$tmp/bands.crc" 2>&1
    check "blobs exact, v3 on 3 threads = baseline on 1" cmp -s "$tmp/baseline.crc" "$tmp/bands.crc"
else
    echo "$TL_NAME: this CPU or host has no x86-64-v3 build: comparisons skipped"
    check "--core x86-64-v3 refused with a reason" grep -q "x86-64-v3" "$tmp/v3.err"
fi

# An unknown build is a usage error that names it.
"$celsim" render scenes/demo.json --crc --core pentium >/dev/null 2>"$tmp/usage.err"
rc=$?
if [ "$rc" -eq 2 ] && grep -q "pentium" "$tmp/usage.err"; then
    ok
else
    bad "--core pentium: exit $rc"
fi

# A bad CELSCAN_CORE is named on stderr and the CPU chooses; the frame is the same.
"$celsim" render scenes/demo.json --crc --core baseline >"$tmp/want.crc" 2>/dev/null
CELSCAN_CORE=pentium "$celsim" render scenes/demo.json --crc >"$tmp/env.crc" 2>"$tmp/env.err"
rc=$?
if [ "$rc" -eq 0 ] && grep -q "CELSCAN_CORE=pentium" "$tmp/env.err" &&
    cmp -s "$tmp/want.crc" "$tmp/env.crc"; then
    ok
else
    bad "CELSCAN_CORE=pentium: exit $rc, $(cat "$tmp/env.err")"
fi
tl_summary
