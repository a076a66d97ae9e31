#!/bin/sh
# fw_qemu_test.sh ELF OUTDIR [BOARD] - boots the firmware under QEMU and
# checks that every frame it renders is bit-identical to the host's.
# FW_QEMU is the board's machine (its BOARD_QEMU, default mps2-an386); the
# stream link is the -serial this script adds after it.
#
# 1. Built-in scenes. The firmware renders its built-in jobs, prints for each
#      job I scene NAME time_ms T size WxH aa N
#      frame crc32 XXXXXXXX / float crc32 XXXXXXXX
#    and dumps the frame over semihosting to OUTDIR/builtin/frames/. The host
#    build of the core renders the same scenes (FW_REF, default
#    build/host/fw_host_ref): the frame CRC, the CRC of the linear-light
#    floats and every byte of the frame must be equal. The same boot checks
#    that the UART delivers a known byte sequence intact.
#
# 2. Streamed scenes. Test scenes are compiled to cel streams on the host
#    (FW_CELC, default `build/host/celc compile`)
#    and sent over the UART in one stream:
#      the full signage demo (scenes/demo.json, FW_DEMO names another; 571
#      control points, rendered in bands of rows where its 275 segments do
#      not fit the board's arena at once), the animated scene with
#      keyframe tracks (tests/fw_tracks_scene.c), the beta-model stack
#      (scenes/beta-stack.json), then the demo again with one byte damaged
#      (a CRC error), the tracks scene cut short, the demo whole again, and
#      a patch transaction that moves a cel and brings it to the front.
#    After every commit and error the firmware renders the frame list FRAMES
#    from the scene on display. Every frame's CRC must equal celsim's for
#    the scene's JSON (`celsim render SCENE.json --size --time --aa --crc`,
#    the contract); the animated scene, which has no JSON yet, is compared
#    with the host core rendering the same C scene directly. Every frame's
#    floats and bytes must also equal the host's (fw_host_ref on the same
#    stream). The errors must be reported with the host reader's words and
#    byte offsets, and the frames after the damaged transaction must be
#    those before it: the picture stays, the firmware keeps running.
#
# 3. The link. Sections 1 and 2 send at the fastest rate QEMU's UART models
#    take (they deliver a byte as soon as the last one is read, whatever the
#    baud rate register says) while frames render: the receive interrupt
#    fills the ring during frames, and the stream still commits intact.
#    Then an overrun is injected (rxdrop=N: the board drops delivered byte N
#    as an overrun loses it) inside a demo transaction sent after the beta
#    stack: it is reported with its offset as bytes lost, the transaction
#    is dropped, the frames after it are those before (the picture stays),
#    and the demo sent whole after it commits and renders as in section 2.
#    Last, the board plays (play=8: the loop it runs on glass, frames at the
#    board clock's time) while the beta stack and the demo stream in; every
#    frame equals the host's render of what it shows at the printed instant.
#    Then damage: 20 frames of scenes/board-anim.json (aa 5 and aa 16) that
#    render and send only what changed (damage=1); each frame's dump (the
#    last one with the window patched in) and its CRC read back from the
#    panel equal the host's whole render of that instant.
#
# 4. Faults. The stack stays within its size, and a deliberate crash (stack
#    overflow into the MPU guard, undefined instruction, division by zero)
#    ends QEMU with a non-zero status instead of hanging.
#
# Prints `qemu-test BOARD: N passed, M failed` like the other tests.
set -u
elf=$1 out=$2 board=${3:-mps2-an386}
host=build/host
default_ref="$host/fw_host_ref --scene {scene} --size {size} --time {time} --aa {aa} --crc --float-crc --dump {dump}"
ref=${FW_REF:-$default_ref}
default_celc="$host/celc compile {json} -o {out}"
celc=${FW_CELC:-$default_celc}
celsim=${FW_CELSIM:-$host/celsim}
demo_json=${FW_DEMO:-scenes/demo.json}
FRAMES=${FW_FRAMES:-480x272@0:5,480x272@0.5:5,480x272@1.25:5,240x136@0.75:none}
tmo=${FW_QEMU_TIMEOUT:-120}
qemu="${FW_QEMU:-qemu-system-arm -M mps2-an386} -display none -monitor none
      -semihosting-config enable=on,target=native -kernel $elf"

