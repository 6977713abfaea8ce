#!/usr/bin/env bash
# Hostile command lines, sidecars and outputs (issue 19; the output format of issue 20): each case
# gets its exit code, one non-empty stderr line naming what is wrong, no output and no *.tmp-*
# file left behind, and an existing output kept as it was. Model files are tests/test_hostile_models.sh's.
# usage: test_hostile_outputs.sh OBSCURA
set -u
OBSCURA=$(realpath "$1")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir" || exit 1
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# No temporary file or directory anywhere under the test directory.
no_tmp() { [ -z "$(find . -name '*.tmp-*' -print -quit)" ]; }

# expect CODE PATTERN NEW -- ARGS...: exit code, one stderr line matching PATTERN, no *.tmp-* left
# and none of the space-separated paths NEW created.
expect() {
    local code=$1 pattern=$2 new=$3
    shift 4
    "$OBSCURA" "$@" >stdout 2>stderr.all
    local got=$?
    # Progress (a bar redrawn with \r, or a line per stage with its percentage) is not the error.
    sed 's/.*\r//' stderr.all | grep -vE '[0-9] ?%' >stderr
    if [ "$got" -ne "$code" ]; then bad "obscura $* exited $got, want $code: $(cat stderr)"; return; fi
    if [ "$(wc -l <stderr)" -ne 1 ] || [ ! -s stderr ]; then bad "obscura $*: not one stderr line: $(cat stderr)"; return; fi
    if ! grep -qE -e "$pattern" stderr; then bad "obscura $*: '$(cat stderr)' lacks /$pattern/"; return; fi
    if ! no_tmp; then bad "obscura $* left $(find . -name '*.tmp-*')"; return; fi
    for f in $new; do
        if [ -e "$f" ]; then bad "obscura $* left $f"; return; fi
    done
    ok
}

R=(render --size 48x36 --method ssao --filter none)

# ---- output names, checked before the render ------------------------------------------------------
expect 2 "^obscura: --out: expected a file name, got ''$" "" -- "${R[@]}" --out ''
expect 2 "^obscura: --out x.bmp: unsupported extension '.bmp'.*\.png, \.jpg.*\.pfm" "x.bmp" -- "${R[@]}" --out x.bmp
expect 2 "^obscura: --out x: no extension.*\.png" "x" -- "${R[@]}" --out x
expect 2 "^obscura: --depth-out d.png: unsupported extension '.png'.*: \.pfm$" "o.png d.png" -- "${R[@]}" --out o.png --depth-out d.png
expect 2 "^obscura: --out and --ao-png both name o.png" "o.png" -- "${R[@]}" --out o.png --ao-png o.png
expect 4 "^obscura: --out nodir/o.png: cannot write a new file in its directory" "nodir" -- "${R[@]}" --out nodir/o.png
expect 2 "^obscura: --out x.gif: unsupported extension" "x.gif" -- sheet --scene corner --size 32x24 --methods ssao --out x.gif
expect 2 "^obscura: --json: expected a file name, got ''$" "b.csv" -- bench --scene corner --size 32x24 --json '' --csv b.csv
expect 2 "^obscura: --report: expected a directory" "" -- compare --scene corner --size 32x24 --report ''
# A name that fits the directory but not with the suffix of its temporary directory: refused
# before the render, not after it.
long=$(printf 'n%.0s' $(seq 250)).png
expect 4 "^obscura: --out n+\.png: cannot write a new file in its directory: File name too long" "$long" -- "${R[@]}" --out "$long"

