#!/bin/sh
# measure.sh ELF PLUGIN OUTDIR [FIRMWARE-ARGS] [STREAM...] - executed
# instructions per frame and per line, counted exactly by the insncount
# QEMU plugin.
#
# Boots the firmware with the plugin watching the five fw_mark_* functions
# (their addresses from the ELF's symbol table), then splits the count:
#   prep    cs_frame_begin: tracks sampled, transform, segments, monotone
#           pieces, sort
#   render  cs_render_line, per line (crossings, spans, coverage, compositing)
#   output  the line sink: RGB565 conversion and the panel write (the
#           semihost panel's, dump= in OUTDIR/frames); the frame's CRC-32 is
#           read back from the panel after the frame, outside the count (a
#           panel that cannot read back adds ~5 instructions a byte)
# A run with damage=1 has no panel: the semihost panel keeps its picture by
# copying the last frame's file into the new one at each frame's start
# (~170 k instructions, where glass keeps it for nothing), so there the
# count has the running CRC of the window's bytes instead.
# With STREAM files, they are sent over the UART one after the other
# (FIRMWARE-ARGS then name the frames, e.g. "frames=480x272@0:5"), and each
# frame is labelled with the file whose commit it shows. Without, the
# built-in jobs FIRMWARE-ARGS selects (default "jobs=0,2,5": the demo-like
# "signage", the animated and the beta-stack scenes at 480x272, aa 5).
# Per-frame counts are exact and repeatable; the whole-run total is not
# when a stream is sent, since the firmware polls the UART meanwhile.
set -eu
elf=$1 plugin=$2 out=$3
args=${4:-jobs=0,2,5}
shift 3
[ $# -gt 0 ] && shift
mkdir -p "$out/frames"
case " $args " in *" damage=1 "*) ;; *) args="$args dump=$out/frames" ;; esac
marks=""
for m in fw_mark_frame_begin fw_mark_frame_ready fw_mark_line_rendered fw_mark_line_out \
         fw_mark_frame_end; do
    a=$(arm-none-eabi-nm "$elf" | awk -v m="$m" '$3 == m {print $1}')
    [ -n "$a" ] || { echo "measure: $m not in $elf" >&2; exit 1; }
    marks="$marks,mark=0x$a"
done
names=""
if [ $# -gt 0 ]; then
    cat "$@" >"$out/stream.cels"
    for f in "$@"; do names="$names $(basename "$f" .cels)"; done
    args="$args stream=$(wc -c <"$out/stream.cels")"
else
    : >"$out/stream.cels"
fi
timeout "${FW_QEMU_TIMEOUT:-300}" qemu-system-arm -M mps2-an386 -display none -monitor none \
    -semihosting-config enable=on,target=native -serial stdio -kernel "$elf" \
    -plugin "$plugin$marks,out=$out/marks.log" -append "$args" <"$out/stream.cels" \
    >/dev/null 2>"$out/console.log"
python3 - "$out/marks.log" "$out/console.log" $names <<'PY'
import sys
log = [l.split() for l in open(sys.argv[1])]
names = sys.argv[3:]
jobs = []
for l in open(sys.argv[2]):
    w = l.split()
    if l.startswith("job ") and " scene " in l:
        jobs.append(l.strip())
    elif len(w) == 10 and w[0] == "frame" and w[2] == "size":
        k = int(w[9])
        jobs.append("%s (commit %d: %s) %s t=%s aa %s" %
                    (" ".join(w[:2]), k, names[k - 1] if 0 < k <= len(names) else "?",
                     w[3], w[5], w[7]))
frames, cur = [], None
for rec in log:
    if rec[0] == "total":
        total = int(rec[1])
        continue
    m, c = int(rec[0]), int(rec[1])
    if m == 0:
        cur = {"begin": c, "render": [], "output": []}
    elif m == 1:
        cur["ready"] = last = c
    elif m == 2:
        cur["render"].append(c - last)
        rendered = c
    elif m == 3:
        cur["output"].append(c - rendered)
        last = c
    elif m == 4:
        cur["end"] = c
        frames.append(cur)
print("instructions executed (QEMU insncount plugin, exact; Cortex-M4F, -O2):")
def show(job, f):
    n = len(f["render"])
    r, o = f["render"], f["output"]
    tot = f["end"] - f["begin"]
    print("  %s" % job)
    print("    frame %12d  = prep %d + render %d + output %d" %
          (tot, f["ready"] - f["begin"], sum(r), sum(o)))
    if n:
        print("    per line (%d lines): render mean %d, min %d, max %d; output %d; all %d" %
              (n, sum(r) // n, min(r), max(r), sum(o) // n, (sum(r) + sum(o)) // n))
    else:
        print("    no lines (nothing changed)")
if len(frames) <= 16:
    for job, f in zip(jobs, frames):
        show(job, f)
else:
    # A sequence (repeat=, damage=1): the first frame, then the whole run.
    show(jobs[0], frames[0])
    tots = [f["end"] - f["begin"] for f in frames]
    lines = [len(f["render"]) for f in frames]
    rest = tots[1:]
    print("  %d frames, %s .. %s: mean %d instructions per frame (%d after the first), "
          "min %d, max %d; %d lines rendered per frame on average (of %d)" %
          (len(tots), jobs[0].split(" t=")[-1].split()[0], jobs[-1].split(" t=")[-1].split()[0],
           sum(tots) // len(tots), sum(rest) // len(rest), min(tots), max(tots),
           sum(lines) // len(lines), max(lines)))
print("  whole run: %d instructions" % total)
PY
