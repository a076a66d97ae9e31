#!/bin/sh
# qemu_check.sh CELC CELSIM ELF DIR FILE... - imported Lottie files on the 64 KiB board.
#
# Each FILE of DIR (the conformance set) is imported with `celc import` into a
# cel stream, streamed to the mps2-an386 firmware under QEMU
# (tools/fw_qemu_run.sh) and rendered there at 480x272 with 5 sub-scanlines
# (the board's setting) at t = 0.2 s and 0.5 s; each frame's CRC must equal
# celsim's for the same stream, size, time and AA. A FILE written
# scene:PATH is a scene JSON of the project, compiled with `celc compile`
# instead; one written lottie:PATH is a Lottie file of the project, imported. A FILE
# written too-many-WHAT:FILE is one whose scene is beyond the board's capacities: the
# board must refuse its stream with the error naming them ("scene store full: too many
# WHAT"), and render nothing. Prints one line per frame or refusal and ends with
# "lottie-qemu: N passed, M failed".
set -u
celc=$1 celsim=$2 elf=$3 dir=$4
shift 4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
for f in "$@"; do
    refuse=
    case $f in
    too-many-*:*) refuse=$(echo "${f%%:*}" | tr - ' ') f=${f#*:} ;;
    esac
    s=$tmp/$(basename "$f" .json).cels
    case $f in
    scene:*) make_it="$celc compile ${f#scene:} -o $s" ;;
    lottie:*) make_it="$celc import ${f#lottie:} -o $s -q" ;;
    *) make_it="$celc import $dir/$f -o $s -q" ;;
    esac
    if ! $make_it; then
        echo "$f: import failed"; fail=$((fail + 1)); continue
    fi
    if [ -n "$refuse" ]; then
        out=$(FW_QEMU_TIMEOUT=60 tools/fw_qemu_run.sh "$elf" --stream "$s" 480x272 0.2 5 2>&1)
        why=$(echo "$out" | sed -n 's/^stream error: //p' | head -1)
        if echo "$why" | grep -q "scene store full: $refuse" && echo "$out" | grep -q "0 commits"; then
            echo "$f: refused by the board ($(wc -c <"$s") B stream): $why"; pass=$((pass + 1))
        else
            echo "$f: FAIL: the board did not refuse it with '$refuse': '$why'"; fail=$((fail + 1))
        fi
        continue
    fi
    for t in 0.2 0.5; do
        want=$("$celsim" render "$s" --size 480x272 --time $t --aa 5 --crc 2>&1 | sed -n 's/^frame crc32 //p')
        got=$(FW_QEMU_TIMEOUT=60 tools/fw_qemu_run.sh "$elf" --stream "$s" 480x272 $t 5 2>&1 |
            sed -n 's/^frame crc32 //p')
        if [ -n "$want" ] && [ "$want" = "$got" ]; then
            echo "$f t=$t: board crc $got = celsim ($(wc -c <"$s") B stream)"; pass=$((pass + 1))
        else
            echo "$f t=$t: FAIL board crc '$got', celsim '$want'"; fail=$((fail + 1))
        fi
    done
done
echo "lottie-qemu: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
