#!/bin/sh
# bench_run.sh - what `make bench` measures, written to RESULTS/*.txt.
#
#   tools/bench_run.sh BENCH CELSIM RESULTS SCRATCH [bench options...]
#
# Runs the bench program (speed, accuracy, beam racing, scaling), the
# celsim command line of issue 8's "done" criterion on the Many-blobs scene,
# and one frame under callgrind for an instruction count that does not
# depend on the machine's load. Each result is a Markdown fragment that
# tools/bench_md.py splices into BENCHMARKS.md.
set -eu
bench=$1
celsim=$2
res=$3
tmp=$4
shift 4
start=$(date +%s)

# The build of the core the host programs render with (tools/core_variant.h):
# CELSCAN_CORE's if set, else the fastest this CPU runs.
core=${CELSCAN_CORE:-$("$celsim" render scenes/demo.json --crc --core x86-64-v3 >/dev/null 2>&1 &&
    echo x86-64-v3 || echo baseline)}

{
    echo "- machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -n 1)"
    echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
    echo "- commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD -- core host-sim bench ':!bench/results' 2>/dev/null || echo ' (with local changes)')"
    echo "- compiler: $(${CC:-cc} --version | head -n 1), bench at -O2; the core's build: $core (baseline x86-64 at -O2, or -O3 -march=x86-64-v3; \`CELSCAN_CORE\`, tools/core_variant.h)"
    echo "- cairo $(dpkg-query -W -f='${Version}' libcairo2 2>/dev/null || pkg-config --modversion cairo), FreeType $(dpkg-query -W -f='${Version}' libfreetype6 2>/dev/null || pkg-config --modversion freetype2), AGG $(dpkg-query -W -f='${Version}' libagg-dev 2>/dev/null || pkg-config --modversion libagg) (Debian packages)"
    echo "- load average at start: $(cut -d' ' -f1-3 /proc/loadavg) (the machine is shared: medians and ratios, not absolute times, are the figures to trust)"
    echo "- command: \`make bench\` (runs \`$bench --out $res${*:+ $*}\`, then the celsim and callgrind runs below)"
} >"$res/machine.txt"

"$bench" --out "$res" "$@"

# The issue's own command line, next to cairo on the same scene and size:
# nine rounds, each running the four commands once in turn (so that a slow
# spell of the shared machine falls on all of them), the medians, and the
# median of each round's ratio to cairo, which the machine's load moves less.
{
    rounds=9
    echo "### celsim on Many-blobs at 1920x1080, next to cairo ($rounds interleaved rounds)"
    echo
    # one thread: the board's path (make bench-threads measures --threads 2)
    args16="render scenes/bench/blobs.json --size 1920x1080 --aa 16 --repeat 5 --threads 1"
    argsx="render scenes/bench/blobs.json --size 1920x1080 --aa exact --repeat 5 --threads 1"
    argsb="$argsx --core baseline"
    argsc="--profile blobs --peer cairo --frames 5"
    r16= rx= rb= rc= qx= qb=
    for round in $(seq "$rounds"); do
        # each prints "<ms> ms/frame"
        t16=$("$celsim" $args16 | cut -d' ' -f1)
        tx=$("$celsim" $argsx | cut -d' ' -f1)
        tb=$("$celsim" $argsb | cut -d' ' -f1)
        tc=$("$bench" $argsc | cut -d' ' -f1)
        r16="$r16 $t16" rx="$rx $tx" rb="$rb $tb" rc="$rc $tc"
        qx="$qx $(awk -v a="$tx" -v c="$tc" 'BEGIN { printf "%.3f", a / c }')"
        qb="$qb $(awk -v a="$tb" -v c="$tc" 'BEGIN { printf "%.3f", a / c }')"
    done
    med() { printf '%s\n' "$@" | sort -g | sed -n "$(( ($# + 1) / 2 ))p"; }
    echo "| command (each a median of 5 frames) | rounds, ms/frame | median ms/frame |"
    echo "|---|---|---:|"
    echo "| \`celsim $args16\` | $r16 | $(med $r16) |"
    echo "| \`celsim $argsx\` ($core build) | $rx | $(med $rx) |"
    echo "| \`celsim $argsb\` | $rb | $(med $rb) |"
    echo "| \`bench $argsc\` (cairo, default antialias) | $rc | $(med $rc) |"
    echo
    echo "celsim --aa exact / cairo, the median of the rounds' ratios: $(med $qx) with the $core build"
    echo "(rounds:$qx), $(med $qb) with the baseline build (rounds:$qb). Issue 8 asks for at most 0.5,"
    echo "issue 27 for at most 0.6."
} >"$res/celsim.txt"
cat "$res/celsim.txt"

