#!/usr/bin/env python3
"""put_table.py DOC TABLE - replaces the text between the markers
<!-- lottie-table begin --> and <!-- lottie-table end --> in DOC with the
contents of TABLE (written by tests/lottie_conf --table), so that
`make lottie-conformance` keeps docs/LOTTIE.md's figures those of the last run."""
import sys

BEGIN, END = "<!-- lottie-table begin -->", "<!-- lottie-table end -->"


def main():
    doc_path, table_path = sys.argv[1], sys.argv[2]
    doc = open(doc_path, encoding="utf-8").read()
    table = open(table_path, encoding="utf-8").read().strip()
    a, b = doc.find(BEGIN), doc.find(END)
    if a < 0 or b < a:
        sys.exit(f"put_table: {doc_path} lacks the {BEGIN} ... {END} markers")
    doc = doc[: a + len(BEGIN)] + "\n" + table + "\n" + doc[b:]
    open(doc_path, "w", encoding="utf-8").write(doc)


if __name__ == "__main__":
    main()