# Outputs that exist and are not regular files are refused and left as they were.
mkfifo fifo.png
mkdir dir.png
ln -s /dev/null null.png
expect 4 "^obscura: --out /dev/null: exists and is a character device, not a regular file" "" -- "${R[@]}" --out /dev/null
[ -c /dev/null ] && ok || bad "/dev/null is no longer a device"
expect 4 "^obscura: --out fifo.png: exists and is a FIFO" "" -- "${R[@]}" --out fifo.png
[ -p fifo.png ] && ok || bad "fifo.png is no longer a FIFO"
expect 4 "^obscura: --out dir.png: exists and is a directory" "" -- "${R[@]}" --out dir.png
[ -d dir.png ] && ok || bad "dir.png is no longer a directory"
expect 4 "^obscura: --ao-out null.png: exists and is a character device" "o.png" -- "${R[@]}" --out o.png --ao-out null.png
[ -L null.png ] && [ -c null.png ] && ok || bad "null.png is no longer a link to /dev/null"
expect 4 "^obscura: --csv fifo.png: exists and is a FIFO" "b.json" -- bench --scene corner --size 32x24 --json b.json --csv fifo.png
expect 4 "^obscura: --out dir.png: exists and is a directory" "" -- tune --method hbao --params hbao.noise --train corner:diagonal --out dir.png
expect 4 "^obscura: --report fifo.png: exists and is a FIFO, not a directory" "" -- compare --scene corner --size 32x24 --report fifo.png
mkdir notes && echo mine >notes/notes.txt
expect 4 "^obscura: --report notes: holds notes.txt, which obscura did not write: refusing to replace it; give a new directory$" \
    "" -- compare --scene corner --size 32x24 --report notes
[ "$(cat notes/notes.txt)" = mine ] && ok || bad "compare touched a directory that is not a report"
rm -rf fifo.png dir.png null.png notes

# ---- the format follows the extension ---------------------------------------------------------------
magic() { head -c "$2" "$1" | od -An -tx1 | tr -d ' \n'; }
if "$OBSCURA" "${R[@]}" --out f.jpg --ao-out a.pfm --ao-png a.jpg --depth-out d.pfm --normal-out n.pfm >/dev/null 2>stderr; then
    [ "$(magic f.jpg 3)" = ffd8ff ] && ok || bad "--out f.jpg is not a JPEG: $(magic f.jpg 8)"
    [ "$(magic a.jpg 3)" = ffd8ff ] && ok || bad "--ao-png a.jpg is not a JPEG"
    [ "$(head -c 2 a.pfm)" = Pf ] && [ "$(head -c 2 n.pfm)" = PF ] && ok || bad "the PFM outputs have the wrong headers"
    [ "$(stat -c %s a.pfm)" -eq $((48 * 36 * 4 + $(head -3 a.pfm | wc -c))) ] && ok || bad "a.pfm has the wrong size"
else
    bad "render to .jpg/.pfm failed: $(cat stderr)"
fi
"$OBSCURA" "${R[@]}" --out F.JPEG >/dev/null 2>&1 && [ "$(magic F.JPEG 3)" = ffd8ff ] && ok || bad "--out F.JPEG is not a JPEG"
"$OBSCURA" "${R[@]}" --out p.png --view ao >/dev/null 2>&1 && [ "$(magic p.png 8)" = 89504e470d0a1a0a ] && ok || bad "--out p.png is not a PNG"
"$OBSCURA" "${R[@]}" --out p.pfm >/dev/null 2>&1 && [ "$(head -c 2 p.pfm)" = PF ] && ok || bad "--out p.pfm is not an RGB PFM"
"$OBSCURA" sheet --scene corner --size 32x24 --methods ssao --out s.jpg >/dev/null 2>&1 && [ "$(magic s.jpg 3)" = ffd8ff ] &&
    ok || bad "sheet --out s.jpg is not a JPEG"
no_tmp && ok || bad "the writes left $(find . -name '*.tmp-*')"

# ---- a failure keeps every existing output --------------------------------------------------------------
# A file-size limit that the PNG fits and the PFM (48x36 floats, 6.9 KB) does not: the second output
# fails after the first was written, the way a full disk would. SIGXFSZ is ignored so that the write
# fails with EFBIG instead of killing the process.
"$OBSCURA" "${R[@]}" --out keep.png >/dev/null 2>&1 && cp keep.png keep.orig && echo old >keep.pfm
( trap '' XFSZ; ulimit -f 5; exec "$OBSCURA" "${R[@]}" --out keep.png --ao-out keep.pfm ) >stdout 2>stderr
got=$?
[ "$got" -eq 4 ] && grep -qE "^obscura: --ao-out keep.pfm: cannot write it" stderr && [ "$(wc -l <stderr)" -eq 1 ] &&
    ok || bad "a failing --ao-out: exit $got, $(cat stderr)"
cmp -s keep.png keep.orig && [ "$(cat keep.pfm)" = old ] && ok || bad "a failing --ao-out changed the existing outputs"
no_tmp && ok || bad "a failing --ao-out left $(find . -name '*.tmp-*')"

