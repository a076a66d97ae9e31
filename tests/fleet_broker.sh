#!/bin/sh
# fleet_broker.sh - the fleet against a real broker: Debian's mosquitto with
# passwords, an ACL and a TLS listener, three celfw signs, celc publish.
#
#   sh tests/fleet_broker.sh BUILD_HOST_DIR WORK_DIR
#
# Nothing is mocked. The test writes the broker's configuration, makes a CA
# and a server certificate with openssl and the password file with
# mosquitto_passwd, starts mosquitto on free loopback ports, and starts real
# celfw processes (null display) and mosquitto clients. Every process it
# starts is stopped by its pid on exit, failure or not.
#
# It shows:
#   - three signs in one group (s1, s2 over mqtt://, s3 over mqtts:// checking
#     the broker's certificate) all apply a publish to the group, and each one's
#     retained status names the BLAKE2b-128 digest of what it applied (computed
#     here with Python's hashlib, not by celfw);
#   - a sign stopped while the group's content changed shows the new content
#     within 2 s of starting (the retained message);
#   - the broker killed (SIGKILL) and restarted: the signs keep their picture
#     (no commit, no stream error), reconnect and report online again;
#   - the ACL: a client without a password, with a wrong one, and a sign's
#     own password publishing content are refused (and no sign changes);
#   - a 40 MB message, beyond what a sign takes, never reaches it;
#   - a broker certificate from another CA is refused by celc publish over TLS;
#   - mutual TLS: a sign's client certificate and key (config file) open a
#     listener that requires one, and without them it stays out; a sign with
#     a wrong password is refused, and says so once, not at every retry;
#   - credentials stay off the command line, and a password file others can
#     read is refused.
#   - three signs that trust the operator's key: an unsigned, a forged (other
#     key), an altered and a replayed publish change none; a publish signed by
#     `celc publish --sign` is applied by all three, and the status names its
#     sequence.
# Last line: "fleet_broker: N passed, M failed".
set -u
TL_NAME=fleet_broker
. "$(dirname "$0")/testlib.sh"
HOST=$1
WORK=$2
CELFW=$HOST/celfw
CELC=$HOST/celc
pids=""
cleanup() {
    for p in $pids; do kill "$p" 2>/dev/null; done
    for p in $pids; do wait "$p" 2>/dev/null; done
}
trap cleanup EXIT
trap 'exit 1' INT TERM

rm -rf "$WORK"
mkdir -p "$WORK"
W=$(cd "$WORK" && pwd)

free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
now() { date +%s.%N; }
digest_of() { python3 -c 'import hashlib, sys; print(hashlib.blake2b(open(sys.argv[1], "rb").read(), digest_size=16).hexdigest())' "$1"; }

# ---------------------------------------------------------------- certificates
# A CA, the broker's certificate for localhost and 127.0.0.1, and a rogue CA.
(
    cd "$W" &&
        openssl req -x509 -newkey rsa:2048 -nodes -keyout ca.key -out ca.crt -days 2 \
            -subj /CN=celscan-test-ca 2>/dev/null &&
        openssl req -newkey rsa:2048 -nodes -keyout server.key -out server.csr \
            -subj /CN=localhost 2>/dev/null &&
        printf 'subjectAltName=DNS:localhost,IP:127.0.0.1\n' >san.ext &&
        openssl x509 -req -in server.csr -CA ca.crt -CAkey ca.key -CAcreateserial \
            -out server.crt -days 2 -extfile san.ext 2>/dev/null &&
        openssl req -newkey rsa:2048 -nodes -keyout client.key -out client.csr \
            -subj /CN=s1 2>/dev/null &&
        openssl x509 -req -in client.csr -CA ca.crt -CAkey ca.key -CAcreateserial \
            -out client.crt -days 2 2>/dev/null &&
        chmod 600 client.key &&
        openssl req -x509 -newkey rsa:2048 -nodes -keyout rogue.key -out rogue.crt -days 2 \
            -subj /CN=rogue-ca 2>/dev/null
) || { bad "openssl could not make the certificates"; tl_summary; exit 1; }

