#!/bin/sh
# consumer_test.sh - firmware outside the tree built against an installed celscan (`make test-consumers`).
#
# Builds examples/consumer-make (pkg-config) and examples/consumer-cmake
# (find_package) against the `make install DESTDIR=STAGE PREFIX=/usr` tree,
# each for the host and for Cortex-M4F (a link check: ARM code, hard-float
# ABI), then runs both host programs: the demo, compiled by celc, must give
# the CRC celsim gives for its JSON at several sizes and times (the
# consumers convert float lines from cs_render_frame, celsim converts runs:
# two paths to the same pixels), and damaged input is reported, not shown.
# SMALL_STAGE holds a Cortex-M4F library installed with other capacities
# (MCU_CFG=examples/sign/sign_config_160x128.h): its pkg-config file must
# name that header as CS_CFG_FILE, and the firmware built against it must
# get the small structs (less RAM than with the default capacities).
#
# usage: consumer_test.sh STAGE WORK_DIR HOST_BUILD_DIR SMALL_STAGE
set -u
TL_NAME=test-consumers
. "$(dirname "$0")/testlib.sh"
stage=$1 work=$2 host=$3 small=$4
TL_CHECK_LOG=$work/last.log

rm -rf "$work"
mkdir -p "$work"
top=$(pwd)

check "consumer-make builds for host and Cortex-M4F" \
    make --no-print-directory -C examples/consumer-make SYSROOT="$stage" O="$work/make"
check "consumer-cmake configures for the host" \
    cmake -S examples/consumer-cmake -B "$work/cmake-host" -DCMAKE_PREFIX_PATH="$stage/usr"
check "consumer-cmake builds for the host" cmake --build "$work/cmake-host"
check "consumer-cmake configures for Cortex-M4F" \
    cmake -S examples/consumer-cmake -B "$work/cmake-arm" -DCMAKE_PREFIX_PATH="$stage/usr" \
    -DCMAKE_TOOLCHAIN_FILE="$top/examples/consumer-cmake/arm-none-eabi.cmake"
check "consumer-cmake builds for Cortex-M4F" cmake --build "$work/cmake-arm"

for elf in "$work/make/cortex-m4f/sign.elf" "$work/cmake-arm/sign.elf"; do
    check "$elf is ARM code" sh -c "readelf -h '$elf' | grep -q 'Machine: *ARM'"
    check "$elf passes floats in VFP registers" sh -c \
        "readelf -A '$elf' | grep -q 'Tag_ABI_VFP_args: VFP registers'"
done

"$host/celc" compile scenes/demo.json -o "$work/demo.cels" >/dev/null 2>&1
"$host/celc" compile scenes/demo-board.json -o "$work/demo-board.cels" >/dev/null 2>&1
for prog in "$work/make/host/sign" "$work/cmake-host/sign"; do
    for run in "demo 480x270 1" "demo 1280x720 0" "demo 333x187 2.25" "demo-board 480x272 0.5"; do
        set -- $run
        want=$("$host/celsim" render "scenes/$1.json" --size "$2" --time "$3" --crc 2>&1)
        got=$("$prog" "$work/$1.cels" "$2" "$3" 2>&1)
        if [ "$got" = "$want" ] && [ -n "$want" ]; then ok; else
            bad "$prog $1 $2 t=$3: '$got', celsim: '$want'"; fi
    done
    # a stream cut inside its only transaction commits nothing
    head -c 3000 "$work/demo.cels" >"$work/cut.cels"
    out=$("$prog" "$work/cut.cels" 64x32 0 2>&1)
    rc=$?
    check "$prog: cut stream: exit 1 (was $rc)" test "$rc" -eq 1
    check "$prog: cut stream reported at byte 3000" sh -c "echo '$out' | grep -q 'byte 3000: .*cut short'"
    out=$("$prog" "$work/demo.cels" 5000x10 0 2>&1)
    rc=$?
    check "$prog: a size beyond the library's capacity is refused (exit $rc)" test "$rc" -eq 2
done

# CS_CFG_FILE: the library's capacities travel with it to the firmware
check "the small library's pkg-config names its CS_CFG_FILE" grep -q \
    'Cflags: .*-DCS_CFG_FILE=\\"sign_config_160x128.h\\"' "$small/usr/share/pkgconfig/celscan-cortex-m4f.pc"
check "the small library's header is installed" test -f "$small/usr/include/celscan/sign_config_160x128.h"
check "consumer-make builds for Cortex-M4F against the small library" \
    make --no-print-directory -C examples/consumer-make SYSROOT="$small" O="$work/make-small" cortex-m4f
bss() { arm-none-eabi-size "$1" 2>/dev/null | awk 'NR == 2 { print $3 }'; }
b_default=$(bss "$work/make/cortex-m4f/sign.elf") b_small=$(bss "$work/make-small/cortex-m4f/sign.elf")
echo "test-consumers: Cortex-M4F sign.elf RAM (bss): ${b_default:-?} B with cs_config_480x272.h, ${b_small:-?} B with sign_config_160x128.h"
check "smaller capacities give the firmware smaller structs" test "${b_small:-0}" -gt 0 -a \
    "${b_small:-0}" -lt "${b_default:-0}"

tl_summary
