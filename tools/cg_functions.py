#!/usr/bin/env python3
"""Instruction counts of a callgrind profile by source function, inlined code included:
python3 tools/cg_functions.py CALLGRIND.OUT [TOP]

callgrind_annotate's function list charges inlined code to the caller (most of a celscan
line is inlined into cs__line_stack), so it cannot say what the time is spent on. Its
per-line annotation can: every source line carries its own count wherever it was inlined.
This script reads the annotated core/ sources, finds which function each line belongs to
(a definition starts at column 0 with "name(" and ends at the next "}" at column 0), and
prints the TOP functions (default 12) with their share of the profile as a Markdown table."""
import re
import subprocess
import sys


def functions_of(path):
    """Line number -> function name for a C file (definitions at column 0)."""
    owner, current = {}, None
    try:
        lines = open(path).read().split("\n")
    except OSError:
        return owner
    for i, text in enumerate(lines, 1):
        m = re.match(r"^[A-Za-z_][\w \*]*?\b(\w+)\(", text)
        if m and not text.rstrip().endswith(";") and not text.startswith(("typedef", "#")):
            current = m.group(1)
        if current:
            owner[i] = current
        if text.startswith("}"):
            current = None
    return owner


def main():
    out, top = sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 12
    text = subprocess.run(["callgrind_annotate", "--auto=yes", "--show-percs=no", "--threshold=100",
                           "--context=0", out], capture_output=True, text=True).stdout
    total, costs, owners, path, line = 0, {}, {}, None, 0
    for row in text.split("\n"):
        if "PROGRAM TOTALS" in row:
            total = int(row.split()[0].replace(",", ""))
        if "events annotated" in row or row.startswith("The following files"):
            path = None
            continue
        m = re.match(r"-- Auto-annotated source: (\S+)", row)
        if m:
            path = m.group(1)
            if path not in owners:
                owners[path] = functions_of(path)
            continue
        m = re.match(r"-- line (\d+) -", row)
        if m:
            line = int(m.group(1)) - 1
            continue
        if path is None or not path.startswith("core/"):
            continue
        m = re.match(r"^\s*([0-9,]+|\.)\s", row)
        if not m:
            continue
        line += 1
        if "=>" in row or m.group(1) == ".":
            if "=>" in row:
                line -= 1  # call lines do not advance the source
            continue
        name = owners[path].get(line, "(file scope)")
        key = "%s:%s" % (path.split("/")[-1], name)
        costs[key] = costs.get(key, 0) + int(m.group(1).replace(",", ""))
    print("| function (with what is inlined into others counted where it is written) | instructions | share |")
    print("|---|---:|---:|")
    for key, v in sorted(costs.items(), key=lambda kv: -kv[1])[:top]:
        print("| %s | %.1f M | %.1f%% |" % (key, v / 1e6, 100.0 * v / total))


if __name__ == "__main__":
    main()