pass=0 fail=0
ok() { pass=$((pass + 1)); echo "  ok   $*"; }
bad() { fail=$((fail + 1)); echo "  FAIL $*"; }

if ! command -v qemu-system-arm >/dev/null; then
    echo "qemu-test: qemu-system-arm missing (tools/install-deps.sh installs it)"
    echo "qemu-test $board: 0 passed, 1 failed"
    exit 1
fi
rm -rf "$out"
mkdir -p "$out/builtin/frames" "$out/builtin/ref" "$out/stream/frames" "$out/stream/ref"

crc_of() { python3 -c 'import sys, zlib; print("%08X" % zlib.crc32(open(sys.argv[1], "rb").read()))' "$1"; }

# boot LOG ARGS < INPUT: runs the firmware, the input sent on its link once
# it has booted (tools/fw_qemu_feed.sh); console to LOG, status in $status.
boot() {
    log=$1
    shift
    cat >"${log%.log}.link"
    # shellcheck disable=SC2086
    tools/fw_qemu_feed.sh "${log%.log}.link" "$log" "$tmo" $qemu -serial stdio -append "$*" \
        >"${log%.log}.uart"
    status=$?
    name=$(basename "$(dirname "$log")")
    if [ $status -eq 0 ]; then ok "$name: firmware ran and exited 0"
    elif [ $status -eq 124 ]; then bad "$name: firmware did not finish within ${tmo}s"
    else bad "$name: firmware exited with status $status"; fi
    grep -E '^(FAULT|job .* error|frame .* error|stream: link idle)' "$log" | sed 's/^/       /'
    used=$(awk '/^stack high-water/ {print $3, $5}' "$log")
    if [ -n "$used" ] && [ "${used% *}" -lt "${used#* }" ]; then
        ok "$name: stack high-water ${used% *} of ${used#* } bytes"
    else
        bad "$name: stack high-water not reported or stack exhausted ($used)"
    fi
}

# compare_frame WHAT FRAME_FILE CRC FCRC REF_CMD [DUMP]: runs the reference
# and compares its CRC lines (and the dump, if the command makes one).
# (Its variables are c_*: sh has no locals.)
compare_frame() {
    c_what=$1 c_frame=$2 c_crc=$3 c_fcrc=$4 c_cmd=$5 c_dump=${6:-}
    rlog=${c_dump:-$out/ref-last}.log
    $c_cmd >"$rlog" 2>"$rlog.err"
    host_c=$(awk '/^frame crc32 / {print toupper($3)}' "$rlog")
    host_f=$(awk '/^float crc32 / {print toupper($3)}' "$rlog")
    if [ -z "$host_c" ]; then
        bad "$c_what: the reference printed no CRC ($c_cmd: $(head -c 200 "$rlog.err"))"
        return
    fi
    if [ "$host_c" = "$c_crc" ]; then
        ok "$c_what: crc32 $c_crc equals $(echo "$c_cmd" | awk '{sub(".*/", "", $1); print $1}')'s"
    else
        bad "$c_what: crc32 $c_crc on the target, $host_c from: $c_cmd"
    fi
    if [ -n "$host_f" ]; then
        if [ "$host_f" = "$c_fcrc" ]; then
            ok "$c_what: linear floats bit-identical (crc32 $c_fcrc)"
        else
            bad "$c_what: linear floats differ: crc32 $c_fcrc on the target, $host_f on the host"
        fi
    fi
    if [ -n "$c_dump" ]; then
        if cmp -s "$c_frame" "$c_dump"; then
            ok "$c_what: all $(wc -c <"$c_dump") bytes of the frame equal"
        else
            bad "$c_what: frame bytes differ: $(python3 - "$c_frame" "$c_dump" <<'EOF'
import sys, os
a, b = (open(p, "rb").read() if os.path.exists(p) else b"" for p in sys.argv[1:3])
if len(a) != len(b):
    print("sizes %d and %d" % (len(a), len(b)))
else:
    px = [i // 2 for i in range(0, len(a), 2) if a[i:i + 2] != b[i:i + 2]]
    print("%d pixels, first at index %d" % (len(px), px[0]) if px else "none?")
EOF
)"
        fi
    fi
}

