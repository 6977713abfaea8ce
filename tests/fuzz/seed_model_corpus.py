#!/usr/bin/env python3
"""Seed inputs for tests/fuzz/fuzz_model.c (make fuzz): OUTDIR gets one file per small model of
assimp-testmodels (/usr/share/assimp/models, when installed) and of the hostile corpus
(tests/hostile/make_corpus.py), each prefixed with the byte fuzz_model reads as the extension.
Starting from real files of every format reaches the importers' deeper code in minutes; from an
empty corpus libFuzzer spends the run rediscovering headers.

Usage: seed_model_corpus.py OUTDIR     (Python 3 standard library only)
"""
import glob
import os
import subprocess
import sys
import tempfile

# The order of ext[] in fuzz_model.c: the first byte of an input, modulo its length, picks one.
EXT = [".ply", ".obj", ".gltf", ".glb", ".stl", ".off", ".fbx", ".dae", ".pk3", ".bsp"]
MAX_LEN = 65535  # make fuzz runs with -max_len=65536: one byte of prefix

out = sys.argv[1] if len(sys.argv) > 1 else "seeds-model"
os.makedirs(out, exist_ok=True)
here = os.path.dirname(os.path.abspath(__file__))
n = 0


def add(path):
    global n
    ext = os.path.splitext(path)[1].lower()
    if ext not in EXT or not os.path.isfile(path) or os.path.getsize(path) > MAX_LEN:
        return
    with open(path, "rb") as f:
        data = f.read()
    with open(os.path.join(out, "seed-%04d%s" % (n, ext)), "wb") as f:
        f.write(bytes([EXT.index(ext)]) + data)
    n += 1


for p in sorted(glob.glob("/usr/share/assimp/models/**/*", recursive=True)):
    add(p)
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([sys.executable, os.path.join(here, "..", "hostile", "make_corpus.py"), tmp],
                   check=True, stdout=subprocess.DEVNULL)
    for p in sorted(glob.glob(os.path.join(tmp, "**", "*"), recursive=True)):
        if not os.path.islink(p):
            add(p)
print(n)