# ---------------------------------------------------------------- users and ACL
: >"$W/passwd"
for u in ops s1 s2 s3 s4 s5 s6; do
    mosquitto_passwd -b "$W/passwd" "$u" "pw-$u-secret" 2>/dev/null
done
chmod 600 "$W/passwd"
cat >"$W/acl" <<EOF
# the operator publishes content and reads the fleet's status
user ops
topic readwrite groups/#
topic readwrite signs/#
# every sign reads its own topic and the groups, and writes only its status
pattern read signs/%u
pattern read groups/#
pattern write signs/%u/status
EOF

PORT=0
TPORT=0
MPORT=0
start_broker() {
    cat >"$W/mosquitto.conf" <<EOF
per_listener_settings false
allow_anonymous false
password_file $W/passwd
acl_file $W/acl
user $(id -un)
persistence false
log_dest file $W/broker.log
listener $PORT 127.0.0.1
listener $TPORT 127.0.0.1
cafile $W/ca.crt
certfile $W/server.crt
keyfile $W/server.key
listener $MPORT 127.0.0.1
cafile $W/ca.crt
certfile $W/server.crt
keyfile $W/server.key
require_certificate true
EOF
    /usr/sbin/mosquitto -c "$W/mosquitto.conf" 2>>"$W/broker.err" &
    BROKER=$!
    pids="$pids $BROKER"
    # Up when the plain port answers (an anonymous client is refused, which proves it).
    i=0
    while [ $i -lt 50 ]; do
        if ! kill -0 "$BROKER" 2>/dev/null; then return 1; fi
        if mosquitto_pub -h 127.0.0.1 -p "$PORT" -t probe -m x -q 0 2>&1 | grep -q -i 'refused\|not auth'; then
            return 0
        fi
        sleep 0.1
        i=$((i + 1))
    done
    return 1
}
# Free ports chosen by the kernel; another process may take one first: retry.
tries=0
while :; do
    PORT=$(free_port)
    TPORT=$(free_port)
    MPORT=$(free_port)
    [ "$PORT" != "$TPORT" ] && [ "$PORT" != "$MPORT" ] && [ "$TPORT" != "$MPORT" ] && start_broker && break
    tries=$((tries + 1))
    [ $tries -lt 5 ] || { bad "mosquitto would not start: $(cat "$W/broker.err" "$W/broker.log" 2>/dev/null | tail -3)"; tl_summary; exit 1; }
done

