#!/bin/sh
# fw_qemu_run.sh ELF --stream FILE SIZE TIME [AA]
# fw_qemu_run.sh ELF --scene NAME SIZE TIME [AA]
#
# Boots the firmware under QEMU and prints its console, which includes the
# contract line
#   frame crc32 XXXXXXXX
# for one frame at SIZE (WxH), TIME (seconds) and AA sub-scanlines ("none"
# for one sample per pixel; default 16, celsim's default), so that
#   make qemu-run STREAM=F SIZE=WxH TIME=T
# prints what `celsim render F --size WxH --time T --crc` prints.
#
# --stream: FILE (a .cels stream; a .json scene is first compiled with
# FW_CELC, default `build/host/celc compile`) is sent over
# the UART; the frame is rendered from the last committed scene once the
# stream has ended (errors are printed as they happen).
# --scene: one of the firmware's built-in scenes; TIME must then be whole
# milliseconds.
set -eu
elf=$1 mode=$2 what=$3 size=$4 time=$5 aa=${6:-16}
# FW_QEMU: the board's machine (its BOARD_QEMU); the link is the next -serial.
qemu="${FW_QEMU:-qemu-system-arm -M mps2-an386} -display none -monitor none
      -semihosting-config enable=on,target=native -kernel $elf"
case $mode in
--stream)
    file=$what
    case $file in
    *.json)
        tmp=$(mktemp -d)
        trap 'rm -rf "$tmp"' EXIT
        default_celc="build/host/celc compile {json} -o {out}"
        cmd=$(echo "${FW_CELC:-$default_celc}" | sed -e "s|{json}|$file|g" -e "s|{out}|$tmp/s.cels|g")
        $cmd
        file=$tmp/s.cels ;;
    esac
    [ -r "$file" ] || { echo "qemu-run: cannot read $file" >&2; exit 2; }
    n=$(wc -c <"$file")
    log=$(mktemp)
    status=0
    # shellcheck disable=SC2086
    tools/fw_qemu_feed.sh "$file" "$log" "${FW_QEMU_TIMEOUT:-120}" $qemu -serial stdio \
        -append "stream=$n frames=$size@$time:$aa render=end" || status=$?
    cat "$log"
    rm -f "$log"
    exit $status
    ;;
--scene)
    ms=$(awk -v t="$time" 'BEGIN {
        ms = t * 1000; r = int(ms + 0.5)
        if (t !~ /^[0-9]*\.?[0-9]*$/ || (ms - r) > 1e-6 || (r - ms) > 1e-6) exit 1
        print r }') || { echo "qemu-run: TIME must be seconds with at most 3 decimals: $time" >&2; exit 2; }
    [ "$aa" = none ] && aa=0
    # shellcheck disable=SC2086
    exec timeout "${FW_QEMU_TIMEOUT:-120}" $qemu -serial null \
        -append "scene=$what size=$size time_ms=$ms aa=$aa" 2>&1
    ;;
*)
    echo "usage: fw_qemu_run.sh ELF --stream FILE|--scene NAME SIZE TIME [AA]" >&2
    exit 2 ;;
esac
