#!/usr/bin/env bash
# Progress in a log (issue 20): compare and bench with stdout and stderr redirected to files write
# no carriage return, and each job's labelled stage lines ("LABEL: P % (done/total) ...") start at
# 0 % and climb strictly to 100 % (a multithreaded reference once printed 97 -> 94 -> 100); the
# report line that follows them is intact. Two views so that labels repeat; ssdo adds the
# one-bounce reference; --no-cache so the references are traced here.
# usage: test_progress.sh OBSCURA
set -uo pipefail
OBSCURA=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# check_log OUT ERR LABEL...: no \r anywhere; every LABEL's runs go 0 -> ... -> 100, strictly up.
check_log() {
    python3 - "$@" <<'PY'
import re, sys
out, err, labels = sys.argv[1], sys.argv[2], sys.argv[3:]
for path in (out, err):
    data = open(path, "rb").read()
    assert b"\r" not in data, f"{path} holds a carriage return"
    assert b"\x1b" not in data, f"{path} holds a terminal escape"
runs = {}   # label -> list of runs, each a list of percentages
for line in open(err).read().splitlines():
    m = re.match(r"^(.+?): (\d+) % \((\d+)/(\d+)\)", line)
    if not m:
        continue
    label, pct, done, total = m.group(1), int(m.group(2)), int(m.group(3)), int(m.group(4))
    assert pct == done * 100 // total, line
    seq = runs.setdefault(label, [])
    if pct == 0:
        assert not seq or seq[-1][-1] == 100, f"{label}: a new run began before the last reached 100: {seq}"
        seq.append([0])
        continue
    assert seq, f"{label}: {pct} % before its 0 %"
    assert pct > seq[-1][-1], f"{label}: went from {seq[-1][-1]} % to {pct} %"
    seq[-1].append(pct)
for want in labels:
    got = [l for l in runs if l.startswith(want)]
    assert got, f"no stage lines for {want}: {list(runs)}"
for label, seq in runs.items():
    for r in seq:
        assert r[-1] == 100, f"{label}: stopped at {r[-1]} %"
        # A stage line per quarter crossed, no more: at most 0, 25, 50, 75, 100.
        assert len(r) <= 5 and len({p // 25 for p in r}) == len(r), f"{label}: {r}"
PY
}

if "$OBSCURA" compare --scene corner:diagonal --scene cornell:front --methods ssao,ssdo --size 80x60 --spp 32 \
    --no-cache --report "$dir/report" >"$dir/compare.out" 2>"$dir/compare.err"; then ok
else bad "compare failed: $(cat "$dir/compare.err")"; fi
if check_log "$dir/compare.out" "$dir/compare.err" "compare" "reference AO" "reference bounce"; then ok
else bad "compare's log: $(cat "$dir/compare.err")"; fi
# Two views of two methods: compare's 0 %, then a line per method naming the view and the method
# (it moves at every method, so ten methods a view never look hung); each reference once per view.
[ "$(grep -c '^compare: ' "$dir/compare.err")" -eq 5 ] &&
    grep -q '^compare: 50 % (2/4) corner:diagonal ssdo (2/2)' "$dir/compare.err" &&
    grep -q '^compare: 75 % (3/4) cornell:front ssao (1/2)' "$dir/compare.err" && ok ||
    bad "compare's step lines: $(grep '^compare' "$dir/compare.err")"
[ "$(grep -c '^reference AO .*: 0 %' "$dir/compare.err")" -eq 2 ] && ok || bad "reference AO runs: $(cat "$dir/compare.err")"
grep -qx "report: $dir/report/index.html" "$dir/compare.out" && ok || bad "report line: $(cat "$dir/compare.out")"

# On a terminal (a pseudo-terminal 100 columns wide): compare's bar keeps a line of its own. It
# is held, naming the view, on the line above each view's reference bars (not wiped by them), it
# ends at 100 % on its own line, and no redraw is wider than the terminal (a wrapped line would
# leave its upper rows behind at every '\r').
if python3 - "$OBSCURA" "$dir/tty" <<'PY'
import fcntl, os, pty, re, struct, subprocess, sys, termios
obscura, report = sys.argv[1], sys.argv[2]
m, s = pty.openpty()
fcntl.ioctl(s, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
p = subprocess.Popen([obscura, "compare", "--scene", "corner:diagonal", "--scene", "cornell:front", "--methods",
                      "ssao,ssdo", "--size", "80x60", "--spp", "32", "--no-cache", "--report", report],
                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=s)
os.close(s)
data = b""
while True:
    try:
        chunk = os.read(m, 65536)
    except OSError:
        break
    if not chunk:
        break
    data += chunk
assert p.wait() == 0, data.decode(errors="replace")
# The terminal turns "\n" into "\r\n"; what a line finally shows is what follows its last '\r'.
lines = [l.split(b"\r")[-1].replace(b"\x1b[K", b"").decode() for l in data.replace(b"\r\n", b"\n").split(b"\n")]
for l in data.replace(b"\r\n", b"\n").split(b"\n"):
    for seg in l.split(b"\r"):
        assert len(seg.replace(b"\x1b[K", b"")) < 100, f"wider than the terminal: {seg!r}"
for k, view in enumerate(("corner:diagonal", "cornell:front")):
    held = [i for i, l in enumerate(lines) if l.startswith("compare [") and f"{view} reference (view {k + 1}/2)" in l]
    assert held, f"no held compare line for {view}: {lines}"
    assert lines[held[0] + 1].startswith("reference AO"), f"the reference bar is not below it: {lines}"
assert re.match(r"compare \[#+\] 100 % 4/4 cornell:front ssdo \(2/2\)", lines[-2]), lines
PY
then ok; else bad "compare on a terminal"; fi

if "$OBSCURA" bench --scene corner --methods ssao,gtao --size 48x36 --frames 2 --warmup 1 \
    >"$dir/bench.out" 2>"$dir/bench.err"; then ok; else bad "bench failed: $(cat "$dir/bench.err")"; fi
check_log "$dir/bench.out" "$dir/bench.err" "bench" && ok || bad "bench's log: $(cat "$dir/bench.err")"
# A run without --full says how to run the whole table.
grep -q -- "--full" "$dir/bench.out" && ok || bad "bench names no --full: $(cat "$dir/bench.out")"

echo "test_progress: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