# Along an orbit: a frame output that cannot be written is found before the first frame.
mkfifo orbit-0002.png
expect 4 "^obscura: --out orbit-0002.png: exists and is a FIFO" "orbit-0000.png orbit-0001.png" -- \
    "${R[@]}" --orbit 30 --path-frames 3 --out orbit.png
rm -f orbit-0002.png

# bench: the CSV is written first, then the JSON; a JSON that fails leaves neither and keeps both
# earlier files (the JSON, 3.6 KB here, is the larger: a 3 KB limit fails it alone).
B=(bench --scene corner --size 32x24 --frames 2 --warmup 0 --methods ssao --samples 12 --radius 4 --cameras default)
echo old-json >b.json && echo old-csv >b.csv
( trap '' XFSZ; ulimit -f 3; exec "$OBSCURA" "${B[@]}" --json b.json --csv b.csv ) >/dev/null 2>stderr
got=$?
[ "$got" -eq 4 ] && grep -qE "^obscura: --json b.json: cannot write it" stderr && ok || bad "bench with a failing JSON: exit $got, $(cat stderr)"
[ "$(cat b.json)" = old-json ] && [ "$(cat b.csv)" = old-csv ] && ok || bad "a failed bench changed b.json or b.csv"
no_tmp && ok || bad "a failed bench left $(find . -name '*.tmp-*')"
"$OBSCURA" "${B[@]}" --json b.json --csv b.csv >/dev/null 2>&1 && python3 -c 'import json,sys; json.load(open("b.json"))' &&
    head -1 b.csv | grep -q '^scene,' && ok || bad "bench did not replace the pair when it succeeded"

# ---- cameras and lights, from the options and from sidecars, checked alike --------------------------------
expect 2 "^obscura: --eye/--target: up \(0, 1, 0\) is parallel to the view direction" "o.png" -- \
    "${R[@]}" --out o.png --eye 0,5,0 --target 0,0,0
expect 2 "^obscura: --eye/--target: eye \(1e\+30, 5, 0\) is not finite or beyond" "o.png" -- "${R[@]}" --out o.png --eye 1e30,5,0 --target 0,0,0
expect 2 "^obscura: --eye: expected X,Y,Z \(finite numbers\), got '1e39,5,0'" "o.png" -- "${R[@]}" --out o.png --eye 1e39,5,0 --target 0,0,0
expect 2 "^obscura: --fov: expected degrees in \[0.01, 179\)" "o.png" -- "${R[@]}" --out o.png --fov 0.001
expect 2 "dir=1e39,1,0.*bad value for dir" "o.png" -- "${R[@]}" --out o.png --light "directional dir=1e39,1,0"
expect 2 "intensity 1e\+20 .*above 10000 for a directional light" "o.png" -- "${R[@]}" --out o.png --light "directional dir=0,1,0 intensity=1e20"
expect 2 "intensity 1e\+20 .*above 1e\+12 for a point or spot light" "o.png" -- "${R[@]}" --out o.png --light "point pos=0,1,0 intensity=1e20"
# A direction whose squares overflow a float is still a direction (it used to become NaN: no light).
"$OBSCURA" "${R[@]}" --out big.png --light "directional dir=1e30,1e30,0" >/dev/null 2>&1 &&
    "$OBSCURA" "${R[@]}" --out small.png --light "directional dir=1,1,0" >/dev/null 2>&1 && cmp -s big.png small.png &&
    ok || bad "dir=1e30,1e30,0 does not light as dir=1,1,0"

# A tiny model (a floor and a wall) with sidecars.
printf 'v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nf 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\n' >m.obj
side() { printf '%s\n' "$1" >m.obscura.json; }
side '{"cameras": [{"name": "far", "eye": [1e30, 0, 0], "target": [0, 0, 0]}]}'
expect 3 "^obscura: ./m.obscura.json: cameras\[0\] \(\"far\"\): eye \(1e\+30, 0, 0\) is not finite or beyond" "o.png" -- \
    "${R[@]}" --scene m.obj --out o.png
