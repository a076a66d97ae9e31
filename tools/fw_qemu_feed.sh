#!/bin/sh
# fw_qemu_feed.sh INPUT LOG TIMEOUT QEMU-COMMAND... - runs a firmware image
# in QEMU with INPUT as its link's input (the -serial stdio the command
# names), sent only once the firmware has booted: once its console (QEMU's
# stderr, written to LOG) shows the `celfw ` banner, which main prints after
# board_init. QEMU's STM32 USART model takes input even while the USART is
# still disabled, and drops it. QEMU's stdout passes through; the exit
# status is QEMU's (124 if TIMEOUT seconds pass).
set -u
input=$1 log=$2 tmo=$3
shift 3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkfifo "$dir/link"
exec 3<>"$dir/link" # a reader and writer of our own: neither open blocks
timeout "$tmo" "$@" <"$dir/link" 2>"$log" &
qemu=$!
i=0
while ! grep -q '^celfw ' "$log" 2>/dev/null && kill -0 $qemu 2>/dev/null && [ $i -lt 1200 ]; do
    sleep 0.05
    i=$((i + 1))
done
cat "$input" >&3 &
feeder=$!
exec 3>&-
wait $qemu
status=$?
kill $feeder 2>/dev/null
wait $feeder 2>/dev/null
exit $status