# --------------------------------------------------- 1. built-in scenes
echo "qemu-test: built-in scenes ($elf)"
# Link input: every byte value, and more than any FIFO would hold.
python3 -c '
import sys
data = bytes((i * 7 + 3) & 255 for i in range(3000)) + bytes(range(256))
sys.stdout.buffer.write(data)' >"$out/builtin/link.bin"
link_len=$(wc -c <"$out/builtin/link.bin")
link_crc=$(crc_of "$out/builtin/link.bin")
boot "$out/builtin/console.log" "dump=$out/builtin/frames uart=$link_len fcrc=1" <"$out/builtin/link.bin"
if grep -q "^link rx $link_len bytes crc32 $link_crc\$" "$out/builtin/console.log"; then
    ok "UART ingress: $link_len bytes, crc32 $link_crc"
else
    bad "UART ingress: expected $link_len bytes crc32 $link_crc, got: $(grep '^link rx' "$out/builtin/console.log")"
fi
# Pair each job line with the frame and float CRC lines that follow it.
awk '/^job [0-9]+ scene / {job = $0; crc = ""; next}
     /^frame crc32 / && job != "" {crc = $3; next}
     /^float crc32 / && job != "" && crc != "" {print job " crc " crc " fcrc " $3; job = ""}' \
    "$out/builtin/console.log" >"$out/builtin/jobs.txt"
jobs=$(wc -l <"$out/builtin/jobs.txt")
[ "$jobs" -ge 1 ] && ok "$jobs built-in frames rendered" || bad "no built-in frames rendered"
while read -r _ idx _ scene _ ms _ size _ aa _ crc _ fcrc; do
    time=$(awk -v ms="$ms" 'BEGIN {printf "%g", ms / 1000}')
    frame=$(printf '%s/builtin/frames/frame%02d.rgb565' "$out" "$idx")
    dump="$out/builtin/ref/frame$idx.rgb565"
    cmd=$(echo "$ref" | sed -e "s|{scene}|$scene|g" -e "s|{size}|$size|g" -e "s|{time}|$time|g" \
        -e "s|{aa}|$aa|g" -e "s|{dump}|$dump|g")
    case "$ref" in *{dump}*) ;; *) dump= ;; esac
    compare_frame "job $idx: $scene t=$time $size aa $aa" "$frame" "$crc" "$fcrc" "$cmd" "$dump"
done <"$out/builtin/jobs.txt"

# --------------------------------------------------- 2. streamed scenes
echo "qemu-test: streamed scenes"
s=$out/stream
gen() { # gen JSON OUT
    cmd=$(echo "$celc" | sed -e "s|{json}|$1|g" -e "s|{out}|$2|g")
    $cmd || bad "could not compile $1 to a cel stream ($cmd)"
}
gen "$demo_json" "$s/demo.cels"
gen scenes/beta-stack.json "$s/beta.cels"
$host/fw_cels_gen --tracks "$s/tracks.cels" || bad "could not write the tracks scene stream"
# The stream: pieces in order, with their offsets for the expected errors.
# The last piece is a patch transaction written here, record by record: it
# moves the demo's blob (the cel named so) and brings it to the front;
# demo-patched.json is the same edit made to the JSON, for celsim.
python3 - "$s" "$demo_json" <<'EOF' >"$s/pieces.txt"
import json, struct, sys, zlib
d, demo_json = sys.argv[1], sys.argv[2]
demo, tracks, beta = (open("%s/%s.cels" % (d, n), "rb").read() for n in ("demo", "tracks", "beta"))
damaged = bytearray(demo)
damaged[16 + 16 + 10] ^= 0x04       # a byte of the first record's payload: CRC mismatch
cut = tracks[:16 + 16 + 60]         # stream header, transaction header, part of the body
def rec(kind, payload):
    return struct.pack("<HI", kind, len(payload)) + payload
