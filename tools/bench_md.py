#!/usr/bin/env python3
"""Splices benchmark results into BENCHMARKS.md: python3 tools/bench_md.py RESULTS_DIR BENCHMARKS.md

BENCHMARKS.md is hand-written prose with generated tables. Each table lives between
<!-- bench:NAME --> and <!-- /bench:NAME --> and is replaced by RESULTS_DIR/NAME.txt
(written by tools/bench_run.sh and the bench program); text outside the markers is kept.
A marker whose file is missing keeps its old contents, so running one section at a time
leaves the others as they were."""
import os
import re
import sys


def main():
    res, md = sys.argv[1], sys.argv[2]
    text = open(md).read()

    def fill(m):
        name = m.group(1)
        path = os.path.join(res, name + ".txt")
        if not os.path.exists(path):
            return m.group(0)
        body = open(path).read().rstrip("\n")
        return "<!-- bench:%s -->\n%s\n<!-- /bench:%s -->" % (name, body, name)

    new = re.sub(r"<!-- bench:([a-z]+) -->.*?<!-- /bench:\1 -->", fill, text, flags=re.S)
    with open(md, "w") as f:
        f.write(new)


if __name__ == "__main__":
    main()