# ---------------------------------------------------------------- content
"$CELC" compile scenes/demo.json -o "$W/demo.cels" >/dev/null || bad "celc compile demo"
"$CELC" compile scenes/motion.json -o "$W/motion.cels" >/dev/null || bad "celc compile motion"
# The demo with another background: another content of the very same length.
python3 -c 'import json, sys; d = json.load(open("scenes/demo.json")); d["canvas"]["background"] = "#203040"; json.dump(d, open(sys.argv[1], "w"))' "$W/demo-b.json"
"$CELC" compile "$W/demo-b.json" -o "$W/demo-b.cels" >/dev/null || bad "celc compile demo-b"
D_DEMO=$(digest_of "$W/demo.cels")
D_MOTION=$(digest_of "$W/motion.cels")
printf 'username = ops\npassword = pw-ops-secret\nca = %s/ca.crt\n' "$W" >"$W/ops.cred"
printf 'username = s1\npassword = pw-s1-secret\n' >"$W/s1.cred"
printf 'username = ops\npassword = wrong\n' >"$W/bad.cred"
printf 'username = ops\npassword = pw-ops-secret\nca = %s/rogue.crt\n' "$W" >"$W/rogue.cred"
chmod 600 "$W"/*.cred

# ---------------------------------------------------------------- signs
sign_conf() { # id
    printf 'pw-%s-secret\n' "$1" >"$W/$1.pw"
    chmod 600 "$W/$1.pw"
    cat >"$W/$1.conf" <<EOF
sign-id = $1
mqtt-username = $1
mqtt-password-file = $W/$1.pw
mqtt-ca = $W/ca.crt
EOF
}
start_sign() { # id url
    "$CELFW" --config "$W/$1.conf" --backend null --size 32x16 --fps 20 --log-interval 1 \
        --duration 90 --input "$2" --mqtt-topic groups/lobby 2>>"$W/$1.log" &
    eval "PID_$1=$!"
    pids="$pids $!"
}
url_of() { # id
    if [ "$1" = s3 ]; then echo "mqtts://localhost:$TPORT"; else echo "mqtt://127.0.0.1:$PORT"; fi
}
# wait_log FILE PATTERN SECONDS: the pattern appears in time
wait_log() {
    end=$(python3 -c "import time; print(time.time() + $3)")
    while :; do
        grep -q -- "$2" "$1" 2>/dev/null && return 0
        python3 -c "import sys, time; sys.exit(0 if time.time() < $end else 1)" || return 1
        sleep 0.05
    done
}
count_log() { grep -c -- "$2" "$1" 2>/dev/null; }
# status ID: the sign's retained status, as the operator sees it (none within 1 s: empty)
status_of() {
    mosquitto_sub -h 127.0.0.1 -p "$PORT" -u ops -P pw-ops-secret -t "signs/$1/status" -C 1 -W 1 \
        2>/dev/null
}
wait_status() { # id pattern seconds
    end=$(python3 -c "import time; print(time.time() + $3)")
    while :; do
        status_of "$1" | grep -q -- "$2" && return 0
        python3 -c "import sys, time; sys.exit(0 if time.time() < $end else 1)" || return 1
        sleep 0.2
    done
}

for s in s1 s2 s3; do
    sign_conf $s
    start_sign $s "$(url_of $s)"
done
for s in s1 s2 s3; do
    check "$s connects to the broker" wait_log "$W/$s.log" "mqtt connected to" 8
done

# 1. One publish to the group reaches all three.
"$CELC" publish "$W/demo.cels" --broker "mqtt://127.0.0.1:$PORT" --topic groups/lobby --retain \
    --credentials "$W/ops.cred" >"$W/pub1.out" 2>&1 || bad "celc publish demo: $(cat "$W/pub1.out")"
for s in s1 s2 s3; do
    check "$s applies the group's publish" wait_log "$W/$s.log" "stream commit 1 applied" 5
    check "$s reports content $D_DEMO (the demo stream)" wait_status $s "\"content\":\"$D_DEMO\"" 5
done
check "s3's status says online" wait_status s3 '"online":true' 3
"$CELC" publish "$W/demo-b.cels" --broker "mqtt://127.0.0.1:$PORT" --topic groups/lobby --retain \
    --credentials "$W/ops.cred" >/dev/null 2>&1 || bad "celc publish demo-b"
for s in s1 s2 s3; do
    check "$s applies new content of the same length (not taken for a re-delivery)" \
        wait_log "$W/$s.log" "stream commit 2 applied" 5
done

# 2. s2 stopped while the content changes; back, it shows it within 2 s.
kill "$PID_s2"
wait "$PID_s2" 2>/dev/null
check "s2's clean exit marks it offline" wait_status s2 '"online":false' 3
"$CELC" publish "$W/motion.cels" --broker "mqtts://localhost:$TPORT" --topic groups/lobby --retain \
    --credentials "$W/ops.cred" >"$W/pub2.out" 2>&1 || bad "celc publish motion over TLS: $(cat "$W/pub2.out")"
: >"$W/s2.log"
t0=$(now)
start_sign s2 "$(url_of s2)"
if wait_log "$W/s2.log" "stream commit 1 applied" 2; then
    t1=$(now)
    ok
    echo "fleet_broker: s2 showed the current content $(python3 -c "print('%.2f' % ($t1 - $t0))") s after starting"
else
    bad "s2 did not apply the retained content within 2 s of starting: $(tail -3 "$W/s2.log")"
fi
check "s2 applied the motion stream ($D_MOTION)" grep -q "content $D_MOTION" "$W/s2.log"
for s in s1 s3; do
    check "$s applies the new group content too" wait_log "$W/$s.log" "stream commit 3 applied" 5
done

# 3. The broker killed and restarted.
before1=$(count_log "$W/s1.log" "stream commit")
errs1=$(count_log "$W/s1.log" "stream error")
kill -9 "$BROKER"
wait "$BROKER" 2>/dev/null
for s in s1 s2 s3; do
    check "$s notices the broker is gone" wait_log "$W/$s.log" "lost" 25
done
sleep 0.5
start_broker || bad "mosquitto would not restart"
for s in s1 s2 s3; do
    check "$s reconnects and reports online" wait_status $s '"online":true' 15
done
check "s1 kept its picture (no commit, no stream error)" \
    test "$(count_log "$W/s1.log" "stream commit")" = "$before1" -a \
    "$(count_log "$W/s1.log" "stream error")" = "$errs1"

# 4. The ACL and the passwords.
out=$(mosquitto_pub -h 127.0.0.1 -p "$PORT" -t groups/lobby -f "$W/demo.cels" -q 1 2>&1)
check "a client without a password is refused ($out)" test $? -ne 0
out=$("$CELC" publish "$W/demo.cels" --broker "mqtt://127.0.0.1:$PORT" --topic groups/lobby \
    --credentials "$W/bad.cred" 2>&1)
rc=$?
check "a wrong password is refused (rc $rc: $out)" sh -c "[ $rc -eq 1 ] && echo '$out' | grep -q 'refused the connection'"
before=$(count_log "$W/s3.log" "stream commit")
out=$("$CELC" publish "$W/demo.cels" --broker "mqtt://127.0.0.1:$PORT" --topic groups/lobby \
    --retain --credentials "$W/s1.cred" 2>&1)
rc=$?
check "a sign's password publishing content is refused by the ACL (rc $rc: $out)" \
    sh -c "[ $rc -eq 1 ] && echo '$out' | grep -q -i 'not authori'"
sleep 0.5
check "no sign changed after the refused publish" test "$(count_log "$W/s3.log" "stream commit")" = "$before"

# A message bigger than a sign takes (32 MiB; the sign says so in its MQTT 5
# CONNECT) is dropped by the broker for it: no feed, no disconnect.
head -c 40000000 /dev/zero >"$W/big.bin"
lost=$(count_log "$W/s1.log" "lost")
fed=$(count_log "$W/s1.log" "mqtt message on")
mosquitto_pub -h 127.0.0.1 -p "$PORT" -u ops -P pw-ops-secret -t groups/lobby -q 1 \
    -f "$W/big.bin" >/dev/null 2>&1 || bad "publishing 40 MB"
rm -f "$W/big.bin"
sleep 1
check "a 40 MB message is kept from the signs, which stay connected" \
    test "$(count_log "$W/s1.log" "mqtt message on")" = "$fed" -a "$(count_log "$W/s1.log" "lost")" = "$lost" \
    -a "$(count_log "$W/s1.log" "bytes, more than")" = 0

# 5. TLS: a broker whose certificate another CA signed is not trusted.
out=$("$CELC" publish "$W/demo.cels" --broker "mqtts://localhost:$TPORT" --topic groups/lobby \
    --credentials "$W/rogue.cred" --timeout 3 2>&1)
rc=$?
check "celc publish refuses a broker certificate from another CA (rc $rc: $out)" test $rc -eq 1

# Mutual TLS: a listener that wants a client certificate takes s1 with its
# certificate and key (from the config file), and not without them.
cp "$W/s1.conf" "$W/s1m.conf"
printf 'mqtt-cert = %s/client.crt\nmqtt-key = %s/client.key\n' "$W" "$W" >>"$W/s1m.conf"
"$CELFW" --config "$W/s1m.conf" --backend null --size 8x8 --fps 10 --duration 20 \
    --input "mqtts://localhost:$MPORT" 2>"$W/s1m.log" &
m1=$!
pids="$pids $m1"
"$CELFW" --config "$W/s1.conf" --backend null --size 8x8 --fps 10 --duration 20 \
    --input "mqtts://localhost:$MPORT" 2>"$W/s1n.log" &
m2=$!
pids="$pids $m2"
# And a sign with a wrong password: refused by the broker, said once per outage.
printf 'wrong\n' >"$W/s1bad.pw"
chmod 600 "$W/s1bad.pw"
sed "s|$W/s1.pw|$W/s1bad.pw|" "$W/s1.conf" >"$W/s1bad.conf"
"$CELFW" --config "$W/s1bad.conf" --backend null --size 8x8 --fps 10 --duration 20 \
    --input "mqtt://127.0.0.1:$PORT" 2>"$W/s1bad.log" &
m3=$!
pids="$pids $m3"
check "a client certificate from the config file opens a listener that requires one" \
    wait_log "$W/s1m.log" "mqtt connected to" 8
check "no client certificate: the sign says it cannot connect" wait_log "$W/s1n.log" "retrying every" 5
check "no client certificate: not connected" sh -c "! grep -q 'mqtt connected to' '$W/s1n.log'"
sleep 3.2 # two retries at least (1 s, 2 s)
check "a sign's wrong password is refused by the broker, said once ($(count_log "$W/s1bad.log" refused) lines)" \
    test "$(count_log "$W/s1bad.log" "refused the connection")" = 1
kill $m1 $m2 $m3 2>/dev/null

# 6. Credentials only from the config file, and only from private files.
out=$("$CELFW" --backend null --size 8x8 --frames 1 --mqtt-password-file "$W/s1.pw" 2>&1)
rc=$?
check "celfw refuses a password file on the command line (rc $rc)" \
    sh -c "[ $rc -eq 2 ] && echo '$out' | grep -q 'only be set in the config file'"
chmod 644 "$W/s1.pw"
out=$("$CELFW" --config "$W/s1.conf" --backend null --size 8x8 --frames 1 \
    --input "mqtt://127.0.0.1:$PORT" 2>&1)
rc=$?
check "celfw refuses a password file others can read (rc $rc)" \
    sh -c "[ $rc -eq 3 ] && echo '$out' | grep -q 'chmod 600'"
chmod 600 "$W/s1.pw"

# Malformed fleet settings are refused before anything starts.
out=$("$CELFW" --backend null --size 8x8 --frames 1 --input "mqtt://127.0.0.1:$PORT" 2>&1)
rc=$?
check "an mqtt input without sign-id is refused (rc $rc)" sh -c "[ $rc -eq 2 ] && echo '$out' | grep -q 'needs sign-id'"
for spec in "mqtt://127.0.0.1" "mqtt://127.0.0.1:0/t" "mqtt://:$PORT" "mqtt://[::1/t"; do
    out=$("$CELFW" --backend null --size 8x8 --frames 1 --sign-id x --input "$spec" 2>&1)
    rc=$?
    check "input $spec is refused (rc $rc)" sh -c "[ $rc -eq 3 ] && echo '$out' | grep -q 'expected mqtt\[s\]://HOST:PORT'"
done
out=$("$CELFW" --backend null --size 8x8 --frames 1 --sign-id 'a/b' 2>&1)
check "a sign id with a '/' is refused" sh -c "echo '$out' | grep -q 'is not a sign id'"

# 7. Signed streams (issue 23): three signs that trust the operator's key
# apply only what that key signed, delivered by MQTT; unsigned, forged
# (another key, or a signature altered in transit) and replayed publishes
# change none of them, and their status names the applied sequence.
"$CELC" keygen -o "$W/operator" >/dev/null 2>&1 || bad "celc keygen operator"
"$CELC" keygen -o "$W/intruder" >/dev/null 2>&1 || bad "celc keygen intruder"
"$CELC" sign "$W/motion.cels" -o "$W/motion.forged.cels" --key "$W/intruder.key" >/dev/null 2>&1 ||
    bad "celc sign (intruder)"
"$CELC" sign "$W/demo.cels" -o "$W/demo.signed.cels" --key "$W/operator.key" >/dev/null 2>&1 ||
    bad "celc sign (operator)"
# The operator's envelope with one bit of its signature flipped (envelope bytes 32..95,
# after the 16-byte stream header) and the envelope's CRC made right again: a forgery, not damage.
python3 - "$W/demo.signed.cels" "$W/demo.tampered.cels" <<'PY'
import struct, sys, zlib
b = bytearray(open(sys.argv[1], "rb").read())
env = 16
b[env + 40] ^= 1
body = struct.unpack_from("<I", b, env + 8)[0]
struct.pack_into("<I", b, env + 16 + body, zlib.crc32(bytes(b[env:env + 16 + body])))
open(sys.argv[2], "wb").write(b)
PY
for s in s4 s5 s6; do
    mkdir -p "$W/state-$s"
    chmod 700 "$W/state-$s"
    sign_conf $s
    printf 'trust = %s/operator.pub\nstate-dir = %s/state-%s\n' "$W" "$W" "$s" >>"$W/$s.conf"
    "$CELFW" --config "$W/$s.conf" --backend null --size 32x16 --fps 20 --log-interval 1 \
        --duration 60 --input "mqtt://127.0.0.1:$PORT" --mqtt-topic groups/secure 2>>"$W/$s.log" &
    pids="$pids $!"
done
for s in s4 s5 s6; do
    check "$s (trusting the operator) connects" wait_log "$W/$s.log" "mqtt connected to" 8
done
secure_pub() { # file [extra args]: publish to the secure group, then give the signs time to act
    f=$1
    shift
    "$CELC" publish "$f" --broker "mqtt://127.0.0.1:$PORT" --topic groups/secure \
        --credentials "$W/ops.cred" "$@" >"$W/pub.out" 2>&1 || bad "publish $f: $(cat "$W/pub.out")"
}
for f in motion.cels motion.forged.cels demo.tampered.cels; do
    secure_pub "$W/$f"
done
for s in s4 s5 s6; do
    check "$s refuses the unsigned publish" wait_log "$W/$s.log" "refused.*: unsigned" 5
    check "$s refuses the intruder's publish" wait_log "$W/$s.log" "refused.*: unknown key" 5
    check "$s refuses the altered signature" wait_log "$W/$s.log" "refused.*: bad signature" 5
    check "$s changed nothing for them" test "$(count_log "$W/$s.log" "stream commit")" = 0
done
check "s4's status names the refusal" wait_status s4 '"last_error":"bad signature' 3
# celc publish --sign: a scene JSON compiled and signed on the way out.
secure_pub scenes/motion.json --sign "$W/operator.key"
for s in s4 s5 s6; do
    check "$s applies the operator's signed publish" wait_log "$W/$s.log" "stream commit 1 applied" 5
done
check "s5's status names the applied signature sequence" wait_status s5 '"seq":[1-9]' 3
# An older stream the operator signed is a rollback now: refused.
secure_pub "$W/demo.signed.cels"
for s in s4 s5 s6; do
    check "$s refuses the replayed older signed stream" wait_log "$W/$s.log" "refused.*: replayed sequence" 5
    check "$s still shows the signed publish" test "$(count_log "$W/$s.log" "stream commit")" = 1
done

tl_summary
