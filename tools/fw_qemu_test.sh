#!/bin/sh
# fw_qemu_test.sh ELF OUTDIR - boots the firmware under QEMU and checks that
# every frame it renders is bit-identical to the host renderer's.
#
# The firmware (mps2-an386 image) renders its built-in jobs, prints for each
#   job I scene NAME time_ms T size WxH aa N
#   frame crc32 XXXXXXXX
# and dumps the frame over semihosting to OUTDIR/frames/frameII.rgb565. For
# each job this script asks the host reference for the same frame and
# compares the CRC line and, when the reference can dump, every byte.
#
# The reference command is a template (FW_REF), with {scene} {size} {time}
# {aa} and {dump} replaced; the default is the host build of the core
# rendering the same built-in scene:
#   build/host/fw_host_ref --scene {scene} --size {size} --time {time} --aa {aa} \
#       --crc --float-crc --dump {dump}
# Once scenes arrive as streams, point it at celsim, e.g.
#   FW_REF='build/host/celsim render scenes/{scene}.cels --size {size} --time {time} --aa {aa} --crc'
# (without {dump} only the CRCs are compared). When the reference also
# prints `float crc32`, the CRC of the linear-light floats before pixel
# conversion, that is compared too: it shows bit-identical arithmetic,
# which the 5/6-bit panel format alone could hide.
#
# Also checked: the UART ingress delivers a known byte sequence intact, the
# run exits 0 within its timeout, the stack stays within its size, and a
# deliberate crash (stack overflow into the MPU guard, undefined
# instruction, division by zero) ends QEMU with a non-zero status instead
# of hanging. Prints `qemu-test: N passed, M failed` like the other tests.
set -u
elf=$1 out=$2
default_ref='build/host/fw_host_ref --scene {scene} --size {size} --time {time} --aa {aa} --crc --float-crc --dump {dump}'
ref=${FW_REF:-$default_ref}
tmo=${FW_QEMU_TIMEOUT:-120}
qemu="qemu-system-arm -M mps2-an386 -display none -monitor none
      -semihosting-config enable=on,target=native -kernel $elf"

pass=0 fail=0
ok() { pass=$((pass + 1)); echo "  ok   $*"; }
bad() { fail=$((fail + 1)); echo "  FAIL $*"; }

if ! command -v qemu-system-arm >/dev/null; then
    echo "qemu-test: qemu-system-arm missing (tools/install-deps.sh installs it)"
    echo "qemu-test: 0 passed, 1 failed"
    exit 1
fi
rm -rf "$out"
mkdir -p "$out/frames" "$out/ref"

# Link input: every byte value, and more than any FIFO would hold.
python3 -c '
import sys
data = bytes((i * 7 + 3) & 255 for i in range(3000)) + bytes(range(256))
sys.stdout.buffer.write(data)' >"$out/link.bin"
link_len=$(wc -c <"$out/link.bin")
link_crc=$(python3 -c 'import sys, zlib; print("%08X" % zlib.crc32(open(sys.argv[1], "rb").read()))' "$out/link.bin")

echo "qemu-test: booting $elf"
# shellcheck disable=SC2086
timeout "$tmo" $qemu -serial stdio -append "dump=$out/frames uart=$link_len fcrc=1" \
    <"$out/link.bin" >"$out/uart.log" 2>"$out/console.log"
status=$?
if [ $status -eq 0 ]; then ok "firmware ran and exited 0"
elif [ $status -eq 124 ]; then bad "firmware did not finish within ${tmo}s"
else bad "firmware exited with status $status"; fi
grep -E '^(FAULT|job .* error)' "$out/console.log" | sed 's/^/       /'

if grep -q "^link rx $link_len bytes crc32 $link_crc\$" "$out/console.log"; then
    ok "UART ingress: $link_len bytes, crc32 $link_crc"
else
    bad "UART ingress: expected $link_len bytes crc32 $link_crc, got: $(grep '^link rx' "$out/console.log")"
fi