side '{"cameras": [{"name": "down", "eye": [0.5, 5, 0.5], "target": [0.5, 0, 0.5]}]}'
expect 3 "^obscura: ./m.obscura.json: cameras\[0\] \(\"down\"\): up \(0, 1, 0\) is parallel" "o.png" -- "${R[@]}" --scene m.obj --out o.png
side '{"lights": [{"type": "directional", "direction": [0, 1, 0], "intensity": 1e6}]}'
expect 3 "^obscura: ./m.obscura.json: lights\[0\]: intensity 1e\+06 .*above 10000" "o.png" -- "${R[@]}" --scene m.obj --out o.png
side '{"lights": [{"type": "point", "position": [1e30, 0, 0]}]}'
expect 3 "^obscura: ./m.obscura.json: lights\[0\]: position \(1e\+30, 0, 0\) is not finite or beyond" "o.png" -- "${R[@]}" --scene m.obj --out o.png

# ---- empty frames --------------------------------------------------------------------------------------
side '{"cameras": [{"name": "away", "eye": [0.5, 0.5, 5], "target": [0.5, 0.5, 10]}]}'
expect 3 "^obscura: nothing visible from this camera \(m:away\)" "o.png" -- "${R[@]}" --scene m.obj --camera away --out o.png
expect 2 "^obscura: nothing visible from this camera \(cornell:explicit\)" "o.png" -- "${R[@]}" --out o.png --eye 0,0,100 --target 0,0,200
expect 3 "^obscura: nothing visible from this camera \(m:away\)" "s.png" -- sheet --scene m.obj --camera away --size 32x24 --methods ssao --out s.png
expect 3 "^obscura: nothing visible from this camera \(m:away\)" "e.json" -- bench --scene m.obj --cameras away --size 32x24 \
    --frames 2 --warmup 0 --methods ssao --samples 12 --radius 4 --json e.json
"$OBSCURA" "${R[@]}" --scene m.obj --camera away --out empty.png --allow-empty >/dev/null 2>&1 && [ -s empty.png ] &&
    ok || bad "--allow-empty did not write the empty frame"

# ---- compare: the report replaces --report only whole -------------------------------------------------------
C=(compare --size 32x24 --spp 8 --methods ssao --filters none)
export XDG_CACHE_HOME=$dir/cache
# The second view sees nothing: it fails after the first view's images were written.
expect 3 "^obscura: nothing visible from this camera \(m:away\)" "rep" -- "${C[@]}" --scene corner --scene m.obj:away --report rep
if "$OBSCURA" "${C[@]}" --scene corner --report rep >/dev/null 2>stderr; then ok; else bad "compare failed: $(cat stderr)"; fi
sum() { find rep -type f | sort | xargs cat | md5sum; }
before=$(sum)
expect 3 "^obscura: nothing visible from this camera \(m:away\)" "" -- "${C[@]}" --scene corner --scene m.obj:away --report rep
[ "$(sum)" = "$before" ] && ok || bad "a failed compare changed the existing report"
"$OBSCURA" "${C[@]}" --scene sphere-on-plane --report rep/ >stdout 2>stderr && grep -q "^report: rep/index.html" stdout &&
    grep -q sphere rep/results.json && ! grep -q '"corner"' rep/results.json && ok || bad "a good compare did not replace the report: $(cat stderr)"
no_tmp && ok || bad "compare left $(find . -name '*.tmp-*')"

# ---- --report replaces only what obscura wrote (issue 44, class 5) ------------------------------------------
# A report lists what it holds in .obscura-report; a directory is replaced only when it is empty
# or holds nothing that list does not name. Whatever is refused is left exactly as it was.
python3 - rep <<'PY' && ok || bad "rep/.obscura-report does not list exactly what the report holds"
import json, os, sys
root = sys.argv[1]
listed = set(json.load(open(os.path.join(root, ".obscura-report")))["written"])
found = set()
for d, dirs, files in os.walk(root):
    rel = os.path.relpath(d, root)
    found |= {os.path.join(rel, x).removeprefix("./") + "/" for x in dirs}
    found |= {os.path.join(rel, x).removeprefix("./") for x in files}
found.discard(".obscura-report")
assert listed == found, (sorted(listed ^ found))
PY
tree() { (cd "$1" && find . | LC_ALL=C sort && find . -type f -exec md5sum {} + | LC_ALL=C sort -k2); }
# A folder with an index.html of its own, notes and images: the report of an earlier obscura, or
# not a report at all; either way not obscura's to delete.
mkdir -p mine/img && echo '<html>mine</html>' >mine/index.html && echo notes >mine/notes.txt && echo px >mine/img/a.png
before=$(tree mine)
expect 4 "^obscura: --report mine: a report of an earlier obscura, which did not list the files it wrote \(no \.obscura-report\)" \
    "" -- "${C[@]}" --scene corner --report mine