scene = json.load(open(demo_json))
at_blob = [c.get("name") for c in scene["cels"]].index("blob")
moved = [1.03366, -0.37622, 0.37622, 1.03366, 190, 200]
body = rec(0x0300, struct.pack("<I6f", at_blob, *moved)) + \
    rec(0x0204, struct.pack("<II", at_blob, 0)) + rec(0x0001, b"")
head = b"CSTX" + bytes([1, 0, 0, 0]) + struct.pack("<I", len(body))
head += struct.pack("<I", zlib.crc32(head))
patch = head + body + struct.pack("<I", zlib.crc32(head + body))
blob = scene["cels"].pop(at_blob)
assert blob["name"] == "blob"
blob["transform"] = moved
scene["cels"].insert(0, blob)
json.dump(scene, open(d + "/demo-patched.json", "w"), indent=1)
open(d + "/patched.cels", "wb").write(demo + patch)
pieces = [("demo", demo), ("tracks", tracks), ("beta", beta), ("damaged", bytes(damaged)),
          ("cut", cut), ("demo", demo), ("patch", patch)]
out, at = b"", []
for name, p in pieces:
    at.append((name, len(out)))
    out += p
open(d + "/all.cels", "wb").write(out)
for name, off in at:
    print(name, off)
EOF
stream_len=$(wc -c <"$s/all.cels")
off_damaged=$(awk '$1 == "damaged" {print $2}' "$s/pieces.txt")
off_cut=$(awk '$1 == "cut" {print $2}' "$s/pieces.txt")
boot "$s/console.log" "dump=$s/frames fcrc=1 stream=$stream_len frames=$FRAMES" <"$s/all.cels"
# Commit K shows: 1 demo, 2 tracks, 3 beta, 4 demo, 5 the patched demo (the
# damaged and cut transactions never commit).
scene_of() {
    case $1 in 1|4) echo demo ;; 2) echo tracks ;; 3) echo beta ;; 5) echo patched ;; *) echo none ;; esac
}

if grep -q "^stream: $stream_len bytes, 5 commits, 2 errors\$" "$s/console.log"; then
    ok "stream of $stream_len bytes: 5 commits, 2 errors"
else
    bad "stream: expected $stream_len bytes, 5 commits, 2 errors; got: $(grep '^stream: ' "$s/console.log")"
fi
# The errors, as the host reader words them for the same bytes.
grep '^stream error: ' "$s/console.log" >"$s/errors.fw"
$host/fw_host_ref --cels "$s/all.cels" --crc | grep '^stream error: ' >"$s/errors.host"
if [ -s "$s/errors.fw" ] && cmp -s "$s/errors.fw" "$s/errors.host"; then
    ok "stream errors reported as the host reader reports them:"
    sed 's/^/       /' "$s/errors.fw"
else
    bad "stream errors differ from the host reader's:"
    diff "$s/errors.fw" "$s/errors.host" | sed 's/^/       /'
fi
if sed -n 1p "$s/errors.fw" | grep -q "CRC mismatch.*(transaction at byte $((off_damaged + 16)) dropped)\$"; then
    ok "damaged transaction at byte $((off_damaged + 16)): CRC mismatch, dropped"
else
    bad "damaged transaction at byte $((off_damaged + 16)) not reported as a CRC mismatch"
fi
if sed -n 2p "$s/errors.fw" | grep -q "cut short.*(transaction at byte $((off_cut + 16)) dropped)\$"; then
    ok "transaction at byte $((off_cut + 16)) cut short by the next one: dropped"
else
    bad "cut transaction at byte $((off_cut + 16)) not reported as cut short"
fi

