#!/bin/sh
# fw_qemu_run.sh ELF SCENE SIZE TIME [AA] - boots the firmware under QEMU,
# renders one built-in scene at SIZE (WxH) and TIME (seconds, at most three
# decimals: the firmware takes whole milliseconds) with AA sub-scanlines,
# and prints the firmware's console, including the contract line
#   frame crc32 XXXXXXXX
# Used by `make qemu-run SCENE=signage SIZE=480x272 TIME=0.75`. When the
# stream decoder lands, STREAM=F will be fed to the UART instead of naming
# a built-in scene.
set -eu
elf=$1 scene=$2 size=$3 time=$4 aa=${5:-5}
ms=$(awk -v t="$time" 'BEGIN {
    ms = t * 1000; r = int(ms + 0.5)
    if (t !~ /^[0-9]*\.?[0-9]*$/ || (ms - r) > 1e-6 || (r - ms) > 1e-6) exit 1
    print r }') || { echo "qemu-run: TIME must be seconds with at most 3 decimals: $time" >&2; exit 2; }
exec timeout "${FW_QEMU_TIMEOUT:-120}" qemu-system-arm -M mps2-an386 -display none -monitor none \
    -semihosting-config enable=on,target=native -serial null -kernel "$elf" \
    -append "scene=$scene size=$size time_ms=$ms aa=$aa" 2>&1
