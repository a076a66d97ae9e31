#!/bin/sh
# cli_stream.sh HOSTDIR OUTDIR - the command-line contract of celc and celsim for streams.
#
# Through the programs, as a user or a CI job runs them:
#   - celc compile turns every scenes/*.json into a .cels, and celsim renders the
#     JSON and the stream to the same `frame crc32` at several --time values and
#     two sizes (and the animated ones to different CRCs over time);
#   - a valid stream followed by a damaged transaction renders the valid scene,
#     exits 0, and says on stderr what was wrong at which byte offset;
#   - a stream with nothing valid (damaged, cut short, garbage) exits 1 and says so;
#   - celc refuses bad scenes with the JSON path and exit 1, leaves no output file
#     behind, refuses bad command lines with exit 2 (celc text and import: numbers
#     out of range or not numbers; svgimport render likewise), and `celc import` answers;
#   - celsim --threads N renders the frame --threads 1 does, and refuses --threads 0;
# Byte offsets are computed here from the file sizes, independently of the decoder.
# Last line: `cli_stream: N passed, M failed`.
set -u
TL_NAME=cli_stream
. "$(dirname "$0")/testlib.sh"
host=$1 out=$2
celc=$host/celc celsim=$host/celsim
rm -rf "$out" && mkdir -p "$out"

size() { wc -c <"$1" | tr -d ' '; }
crc() { "$celsim" render "$@" --crc 2>"$out/crc.err" | sed -n 's/^frame crc32 //p'; }

