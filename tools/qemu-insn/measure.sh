#!/bin/sh
# measure.sh ELF PLUGIN OUTDIR [FIRMWARE-ARGS] - executed instructions per
# frame and per line, counted exactly by the insncount QEMU plugin.
#
# Boots the firmware with the plugin watching the five fw_mark_* functions
# (their addresses from the ELF's symbol table), then splits the count:
#   prep    cs_frame_begin: transform, segments, monotone pieces, sort
#   render  cs_render_line, per line (crossings, spans, coverage, compositing)
#   output  the line sink: RGB565 conversion and CRC-32 (and the panel write,
#           which on QEMU is a no-op without dump=)
# FIRMWARE-ARGS default to the demo-like scene "signage" and the animated
# and beta-stack scenes at 480x272 with 5 sub-scanlines: "jobs=0,2,5".
set -eu
elf=$1 plugin=$2 out=$3
args=${4:-jobs=0,2,5}
mkdir -p "$out"
marks=""
for m in fw_mark_frame_begin fw_mark_frame_ready fw_mark_line_rendered fw_mark_line_out \
         fw_mark_frame_end; do
    a=$(arm-none-eabi-nm "$elf" | awk -v m="$m" '$3 == m {print $1}')
    [ -n "$a" ] || { echo "measure: $m not in $elf" >&2; exit 1; }
    marks="$marks,mark=0x$a"
done
timeout "${FW_QEMU_TIMEOUT:-300}" qemu-system-arm -M mps2-an386 -display none -monitor none \
    -semihosting-config enable=on,target=native -serial null -kernel "$elf" \
    -plugin "$plugin$marks,out=$out/marks.log" -append "$args" 2>"$out/console.log"
python3 - "$out/marks.log" "$out/console.log" <<'PY'
import sys
log = [l.split() for l in open(sys.argv[1])]
jobs = [l.strip() for l in open(sys.argv[2]) if l.startswith("job ") and " scene " in l]
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
for job, f in zip(jobs, frames):
    n = len(f["render"])
    r, o = f["render"], f["output"]
    tot = f["end"] - f["begin"]
    print("  %s" % job)
    print("    frame %12d  = prep %d + render %d + output %d" %
          (tot, f["ready"] - f["begin"], sum(r), sum(o)))
    print("    per line (%d lines): render mean %d, min %d, max %d; output %d; all %d" %
          (n, sum(r) // n, min(r), max(r), sum(o) // n, (sum(r) + sum(o)) // n))
print("  whole run: %d instructions" % total)
PY