# Frames with the event before them: "F WxH T A K EVENT CRC FCRC".
awk '/^stream commit / {ev = "commit" $3; next}
     /^stream error: / {ev = "error" (++e); next}
     /^frame [0-9]+ size / {f = $2; size = $4; t = $6; aa = $8; k = $10; crc = ""; next}
     /^frame crc32 / && f != "" {crc = $3; next}
     /^float crc32 / && f != "" && crc != "" {print f, size, t, aa, k, ev, crc, $3; f = ""}' \
    "$s/console.log" >"$s/frames.txt"
nframes=$(wc -l <"$s/frames.txt")
nreq=$(echo "$FRAMES" | tr ',' '\n' | wc -l)
# After commits 1, 2, 3, error 1 (the damaged transaction), commits 4 and 5;
# error 2 arrives with the next transaction already open, so its frames wait
# for commit 4.
if [ "$nframes" -eq $((6 * nreq)) ]; then
    ok "$nframes streamed frames rendered ($nreq after each of 6 events)"
else
    bad "$nframes streamed frames rendered, expected $((6 * nreq))"
fi
while read -r f size t aa k ev crc fcrc; do
    scene=$(scene_of "$k")
    frame=$(printf '%s/frames/frame%02d.rgb565' "$s" "$f")
    what="frame $f ($scene after $ev, t=$t $size aa $aa)"
    if [ "$scene" = tracks ]; then
        compare_frame "$what" "$frame" "$crc" "$fcrc" \
            "$host/fw_host_ref --scene tracks --size $size --time $t --aa $aa --crc --float-crc --dump $s/ref/frame$f.rgb565" \
            "$s/ref/frame$f.rgb565"
    else
        case $scene in
        demo) json=$demo_json cels=$s/demo.cels ;;
        beta) json=scenes/beta-stack.json cels=$s/beta.cels ;;
        *) json=$s/demo-patched.json cels=$s/patched.cels ;;
        esac
        compare_frame "$what" "$frame" "$crc" "" "$celsim render $json --size $size --time $t --aa $aa --crc"
        compare_frame "$what" "$frame" "$crc" "$fcrc" \
            "$host/fw_host_ref --cels $cels --size $size --time $t --aa $aa --crc --float-crc --dump $s/ref/frame$f.rgb565" \
            "$s/ref/frame$f.rgb565"
    fi
done <"$s/frames.txt"
# The damaged transaction left the picture as it was.
awk '$6 == "commit3" {print $2, $3, $4, $7}' "$s/frames.txt" >"$s/before.txt"
awk '$6 == "error1" {print $2, $3, $4, $7}' "$s/frames.txt" >"$s/after.txt"
if [ -s "$s/after.txt" ] && cmp -s "$s/before.txt" "$s/after.txt"; then
    ok "after the damaged transaction every frame CRC is unchanged: the picture stays"
else
    bad "frames after the damaged transaction differ from those before it"
fi

# The contract itself: `make qemu-run STREAM=F SIZE=WxH TIME=T` prints the
# line `celsim render F --size WxH --time T --crc` prints (celsim's default
# anti-aliasing; the JSON compiled to a stream on the way).
run_line=$(tools/fw_qemu_run.sh "$elf" --stream scenes/beta-stack.json 320x180 0.25 | grep '^frame crc32 ')
sim_line=$($celsim render scenes/beta-stack.json --size 320x180 --time 0.25 --crc)
if [ -n "$run_line" ] && [ "$run_line" = "$sim_line" ]; then
    ok "qemu-run STREAM=scenes/beta-stack.json SIZE=320x180 TIME=0.25 prints celsim's line: $run_line"
else
    bad "qemu-run printed '$run_line', celsim '$sim_line'"
fi

