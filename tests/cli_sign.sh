#!/bin/sh
# cli_sign.sh HOSTDIR OUTDIR - signing streams through the programs, as an operator types it.
#
#   - celc keygen -o NAME writes NAME.key (mode 0600) and NAME.pub (0644), whatever the
#     umask, and refuses to overwrite either;
#   - celc compile --sign and celc sign turn a stream into one of signed envelopes: a
#     stream header and, per transaction, 100 bytes more (16 header + 80 signature
#     block + 4 trailer, counted here from the format, not from the signer);
#   - celsim renders a signed stream to the same frame CRC as its unsigned original at
#     several times (the core unwraps envelopes), with nothing on stderr;
#   - two runs of celc sign give growing sequence numbers (microseconds of the clock);
#   - a private key others can read, a damaged stream and a signed stream are refused
#     with exit 1 and no output file; bad command lines exit 2.
# Last line: `cli_sign: N passed, M failed`.
set -u
TL_NAME=cli_sign
. "$(dirname "$0")/testlib.sh"
host=$1 out=$2
celc=$host/celc celsim=$host/celsim
rm -rf "$out" && mkdir -p "$out"
size() { wc -c <"$1" | tr -d ' '; }
mode() { stat -c %a "$1"; }
crc() { "$celsim" render "$@" --crc 2>>"$out/celsim.err" | sed -n 's/^frame crc32 //p'; }
# the sequence of the first envelope: u64 little-endian at byte 16 + 16 + 8
seq_of() { od -An -tu8 -j40 -N8 "$1" | tr -d ' '; }

(umask 0; "$celc" keygen -o "$out/op" 2>"$out/keygen.err")
if [ -f "$out/op.key" ] && [ -f "$out/op.pub" ]; then ok; else bad "keygen: $(cat "$out/keygen.err")"; fi
check "NAME.key mode 600 under umask 0 ($(mode "$out/op.key"))" [ "$(mode "$out/op.key")" = 600 ]
check "NAME.pub mode 644 ($(mode "$out/op.pub"))" [ "$(mode "$out/op.pub")" = 644 ]
cp "$out/op.key" "$out/op.key.orig"
"$celc" keygen -o "$out/op" 2>"$out/keygen2.err"
check "keygen refuses to overwrite (exit $?)" grep -q "exists already" "$out/keygen2.err"
check "the key is unchanged" cmp -s "$out/op.key" "$out/op.key.orig"

"$celc" compile scenes/motion.json -o "$out/plain.cels" || bad "compile motion.json"
"$celc" compile scenes/motion.json -o "$out/signed.cels" --sign "$out/op.key" 2>"$out/sign.err"
check "compile --sign: $(cat "$out/sign.err")" [ -s "$out/signed.cels" ]
want=$(($(size "$out/plain.cels") + 100))
check "one envelope: $(size "$out/signed.cels") bytes, want $want" [ "$(size "$out/signed.cels")" = "$want" ]
check "the envelope's magic is CSSG" [ "$(od -An -c -j16 -N4 "$out/signed.cels" | tr -d ' ')" = CSSG ]
for t in 0 0.5 1.25 3; do
    a=$(crc "$out/plain.cels" --time $t) b=$(crc "$out/signed.cels" --time $t)
    if [ -n "$a" ] && [ "$a" = "$b" ]; then ok; else bad "t=$t: unsigned crc '$a', signed crc '$b'"; fi
done
check "celsim reads signed streams without a complaint: $(cat "$out/celsim.err")" [ ! -s "$out/celsim.err" ]

# A stream of several transactions: each gets its envelope, sequences grow across runs.
cat "$out/plain.cels" "$out/plain.cels" >"$out/two.cels"
"$celc" sign "$out/two.cels" -o "$out/two-signed.cels" --key "$out/op.key" || bad "celc sign"
want=$(($(size "$out/two.cels") + 200))
check "two envelopes: $(size "$out/two-signed.cels") bytes, want $want" \
    [ "$(size "$out/two-signed.cels")" = "$want" ]
s1=$(seq_of "$out/signed.cels") s2=$(seq_of "$out/two-signed.cels")
check "the later signing has the higher sequence ($s1 then $s2)" [ "$s2" -gt "$s1" ]
now=$(($(date +%s) * 1000000))
if [ "$s2" -gt $((now - 600000000)) ] && [ "$s2" -le $((now + 600000000)) ]; then ok; else
    bad "the sequence is the clock in microseconds ($s2, now $now)"
fi

# Refusals: exit 1, a message, no output.
refused() { # refused DESCRIPTION RC STDERR-FILE NEEDLE
    if [ "$2" -eq 1 ] && grep -q "$4" "$3" && [ ! -e "$out/x.cels" ]; then ok; else
        bad "$1 (exit $2): $(cat "$3")"
    fi
}
chmod 644 "$out/op.key"
"$celc" sign "$out/plain.cels" -o "$out/x.cels" --key "$out/op.key" 2>"$out/e1"
rc=$?
refused "a readable private key is refused" $rc "$out/e1" "lets others read the private key"
chmod 600 "$out/op.key"
"$celc" sign "$out/signed.cels" -o "$out/x.cels" --key "$out/op.key" 2>"$out/e2"
rc=$?
refused "a signed stream is not signed again" $rc "$out/e2" "byte 16: already signed"
cp "$out/plain.cels" "$out/damaged.cels"
printf 'X' | dd of="$out/damaged.cels" bs=1 seek=40 conv=notrunc 2>/dev/null
"$celc" sign "$out/damaged.cels" -o "$out/x.cels" --key "$out/op.key" 2>"$out/e3"
rc=$?
refused "a damaged stream is not signed" $rc "$out/e3" "CRC mismatch"
"$celc" sign "$out/plain.cels" -o "$out/x.cels" 2>/dev/null
check "sign without --key is a usage error" [ $? -eq 2 ]
"$celc" keygen 2>/dev/null
check "keygen without -o is a usage error" [ $? -eq 2 ]
"$celc" compile scenes/motion.json -o "$out/x.cels" --sign 2>/dev/null
check "--sign without a key is a usage error" [ $? -eq 2 ]

tl_summary
