#!/usr/bin/env bash
# Does a change leave every method's output alone? Renders every method both builds know, at default
# settings, and at --ao-scale 0.5 --filter bilateral, on four views (cornell:front,
# corner:diagonal, bunny:front, fzk-haus:stair) at 160x120 with two builds of obscura, and
# compares the AO PFMs (worst absolute difference, tolerance 1e-5) and the final PNGs (bytes).
# Issue 12's refactor was checked this way against the build before it (0 difference, 56 PFMs
# and 56 PNGs).
#   scripts/compare-builds.sh OLD_OBSCURA NEW_OBSCURA [OUTDIR]
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 OLD_OBSCURA NEW_OBSCURA [OUTDIR]" >&2; exit 2; }
old=$1 new=$2 out=${3:-$(mktemp -d)}
mkdir -p "$out/old" "$out/new"
# The methods both builds know (a method added since OLD has nothing to compare with).
names() { "$1" list --json | python3 -c 'import json,sys; print("\n".join(m["name"] for m in json.load(sys.stdin)["methods"]))'; }
methods=$(grep -Fxf <(names "$old") <(names "$new"))
for v in cornell:front corner:diagonal bunny:front fzk-haus:stair; do
    scene=${v%%:*} cam=${v##*:}
    for m in $methods; do
        for side in old new; do
            bin=$old; [ $side = new ] && bin=$new
            "$bin" render --scene "$scene" --camera "$cam" --method "$m" --size 160x120 \
                --out "$out/$side/${scene}_$m.png" --ao-out "$out/$side/${scene}_$m.pfm"
            "$bin" render --scene "$scene" --camera "$cam" --method "$m" --size 160x120 --ao-scale 0.5 \
                --filter bilateral --out "$out/$side/${scene}_${m}_half.png" --ao-out "$out/$side/${scene}_${m}_half.pfm"
        done
    done
done
python3 - "$out/old" "$out/new" <<'PY'
import glob, os, struct, sys, filecmp
def pfm(p):
    with open(p, 'rb') as f:
        kind = f.readline().strip(); w, h = map(int, f.readline().split()); scale = float(f.readline())
        n = w * h * (3 if kind == b'PF' else 1)
        return struct.unpack(('<' if scale < 0 else '>') + '%df' % n, f.read(4 * n))
a, b = sys.argv[1], sys.argv[2]
worst, bad = 0.0, 0
for p in sorted(glob.glob(a + '/*.pfm')):
    x, y = pfm(p), pfm(os.path.join(b, os.path.basename(p)))
    d = max(abs(u - v) for u, v in zip(x, y)) if len(x) == len(y) else float('inf')
    worst = max(worst, d)
    if d > 1e-5: print('AO differs: %s by %.3g' % (os.path.basename(p), d)); bad += 1
pngs = sorted(glob.glob(a + '/*.png'))
diff = [os.path.basename(p) for p in pngs if not filecmp.cmp(p, os.path.join(b, os.path.basename(p)), shallow=False)]
for d in diff: print('final image differs: ' + d)
print('%d AO maps, worst difference %.3g (%d over 1e-5); %d final images, %d differ'
      % (len(glob.glob(a + '/*.pfm')), worst, bad, len(pngs), len(diff)))
sys.exit(1 if bad or diff else 0)
PY
