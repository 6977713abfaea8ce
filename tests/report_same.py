#!/usr/bin/env python3
"""Two compare reports are the same run's: the same files, every image byte for byte, and every
number of results.json equal but the timings (GPU ms and what is ranked by them: the Pareto front,
median times) and the run's own facts (its date, command line, whether a reference came from the
cache). Used by the shard tests (a merged report against the unsharded run's).

usage: report_same.py WHOLE_REPORT MERGED_REPORT     exit 0 when the same, 1 (and why) when not"""
import json
import os
import sys

TIMING = {"ao_ms", "frame_ms", "chain_ms", "temporal_ms", "pareto", "median_ao_ms", "front", "seconds", "bounce_seconds",
          "cached", "date", "command_line"}


def files(root):
    return sorted(os.path.relpath(os.path.join(d, f), root) for d, _, fs in os.walk(root) for f in fs)


def walk(a, b, path):
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), (path, sorted(set(a) ^ set(b)))
        for k in a:
            if k not in TIMING:
                walk(a[k], b[k], path + "." + k)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), (path, len(a), len(b))
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, "%s[%d]" % (path, i))
    else:
        assert a == b, (path, a, b)


def main(a_dir, b_dir):
    assert files(a_dir) == files(b_dir), (files(a_dir), files(b_dir))
    for f in files(a_dir):
        if f.endswith(".png"):
            with open(os.path.join(a_dir, f), "rb") as fa, open(os.path.join(b_dir, f), "rb") as fb:
                assert fa.read() == fb.read(), f
    ja, jb = (json.load(open(os.path.join(d, "results.json"))) for d in (a_dir, b_dir))
    walk(ja, jb, "")
    assert [v["dir"] for v in ja["views"]] == [v["dir"] for v in jb["views"]]
    ha, hb = (open(os.path.join(d, "index.html")).read() for d in (a_dir, b_dir))
    heads = [v["scene"] + " &mdash; " + v["camera"] for v in ja["views"]]
    at = [hb.find(h) for h in heads]
    assert all(i >= 0 for i in at) and at == sorted(at), (heads, at)


if __name__ == "__main__":
    try:
        main(*sys.argv[1:3])
    except AssertionError as e:
        print(f"report_same: {sys.argv[1]} and {sys.argv[2]} differ: {e}", file=sys.stderr)
        sys.exit(1)