[ "$(tree mine)" = "$before" ] && ok || bad "compare changed a directory with an index.html of its own"
# A report obscura wrote, then a file and a directory of the user's added: refused, kept.
cp -a rep rep2 && echo mine >rep2/notes.txt
before=$(tree rep2)
expect 4 "^obscura: --report rep2: holds notes.txt, which obscura did not write: refusing to replace it; give a new directory$" \
    "" -- "${C[@]}" --scene corner --report rep2
[ "$(tree rep2)" = "$before" ] && ok || bad "compare changed a report that holds a file of the user's"
rm -f rep2/notes.txt && mkdir -p rep2/sphere-on-plane_default/mine
expect 4 "^obscura: --report rep2: holds sphere-on-plane_default/mine/, which obscura did not write" "" -- \
    "${C[@]}" --scene corner --report rep2
[ -d rep2/sphere-on-plane_default/mine ] && ok || bad "compare removed a directory of the user's in a report"
# A manifest that is not one obscura writes is no licence either.
rm -rf rep2/sphere-on-plane_default/mine && echo '{"written": ["index.html"]}' >rep2/.obscura-report
expect 4 "^obscura: --report rep2: its \.obscura-report is not a list obscura wrote" "" -- "${C[@]}" --scene corner --report rep2
# A report obscura wrote, with nothing added (a file of it removed is fine): replaced.
rm -rf rep2 && cp -a rep rep2 && rm rep2/results.json
"$OBSCURA" "${C[@]}" --scene corner --report rep2 >/dev/null 2>stderr && grep -q '"corner"' rep2/results.json &&
    [ ! -e rep2/sphere-on-plane_default ] && ok || bad "compare did not replace a report it wrote: $(cat stderr)"
rm -rf mine rep2
no_tmp && ok || bad "the --report cases left $(find . -name '*.tmp-*')"

# An interrupted compare (SIGTERM while it traces the reference, 600 M rays: far longer than the
# poll) removes its temporary report and dies of the signal.
timeout 300 "$OBSCURA" compare --scene corner --size 64x48 --spp 200000 --methods ssao --filters none --report sig \
    >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1200); do ls -d sig.tmp-* >/dev/null 2>&1 && break; sleep 0.05; done
if ls -d sig.tmp-* >/dev/null 2>&1; then
    kill -TERM $pid
    wait $pid
    got=$?
    [ "$got" -eq 143 ] && [ ! -e sig ] && no_tmp && ok || bad "an interrupted compare: exit $got, left $(ls -d sig* 2>/dev/null)"
else
    wait $pid
    bad "compare made no temporary report"
fi

# ---- names are valid UTF-8 in JSON and HTML --------------------------------------------------------------------
cp m.obj "$(printf 'bad\xff.obj')"
printf '{"cameras": [{"name": "cam\xc3\x28\xed\xa0\x80", "eye": [2, 1.5, 2.5], "target": [0.5, 0.3, 0.5]}]}\n' >"$(printf 'bad\xff.obscura.json')"
badscene=$(printf 'bad\xff.obj:cam\xc3\x28\xed\xa0\x80')
if "$OBSCURA" "${C[@]}" --scene "$badscene" --report utf >/dev/null 2>stderr &&
    "$OBSCURA" "${B[@]}" --scene "$(printf 'bad\xff.obj')" --cameras "$(printf 'cam\xc3\x28\xed\xa0\x80')" --json u.json >/dev/null 2>>stderr; then
    python3 - utf/results.json utf/index.html u.json <<'PY' && ok || bad "invalid UTF-8 reached the JSON or HTML"
import json, sys
for path in sys.argv[1:]:
    text = open(path, "rb").read().decode("utf-8")  # strict: raises on any invalid byte
    if path.endswith(".json"):
        json.loads(text)
    # 0xC3 0x28: the 0xC3 alone is replaced; 0xED 0xA0 0x80 is a surrogate: three replacements.
    assert "cam\ufffd(\ufffd\ufffd\ufffd" in text, path
PY
else
    bad "compare/bench on a scene with invalid UTF-8 names failed: $(cat stderr)"
fi

echo "hostile outputs: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