# Instructions per frame: repeatable where wall-clock time is not.
{
    echo "### Instructions per frame (callgrind, one 1920x1080 frame of celscan, cs_frame_begin to the last converted line)"
    echo
    echo "| scene | --aa | instructions | top functions (share of the frame) |"
    echo "|---|---|---:|---|"
    for run in "blobs 16" "blobs exact" "blobs exact baseline" "blobs none" "signage 16" "thin 16"; do
        set -- $run
        # a third word: the core's build, where it is not $core
        CELSCAN_CORE=${3:-$core} valgrind --tool=callgrind \
            --callgrind-out-file="$tmp/callgrind-$1-$2${3:+-$3}.out" \
            --toggle-collect=celscan_frame "$bench" --profile "$1" --aa "$2" --frames 1 \
            >/dev/null 2>&1
        callgrind_annotate "$tmp/callgrind-$1-$2${3:+-$3}.out" 2>/dev/null |
            awk -v scene="$1" -v aa="$2${3:+ ($3 build)}" '
            /PROGRAM TOTALS/ { gsub(",", "", $1); total = $1 }
            /file:function/ { list = 1; next }
            list && n < 6 && /^ *[0-9,]+ +\( *[0-9.]+%\)/ {
                s = $0
                sub(/^ *[0-9,]+ +\( */, "", s)
                pct = s; sub(/%\).*/, "", pct)
                f = s; sub(/^[^)]*\) +/, "", f); sub(/ .*/, "", f); sub(/.*\//, "", f)
                sub(/:v3_/, ":", f) # the x86-64-v3 build renamed (mk/variant.mk)
                top = top (n ? ", " : "") f " " pct "%"
                n++
            }
            END { printf "| %s | %s | %.1f M | %s |\n", scene, aa, total / 1e6, top }'
    done
    echo
    echo "The function list charges inlined code to its caller (most of a line is inlined into"
    echo "cs__line_stack). By the source function each instruction was written in"
    echo "(tools/cg_functions.py), one frame of Many-blobs at --aa 16:"
    echo
    python3 tools/cg_functions.py "$tmp/callgrind-blobs-16.out" 16

    # The same count for the peers (bench --profile SCENE --peer NAME runs the
    # call the speed section times): a ratio no load on the machine can move.
    echo
    echo "### Instructions per frame against the peers (callgrind, one 1920x1080 frame each)"
    echo
    echo "| scene | celscan exact | cairo | FreeType | AGG | exact/cairo | exact/FT | exact/AGG |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|"
    count() { # callgrind's total in function $1 for one frame of bench --profile $2 $3 $4
        valgrind --tool=callgrind --callgrind-out-file="$tmp/cg-peer.out" \
            --toggle-collect="$1" "$bench" --profile "$2" "$3" "$4" --frames 1 2>&1 |
            sed -n 's/.*Collected : *//p'
    }
    for scene in blobs signage thin rational; do
        x=$(count celscan_frame "$scene" --aa exact)
        c=$(count peer_frame "$scene" --peer cairo)
        f=$(count peer_frame "$scene" --peer freetype)
        a=$(count peer_frame "$scene" --peer agg)
        awk -v s="$scene" -v x="$x" -v c="$c" -v f="$f" -v a="$a" 'BEGIN {
            printf "| %s | %.1f M | %.1f M | %.1f M | %.1f M | %.2f | %.2f | %.2f |\n", s, x / 1e6,
                c / 1e6, f / 1e6, a / 1e6, x / c, x / f, x / a }'
    done
    echo
    echo "Instructions are not time (the speed table has the time): pixman's SIMD composites"
    echo "several pixels an instruction, and cairo draws each shape into a whole frame in memory,"
    echo "where celscan keeps one line. The ratio is the one figure here that load cannot move."
} >"$res/callgrind.txt"
cat "$res/callgrind.txt"

end=$(date +%s)
echo "- \`make bench\` took $((end - start)) s" >>"$res/machine.txt"