# ------------------------------------------------------------- 3. the link
echo "qemu-test: the link"
ring=$(awk '/^link: ring high-water / {print $4, $6, $8}' "$s/console.log")
set -- $ring
if [ $# -eq 3 ] && [ "$1" -gt 16 ] && [ "$3" -eq 0 ]; then
    ok "streamed at full speed while rendering: the ring held up to $1 of $2 bytes, none lost"
else
    bad "ring use not reported, never above 16 bytes, or gaps: '$ring'"
fi
o=$out/overrun
mkdir -p "$o/frames"
cat "$s/beta.cels" "$s/demo.cels" "$s/demo.cels" >"$o/link.cels"
beta_len=$(wc -c <"$s/beta.cels")
drop=$((beta_len + 16 + 16 + 700)) # a byte inside the demo's body (1-based)
o_len=$(wc -c <"$o/link.cels")
boot "$o/console.log" "dump=$o/frames fcrc=1 stream=$((o_len - 1)) rxdrop=$drop frames=$FRAMES" \
    <"$o/link.cels"
if grep -q "^stream: $((o_len - 1)) bytes, 2 commits, 2 errors\$" "$o/console.log" &&
    grep -q "^link: ring high-water [0-9]* of [0-9]* bytes, 1 gaps\$" "$o/console.log"; then
    ok "byte $drop of $o_len dropped as an overrun: 1 gap, 2 commits, 2 errors"
else
    bad "overrun run: $(grep -E '^(stream|link): ' "$o/console.log" | tr '\n' ' ')"
fi
gap_line=$(grep '^stream error: ' "$o/console.log" | sed -n 1p)
if echo "$gap_line" | grep -q "^stream error: byte $((drop - 1)): bytes lost on the link (receive overrun).*(transaction at byte $((beta_len + 16)) dropped)\$"; then
    ok "overrun reported at its offset: $gap_line"
else
    bad "overrun not reported at byte $((drop - 1)) for the transaction at $((beta_len + 16)): $gap_line"
fi
awk '/^stream commit / {ev = "commit" $3; next}
     /^stream error: / {ev = "error" (++e); next}
     /^frame [0-9]+ size / {f = $2; size = $4; t = $6; aa = $8; crc = ""; next}
     /^frame crc32 / && f != "" {crc = $3; next}
     /^float crc32 / && f != "" && crc != "" {print ev, size, t, aa, crc, $3; f = ""}' \
    "$o/console.log" >"$o/frames.txt"
# Commit 1 is the beta stack (commit 3 of section 2), then the gap and the
# skipped rest of the damaged demo, then commit 2, the demo (commit 1 there).
awk '$6 == "commit3" {print $2, $3, $4, $7, $8}' "$s/frames.txt" >"$o/beta.want"
awk '$6 == "commit1" {print $2, $3, $4, $7, $8}' "$s/frames.txt" >"$o/demo.want"
for ev in commit1 error1 error2 commit2; do
    want=$o/beta.want
    [ $ev = commit2 ] && want=$o/demo.want
    awk -v ev=$ev '$1 == ev {print $2, $3, $4, $5, $6}' "$o/frames.txt" >"$o/$ev.got"
    if [ -s "$want" ] && cmp -s "$want" "$o/$ev.got"; then
        ok "frames after $ev equal those checked in section 2 ($(basename "$want" .want), CRC and floats)"
    else
        bad "frames after $ev differ from section 2's $(basename "$want" .want) frames"
    fi
done

# Playback while the stream arrives: the loop a board runs on glass
# (play=N frames at the board clock's time), the beta stack and then the
# demo streamed meanwhile. Every frame shows the built-in demo, the beta
# stack or the demo at the instant it prints, and must equal the host's.
p=$out/play
mkdir -p "$p"
cat "$s/beta.cels" "$s/demo.cels" >"$p/link.cels"
boot "$p/console.log" "play=8 fcrc=1" <"$p/link.cels"
if grep -q "^play: 8 frames, 2 commits, 0 errors\$" "$p/console.log" &&
    grep -q "^link: ring high-water [0-9]* of [0-9]* bytes, 0 gaps\$" "$p/console.log"; then
    ok "played 8 frames while the beta stack and the demo streamed in: 2 commits, no gap"
else
    bad "playback: $(grep -E '^(play|link): ' "$p/console.log" | tr '\n' ' ')"
fi
awk '/^play [0-9]+ time / {f = $2; t = $4; k = $6; crc = ""; next}
     /^frame crc32 / && f != "" {crc = $3; next}
     /^float crc32 / && f != "" && crc != "" {print f, t, k, crc, $3; f = ""}' \
    "$p/console.log" >"$p/frames.txt"
while read -r f t k crc fcrc; do
    case $k in
    0) what="play frame $f: built-in signage t=$t"
       cmd="$host/fw_host_ref --scene signage --size 480x272 --time $t --aa 5 --crc --float-crc" ;;
    1) what="play frame $f: beta stack t=$t"
       cmd="$host/fw_host_ref --cels $s/beta.cels --size 480x272 --time $t --aa 5 --crc --float-crc"
       compare_frame "$what" "" "$crc" "" "$celsim render scenes/beta-stack.json --size 480x272 --time $t --aa 5 --crc" ;;
    *) what="play frame $f: demo t=$t"
       cmd="$host/fw_host_ref --cels $s/demo.cels --size 480x272 --time $t --aa 5 --crc --float-crc"
       compare_frame "$what" "" "$crc" "" "$celsim render $demo_json --size 480x272 --time $t --aa 5 --crc" ;;
    esac
    compare_frame "$what" "" "$crc" "$fcrc" "$cmd"
