#!/usr/bin/env python3
"""fleet_bench.py - how fast one publish reaches a fleet of signs.

    python3 tools/fleet_bench.py BUILD_HOST_DIR [--signs 200] [--publishes 10]

Starts one mosquitto on a free loopback port (anonymous, loopback only: a
bench, not a deployment) and N real celfw processes (null display, 16x8,
5 frames/s) subscribed to their own topic and to groups/bench. It then
publishes the demo stream to the group with `celc publish`, N times
alternating between two variants (the demo and the demo with another
background: a sign does not feed a topic the same bytes twice), and times,
for each publish, the moment each sign logs "stream commit K applied"
after the moment celc publish was started. celfw's stderr is read here
line by line as it comes (one selector over all signs), so the time is
when the sign said it, to the scheduling of this machine.

Prints per publish the median and worst time over the signs, then the
median of the medians and the worst of all, and the broker's CPU time
(user + system, from /proc) spent over the publishes. Every process it
starts is stopped by its pid at the end.
"""
import argparse
import json
import os
import selectors
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    return (int(fields[11]) + int(fields[12])) / ticks  # utime, stime


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("host", help="build/host")
    ap.add_argument("--signs", type=int, default=200)
    ap.add_argument("--publishes", type=int, default=10)
    ap.add_argument("--timeout", type=float, default=30.0)
    a = ap.parse_args()
    celfw, celc = os.path.join(a.host, "celfw"), os.path.join(a.host, "celc")
    work = tempfile.mkdtemp(prefix="celscan-fleet-bench-")
    procs = []
    try:
        # Content: the demo, and the demo with another background.
        demo = json.load(open("scenes/demo.json"))
        other = dict(demo)
        other["canvas"] = dict(demo["canvas"], background="#203040")
        json.dump(other, open(os.path.join(work, "demo-b.json"), "w"))
        streams = []
        for name, src in (("a", "scenes/demo.json"), ("b", os.path.join(work, "demo-b.json"))):
            out = os.path.join(work, f"demo-{name}.cels")
            subprocess.run([celc, "compile", src, "-o", out], check=True)
            streams.append(out)

        port = free_port()
        conf = os.path.join(work, "mosquitto.conf")
        with open(conf, "w") as f:
            f.write(f"listener {port} 127.0.0.1\nallow_anonymous true\nmax_queued_messages 1000\n"
                    f"user {os.environ.get('USER') or 'root'}\n")
        broker = subprocess.Popen(["/usr/sbin/mosquitto", "-c", conf], stderr=subprocess.DEVNULL)
        procs.append(broker)
        time.sleep(0.3)

        sel = selectors.DefaultSelector()
        buf = {}
        commits = {}      # sign -> {k: time}
        connected = {}
        t_start = time.monotonic()
        for i in range(a.signs):
            sid = f"b{i:03d}"
            p = subprocess.Popen([celfw, "--backend", "null", "--size", "16x8", "--fps", "5",
                                  "--log-interval", "0", "--input", f"mqtt://127.0.0.1:{port}",
                                  "--sign-id", sid, "--mqtt-topic", "groups/bench"],
                                 stderr=subprocess.PIPE, stdout=subprocess.DEVNULL)
            procs.append(p)
            os.set_blocking(p.stderr.fileno(), False)
            sel.register(p.stderr, selectors.EVENT_READ, sid)
            buf[sid] = b""
            commits[sid] = {}

        def pump(until, done):
            while time.monotonic() < until and not done():
                for key, _ in sel.select(timeout=0.05):
                    now = time.monotonic()
                    sid = key.data
                    chunk = key.fileobj.read() or b""
                    buf[sid] += chunk
                    *lines, buf[sid] = buf[sid].split(b"\n")
                    for line in lines:
                        if b"mqtt connected to" in line:
                            connected.setdefault(sid, now)
                        elif b"stream commit " in line and b" applied" in line:
                            k = int(line.split(b"stream commit ")[1].split()[0])
                            commits[sid][k] = now

        pump(time.monotonic() + a.timeout, lambda: len(connected) == a.signs)
        if len(connected) < a.signs:
            print(f"only {len(connected)} of {a.signs} signs connected", file=sys.stderr)
            return 1
        print(f"{a.signs} celfw signs connected in {max(connected.values()) - t_start:.2f} s")

        cpu0 = cpu_seconds(broker.pid)
        meds, worst_all = [], 0.0
        for k in range(1, a.publishes + 1):
            time.sleep(0.5)
            t0 = time.monotonic()
            # The signs' lines are read while celc runs, not after: their time is
            # when they came.
            pub = subprocess.Popen([celc, "publish", streams[(k - 1) % 2], "--broker",
                                    f"mqtt://127.0.0.1:{port}", "--topic", "groups/bench",
                                    "--retain"], stdout=subprocess.DEVNULL)
            pump(t0 + a.timeout, lambda: all(k in c for c in commits.values()))
            if pub.wait() != 0:
                print(f"publish {k}: celc publish failed", file=sys.stderr)
                return 1
            got = [c[k] - t0 for c in commits.values() if k in c]
            if len(got) < a.signs:
                print(f"publish {k}: only {len(got)} of {a.signs} signs applied it", file=sys.stderr)
                return 1
            med, worst = statistics.median(got), max(got)
            meds.append(med)
            worst_all = max(worst_all, worst)
            print(f"publish {k:2d}: all {a.signs} applied; median {med * 1000:.0f} ms, "
                  f"worst {worst * 1000:.0f} ms")
        cpu = cpu_seconds(broker.pid) - cpu0
        size = os.path.getsize(streams[0])
        print(f"fleet: {a.signs} signs, {a.publishes} publishes of the demo stream ({size} B): "
              f"median {statistics.median(meds) * 1000:.0f} ms, worst {worst_all * 1000:.0f} ms; "
              f"broker CPU {cpu:.2f} s over the publishes ({cpu / a.publishes * 1000:.0f} ms each)")
        return 0
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
        for p in procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        subprocess.run(["rm", "-rf", work])


if __name__ == "__main__":
    sys.exit(main())