# Pair each job line with the frame and float CRC lines that follow it.
awk '/^job [0-9]+ scene / {job = $0; crc = ""; next}
     /^frame crc32 / && job != "" {crc = $3; next}
     /^float crc32 / && job != "" && crc != "" {print job " crc " crc " fcrc " $3; job = ""}' \
    "$out/console.log" >"$out/jobs.txt"
jobs=$(wc -l <"$out/jobs.txt")
[ "$jobs" -ge 1 ] && ok "$jobs frames rendered" || bad "no frames rendered"

while read -r _ idx _ scene _ ms _ size _ aa _ crc _ fcrc; do
    time=$(awk -v ms="$ms" 'BEGIN {printf "%g", ms / 1000}')
    frame=$(printf '%s/frames/frame%02d.rgb565' "$out" "$idx")
    dump="$out/ref/frame$idx.rgb565"
    cmd=$(echo "$ref" | sed -e "s|{scene}|$scene|g" -e "s|{size}|$size|g" -e "s|{time}|$time|g" \
        -e "s|{aa}|$aa|g" -e "s|{dump}|$dump|g")
    $cmd >"$out/ref/out$idx.log" 2>"$out/ref/err$idx.log"
    host=$(awk '/^frame crc32 / {print toupper($3)}' "$out/ref/out$idx.log")
    host_f=$(awk '/^float crc32 / {print toupper($3)}' "$out/ref/out$idx.log")
    what="job $idx: $scene t=$time ${size} aa $aa"
    if [ -z "$host" ]; then
        bad "$what: the reference printed no CRC ($cmd)"
        continue
    fi
    if [ "$host" = "$(echo "$crc" | tr a-f A-F)" ]; then
        ok "$what: crc32 $crc equals the host's"
    else
        bad "$what: crc32 $crc on the target, $host on the host"
    fi
    if [ -n "$host_f" ]; then
        if [ "$host_f" = "$fcrc" ]; then
            ok "$what: linear floats bit-identical (crc32 $fcrc)"
        else
            bad "$what: linear floats differ: crc32 $fcrc on the target, $host_f on the host"
        fi
    fi
    case "$ref" in *{dump}*)
        if cmp -s "$frame" "$dump"; then
            ok "$what: all $(wc -c <"$dump") bytes of the frame equal"
        else
            bad "$what: frame bytes differ: $(python3 - "$frame" "$dump" <<'EOF'
import sys
a, b = (open(p, "rb").read() if p else b"" for p in sys.argv[1:3])
if len(a) != len(b):
    print("sizes %d and %d" % (len(a), len(b)))
else:
    px = [i // 2 for i in range(0, len(a), 2) if a[i:i + 2] != b[i:i + 2]]
    print("%d pixels, first at index %d" % (len(px), px[0]) if px else "none?")
EOF
)"
        fi ;;
    esac
done <"$out/jobs.txt"

used=$(awk '/^stack high-water/ {print $3, $5}' "$out/console.log")
if [ -n "$used" ] && [ "${used% *}" -lt "${used#* }" ]; then
    ok "stack high-water ${used% *} of ${used#* } bytes"
else
    bad "stack high-water not reported or stack exhausted ($used)"
fi

# A crash must end the run with 128 + the exception number, not hang it.
for c in stack:132:MemManage udf:134:UsageFault div0:134:UsageFault; do
    how=${c%%:*} rest=${c#*:}
    want=${rest%%:*} name=${rest#*:}
    # shellcheck disable=SC2086
    timeout 30 $qemu -serial null -append "crash=$how" >/dev/null 2>"$out/crash-$how.log"
    got=$?
    if [ $got -eq "$want" ] && grep -q "^FAULT: $name" "$out/crash-$how.log"; then
        ok "crash=$how: $name reported, exit status $got"
    else
        bad "crash=$how: expected $name and status $want, got status $got"
    fi
done

echo "qemu-test: $pass passed, $fail failed"
[ $fail -eq 0 ]
