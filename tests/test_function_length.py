#!/usr/bin/env python3
"""No top-level function of compare's, bench's and tune's files (app/compare*.c, app/bench*.c,
app/tune*.c) runs past LIMIT lines, from the line of its opening brace to the line of its closing
one (issue 48: running and reporting were one 200-to-300-line function each, which no one could
change safely; tune's was one of 280 until its shards needed its evaluations apart). Prints the
longest function of each file; fails naming every function over the limit.

usage: test_function_length.py SOURCE_DIR [LIMIT]"""
import glob
import os
import re
import sys

LIMIT = 100


def blank(match):
    """The comment or literal as spaces, its line breaks kept (line numbers stay right)."""
    return re.sub(r"[^\n]", " ", match.group(0))


def functions(path):
    """(name, first line, length) of every top-level function body of a C file."""
    text = open(path, encoding="utf-8").read()
    code = re.sub(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', blank, text, flags=re.S)
    lines = code.split("\n")
    depth, start, name = 0, None, None
    for i, line in enumerate(lines):
        for j, ch in enumerate(line):
            if ch == "{":
                if depth == 0:
                    # A function when the text before the brace ends with ')': its signature.
                    before = "\n".join(lines[max(0, i - 8):i] + [line[:j]]).rstrip()
                    start = None
                    if before.endswith(")"):
                        sig = re.split(r"[;}]", before)[-1]
                        found = re.search(r"([A-Za-z_]\w*)\s*\(", sig)
                        start, name = i, found.group(1) if found else "?"
                depth += 1
            elif ch == "}":
                depth -= 1
                if depth == 0 and start is not None:
                    yield name, start + 1, i - start + 1
                    start = None


def main():
    src = sys.argv[1]
    limit = int(sys.argv[2]) if len(sys.argv) > 2 else LIMIT
    files = sorted(glob.glob(os.path.join(src, "app", "compare*.c")) + glob.glob(os.path.join(src, "app", "bench*.c")) +
                   glob.glob(os.path.join(src, "app", "tune*.c")))
    if not files:
        print("FAIL: no app/compare*.c, app/bench*.c or app/tune*.c under %s" % src)
        return 1
    over = []
    for path in files:
        found = list(functions(path))
        rel = os.path.relpath(path, src)
        if not found:
            over.append("%s: no function found" % rel)
            continue
        name, line, length = max(found, key=lambda f: f[2])
        print("%s: longest %s, %d lines (line %d)" % (rel, name, length, line))
        over += ["%s:%d: %s is %d lines" % (rel, l, n, k) for n, l, k in found if k > limit]
    for o in over:
        print("FAIL: %s (limit %d)" % (o, limit))
    print("test_function_length: %d files, %d over %d lines" % (len(files), len(over), limit))
    return 1 if over else 0


sys.exit(main())