# ------------------------------------------------- every scene: JSON == stream
for json in scenes/*.json; do
    name=$(basename "$json" .json)
    cels=$out/$name.cels
    if ! "$celc" compile "$json" -o "$cels" 2>"$out/celc.err"; then
        bad "celc compile $json: $(cat "$out/celc.err")"
        continue
    fi
    ok
    distinct=""
    for t in 0 0.3 1 1.75 2.5 9; do
        for sz in "" "--size 200x120"; do
            # shellcheck disable=SC2086
            a=$(crc "$json" --time $t $sz) b=$(crc "$cels" --time $t $sz)
            if [ -n "$a" ] && [ "$a" = "$b" ]; then ok; else
                bad "$name at t=$t $sz: JSON crc '$a', stream crc '$b'"
            fi
        done
        case " $distinct " in *" $a "*) ;; *) distinct="$distinct $a" ;; esac
    done
    if grep -q '"animate"' "$json"; then
        n=$(echo $distinct | wc -w)
        check "$name is animated: --time changes the frame ($n distinct of 6)" [ "$n" -ge 3 ]
    fi
done

# --------------------------------------------- valid stream, damaged transaction
demo=$out/demo.cels motion=$out/motion.cels
if [ -f "$demo" ] && [ -f "$motion" ]; then
    good=$(size "$demo")
    # The motion scene's transaction (without its stream header), one body byte flipped.
    python3 - "$demo" "$motion" "$out/damaged.cels" <<'EOF'
import sys
demo = open(sys.argv[1], "rb").read()
txn = bytearray(open(sys.argv[2], "rb").read()[16:])
txn[100] ^= 0x20
open(sys.argv[3], "wb").write(demo + bytes(txn))
EOF
    total=$(size "$out/damaged.cels")
    want=$(crc scenes/demo.json --time 1)
    got=$(crc "$out/damaged.cels" --time 1)
    "$celsim" render "$out/damaged.cels" --time 1 --crc >/dev/null 2>"$out/damaged.err"
    rc=$?
    check "valid + damaged: exit status 0 (got $rc)" [ "$rc" -eq 0 ]
    check "valid + damaged: renders the valid scene ($got, want $want)" [ "$got" = "$want" ]
    # The fault is the trailer CRC, 4 bytes from the end; the dropped transaction starts where the demo ends.
    check "valid + damaged: stderr names the CRC fault at byte $((total - 4)) of a transaction at byte $good: $(cat "$out/damaged.err")" \
        grep -q "^celsim: $out/damaged.cels: byte $((total - 4)): transaction CRC mismatch: data damaged.*(transaction at byte $good dropped)$" "$out/damaged.err"
    check "valid + damaged: stderr says which commit renders" \
        grep -q "rendering commit 1, the last good one (1 error above)" "$out/damaged.err"
    # The same damage with nothing valid before it: exit 1.
    python3 - "$motion" "$out/only-damaged.cels" <<'EOF'
import sys
d = bytearray(open(sys.argv[1], "rb").read())
d[16 + 100] ^= 0x20
open(sys.argv[2], "wb").write(bytes(d))
EOF
    "$celsim" render "$out/only-damaged.cels" --crc >"$out/only.out" 2>"$out/only.err"
    rc=$?
    check "only damaged: exit status 1 (got $rc)" [ "$rc" -eq 1 ]
    check "only damaged: no frame crc printed" [ ! -s "$out/only.out" ]
    check "only damaged: the CRC fault at byte $(($(size "$motion") - 4)) and 'no valid scene': $(cat "$out/only.err")" \
        sh -c "grep -q 'byte $(($(size "$motion") - 4)): transaction CRC mismatch' '$out/only.err' &&
               grep -q 'no valid scene was committed (1 error)' '$out/only.err'"
    # Cut short: the transaction header at byte 16 promises more than there is.
    head -c $((good / 2)) "$demo" >"$out/cut.cels"
    "$celsim" render "$out/cut.cels" --crc >/dev/null 2>"$out/cut.err"
    rc=$?
    check "cut short: exit 1 (got $rc), error at the end of input, byte $((good / 2)): $(cat "$out/cut.err")" \
        sh -c "[ $rc -eq 1 ] && grep -q 'byte $((good / 2)): transaction cut short: input ended inside a transaction (transaction at byte 16 dropped)' '$out/cut.err'"
    # Garbage after a valid stream: reported from its first byte, the scene still renders.
    { cat "$demo"; printf 'this is not a transaction, just noise 0123456789'; } >"$out/noise.cels"
    got=$("$celsim" render "$out/noise.cels" --time 1 --crc 2>"$out/noise.err" | sed -n 's/^frame crc32 //p')
    check "valid + noise: renders the valid scene, names the noise at byte $good: $(cat "$out/noise.err")" \
        sh -c "[ '$got' = '$want' ] && grep -q 'byte $good: bytes outside any transaction were skipped' '$out/noise.err'"
    # A patch after the scene: a later good transaction is what renders.
    cat "$demo" >"$out/two.cels"
    tail -c +17 "$motion" >>"$out/two.cels"
    got=$(crc "$out/two.cels" --time 0.5) want2=$(crc scenes/motion.json --time 0.5)
    check "two good transactions: the last commit renders ($got, want $want2)" [ "$got" = "$want2" ]
    # An empty file commits nothing.
    : >"$out/empty.cels"
    "$celsim" render "$out/empty.cels" --crc >/dev/null 2>"$out/empty.err"
    rc=$?
    check "empty stream: exit 1 (got $rc)" sh -c "[ $rc -eq 1 ] && grep -q 'no valid scene was committed' '$out/empty.err'"
else
    bad "demo or motion stream missing: cannot test damage"
fi

# ------------------------------------------------------------------ celc errors
cat >"$out/bad-weight.json" <<'EOF'
{"canvas": {"width": 10, "height": 10}, "cels": [{"regions": [{"paint": {},
 "contours": [{"degree": 1, "points": [[0,0],[5,0],[5,5,0],[0,5]]}]}]}]}
EOF
"$celc" compile "$out/bad-weight.json" -o "$out/bad.cels" 2>"$out/bad.err"
rc=$?
check "celc: bad weight refused with exit 1 (got $rc) and the JSON path: $(cat "$out/bad.err")" \
    sh -c "[ $rc -eq 1 ] && grep -q '^celc: $out/bad-weight.json: cels\[0\].regions\[0\].contours\[0\].points\[2\]: weight must be > 0' '$out/bad.err'"
check "celc: no output file after a refusal" sh -c "! ls '$out'/bad.cels* >/dev/null 2>&1"
cat >"$out/bad-anim.json" <<'EOF'
{"canvas": {"width": 10, "height": 10}, "cels": [{"animate": {"transform": {"keys": [[0, [1,0,0,1,0,0]],
 [0, [1,0,0,1,5,0]]]}}, "regions": []}]}
EOF
"$celc" compile "$out/bad-anim.json" -o "$out/bad.cels" 2>"$out/bad.err"
rc=$?
check "celc: key times refused with the JSON path: $(cat "$out/bad.err")" \
    sh -c "[ $rc -eq 1 ] && grep -q 'cels\[0\].animate.transform.keys\[1\]\[0\]: key times must increase strictly (0 after 0)' '$out/bad.err'"
printf '{"canvas": {"width": 10, "height": 10}, "cels": [' >"$out/syntax.json"
"$celc" compile "$out/syntax.json" -o "$out/bad.cels" 2>"$out/bad.err"
rc=$?
check "celc: JSON syntax error with line and column: $(cat "$out/bad.err")" \
    sh -c "[ $rc -eq 1 ] && grep -q 'syntax.json:1:[0-9]*: JSON syntax error' '$out/bad.err'"
"$celc" compile scenes/demo.json 2>"$out/bad.err"
rc=$?
check "celc: missing -o is a usage error (exit $rc)" sh -c "[ $rc -eq 2 ] && grep -q 'needs -o' '$out/bad.err'"
"$celc" compile "$out/nope.json" -o "$out/bad.cels" 2>"$out/bad.err"
rc=$?
check "celc: missing input (exit $rc): $(cat "$out/bad.err")" sh -c "[ $rc -eq 1 ] && grep -q 'cannot open' '$out/bad.err'"
"$celc" frobnicate 2>"$out/bad.err"
rc=$?
check "celc: unknown command (exit $rc)" [ "$rc" -eq 2 ]
if [ ! -f tools/celc_import.c ]; then
    "$celc" import drawing.svg -o x.cels 2>"$out/bad.err"
    rc=$?
    check "celc import: not built in (exit $rc): $(cat "$out/bad.err")" \
        sh -c "[ $rc -ne 0 ] && grep -qx 'celc import: not built in' '$out/bad.err'"
fi
# celc text and import: numbers that no scene can hold are refused on the
# command line (exit 2, the option named), not written to the scene file.
refuses() { # refuses COMMAND OPTION VALUE ARGS...: `celc COMMAND ARGS OPTION VALUE` exits 2
    c=$1 o=$2 v=$3
    shift 3
    "$celc" "$c" "$@" "$o" "$v" 2>"$out/bad.err"
    rc=$?
    check "celc $c $o $v refused (exit $rc): $(cat "$out/bad.err")" \
        sh -c "[ $rc -eq 2 ] && grep -q \"^celc $c: $o '$v': expected\" '$out/bad.err'"
}
if [ -f tools/celc_import.c ]; then
    for arg in "--size nan" "--size 1e400" "--size -5" "--position nan,0" "--position 3" \
        "--canvas -5x10" "--canvas 200x40x"; do
        # shellcheck disable=SC2086
        refuses text $arg Hi -o "$out/text.json"
    done
    "$celc" text Hi -o "$out/text.json" --size 24 --position 3,-4 --canvas 200x40 2>"$out/bad.err"
    rc=$?
    check "celc text with valid numbers (exit $rc): $(cat "$out/bad.err")" [ "$rc" -eq 0 ]
    # --font takes a family too: fontconfig's face for the text (a CJK one for CJK text)
    "$celc" text "站台" --font "Noto Sans" -o "$out/text.json" 2>"$out/bad.err"
    rc=$?
    check "celc text --font FAMILY picks a face with the glyphs (exit $rc): $(cat "$out/bad.err")" \
        sh -c "[ $rc -eq 0 ] && grep -q 'glyphs from .*CJK' '$out/bad.err'"
    refuses import --tolerance nan scenes/svg/sign.svg -o "$out/import.json" -q
    refuses import --nominal -5 scenes/svg/sign.svg -o "$out/import.json" -q
    # svgimport render (the importer's debugging tool) reads its numbers as strictly
    for arg in "--size 64x" "--size abcx4" "--size 64x48x" "--aa 0" "--aa abc" \
        "--aa 99999999999999999"; do
        # shellcheck disable=SC2086
        "$host/svgimport" render scenes/svg/sign.svg -o "$out/svg.png" -q $arg 2>/dev/null
        rc=$?
        check "svgimport render $arg refused (exit $rc)" [ "$rc" -eq 2 ]
    done
    "$host/svgimport" render scenes/svg/sign.svg -o "$out/svg.png" -q --size 64x48 --aa 5
    rc=$?
    check "svgimport render with valid numbers (exit $rc)" [ "$rc" -eq 0 ]
fi
# Standard output, and the file is exactly that.
"$celc" compile scenes/demo.json -o - >"$out/stdout.cels" 2>/dev/null
check "celc -o - writes the same stream to standard output" cmp -s "$out/stdout.cels" "$demo"

# ------------------------------------------------------ celsim --threads
# The stream through 1, 2 and 5 threads: one thread's bytes (test_bands checks the floats).
a=$(crc "$demo" --size 320x180 --aa exact --threads 1)
for n in 2 5; do
    b=$(crc "$demo" --size 320x180 --aa exact --threads $n)
    check "celsim --threads $n gives --threads 1's frame ('$b', '$a')" [ -n "$a" -a "$a" = "$b" ]
done
"$celsim" render "$demo" --crc --threads 0 >/dev/null 2>"$out/bad.err"
rc=$?
check "celsim --threads 0 is a usage error (exit $rc)" sh -c "[ $rc -eq 2 ] && grep -q 'threads expects a count 1..64' '$out/bad.err'"

tl_summary