done <"$p/frames.txt"

# ----------------------------------------------------------- damage
# Frames that render and send only what changed (damage=1, cs_frame_damage):
# every frame as the panel then holds it - its dump, the last frame's with
# the window patched in, and the whole frame's CRC read back from it - must
# equal the host's whole render of that instant. Two sequences of the
# board's animated scene: aa 5 (windows of whole rows) and aa 16 (a power
# of two: windows narrower than the rows).
echo "qemu-test: damage"
d=$out/damage
mkdir -p "$d/frames" "$d/ref"
gen scenes/board-anim.json "$d/anim.cels"
boot "$d/console.log" "frames=480x272@0:5,480x272@0.5:16 repeat=10 step_ms=50 damage=1" \
    "render=end dump=$d/frames stream=$(wc -c <"$d/anim.cels")" <"$d/anim.cels"
awk '/^frame [0-9]+ size / {f = $2; size = $4; t = $6; aa = $8; crc = ""; next}
     /^frame crc32 / && f != "" {crc = $3; next}
     / window [0-9]+ [0-9]+ [0-9]+ [0-9]+$/ && f != "" && crc != "" {
         print f, size, t, aa, crc, $(NF - 3), $(NF - 2), $(NF - 1), $NF; f = ""}' \
    "$d/console.log" >"$d/frames.txt"
part=$(awk '!($6 == 0 && $7 == 0 && $8 == 480 && $9 == 272)' "$d/frames.txt" | wc -l)
narrow=$(awk '$4 == 16 && $6 > 0' "$d/frames.txt" | wc -l)
if [ "$(wc -l <"$d/frames.txt")" -eq 20 ] && [ "$part" -ge 16 ] && [ "$narrow" -ge 1 ]; then
    ok "20 frames with damage, $part of them a window, $narrow narrower than the rows"
else
    bad "damage: $(wc -l <"$d/frames.txt") frames (want 20), $part windows, $narrow narrow ones"
fi
while read -r f size t aa crc x0 y0 x1 y1; do
    compare_frame "damaged frame $f (t=$t aa $aa, window $x0,$y0..$x1,$y1)" \
        "$(printf '%s/frames/frame%02d.rgb565' "$d" "$f")" "$crc" "" \
        "$host/fw_host_ref --cels $d/anim.cels --size $size --time $t --aa $aa --crc --dump $d/ref/frame$f.rgb565" \
        "$d/ref/frame$f.rgb565"
done <"$d/frames.txt"

# ------------------------------------------------------------ 4. faults
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

echo "qemu-test $board: $pass passed, $fail failed"
[ $fail -eq 0 ]
