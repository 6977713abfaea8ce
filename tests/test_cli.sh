#!/usr/bin/env bash
# CLI tests: every bad-input case gives one clear line, its exit code, and leaves no file; the
# outputs decode to the expected size and values; the same command twice gives the same bytes.
set -u
OBSCURA=$1
IMGCHECK=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# expect CODE PATTERN -- ARGS...: exit code, a one-line stderr matching PATTERN, no output left.
expect() {
    local code=$1 pattern=$2
    shift 3
    rm -f "$dir"/out.png "$dir"/ao.pfm
    "$OBSCURA" "$@" >"$dir/stdout" 2>"$dir/stderr"
    local got=$?
    local lines
    lines=$(wc -l <"$dir/stderr")
    if [ "$got" -ne "$code" ]; then bad "obscura $* exited $got, want $code: $(cat "$dir/stderr")"; return; fi
    if [ "$lines" -ne 1 ]; then bad "obscura $* printed $lines lines on stderr: $(cat "$dir/stderr")"; return; fi
    if ! grep -qiE "$pattern" "$dir/stderr"; then bad "obscura $*: '$(cat "$dir/stderr")' lacks /$pattern/"; return; fi
    if ls "$dir" | grep -qE '\.(png|pfm)|tmp-'; then bad "obscura $* left files: $(ls "$dir")"; return; fi
    ok
}

# ssao with the geometry filter (the defaults before gtao and crease; issue 13 changed them): the
# messages below name them.
R=(render --size 64x48 --out "$dir/out.png" --ao-out "$dir/ao.pfm" --method ssao --filter geometry)
expect 2 "unknown scene 'nosuch'" -- "${R[@]}" --scene nosuch
expect 2 "unknown method 'nosuch'" -- "${R[@]}" --method nosuch
expect 2 "no parameter 'nosuch'" -- "${R[@]}" --set ssao.nosuch=1
expect 2 "out of range" -- "${R[@]}" --set ssao.radius=-1
expect 2 "out of range" -- "${R[@]}" --set ssao.samples=100000
expect 2 "finite" -- "${R[@]}" --set ssao.radius=nan
expect 2 "expects a number" -- "${R[@]}" --set ssao.bias=abc
expect 2 "integer" -- "${R[@]}" --set ssao.samples=3.5
expect 2 "warmup: expected 0..100000, got '-1'" -- "${R[@]}" --warmup -1
expect 2 "WIDTHxHEIGHT" -- "${R[@]}" --size abc
expect 2 "WIDTHxHEIGHT" -- "${R[@]}" --size 0x0
expect 2 "WIDTHxHEIGHT" -- "${R[@]}" --size 640x
expect 2 "WIDTHxHEIGHT" -- "${R[@]}" --size -5x3
expect 2 "GL_MAX_TEXTURE_SIZE" -- "${R[@]}" --size 100000x8 --scene corner
expect 2 "unknown camera" -- "${R[@]}" --scene corner --camera nosuch
expect 2 "fov" -- "${R[@]}" --scene corner --fov 200
expect 2 "eye" -- "${R[@]}" --scene corner --eye 1,2 --target 0,0,0
expect 2 "unknown option" -- "${R[@]}" --frobnicate 3
expect 2 "unknown filter 'nosuch'" -- "${R[@]}" --filter nosuch
expect 2 "ao-scale" -- "${R[@]}" --ao-scale 0.3
expect 2 "adaptive" -- "${R[@]}" --adaptive maybe
expect 2 "temporal: expected on or off" -- "${R[@]}" --temporal maybe
expect 2 "path and --orbit exclude each other" -- "${R[@]}" --path walk --orbit 30
expect 2 "path-frames needs --path or --orbit" -- "${R[@]}" --path-frames 8
expect 2 "path-frames: expected 2..10000" -- "${R[@]}" --orbit 30 --path-frames 1
expect 2 "orbit: expected degrees" -- "${R[@]}" --orbit many
expect 2 "path gives the camera" -- "${R[@]}" --path walk --camera front
expect 2 "frames and --path/--orbit exclude" -- "${R[@]}" --orbit 30 --frames 4
expect 2 "unknown camera path 'walk'.*no \"paths\"" -- "${R[@]}" --path walk
expect 2 "temporal-at: expected before or after" -- "${R[@]}" --temporal-at middle
expect 2 "jitter: expected on, off or 0..64 sub-pixel positions, got '65'" -- "${R[@]}" --jitter 65
expect 2 "jitter: expected on, off or 0..64 sub-pixel positions, got 'some'" -- "${R[@]}" --jitter some
expect 2 "temporal-frames: expected a history length" -- "${R[@]}" --temporal-frames 0
expect 2 "temporal-frames: expected a history length" -- "${R[@]}" --temporal-frames 300
expect 2 "temporal-detail: expected a share of one-pixel detail" -- "${R[@]}" --temporal-detail 1
expect 2 "temporal-detail: expected a share of one-pixel detail" -- "${R[@]}" --temporal-detail nan
expect 2 "temporal_frames = 0 is out of range" -- "${R[@]}" --set temporal_frames=0
expect 2 "upsample: expected auto, plain or block, got 'fast'" -- "${R[@]}" --upsample fast
expect 2 "upsample expects auto, plain or block, got 'fast'" -- "${R[@]}" --set upsample=fast
expect 2 "textures: expected on or off" -- "${R[@]}" --textures maybe
expect 2 "vsm-bits: expected 16 or 32" -- "${R[@]}" --shadow vsm --vsm-bits 8
expect 2 "view" -- "${R[@]}" --view bogus
# --upsample's programs give the same image (tests/test_filters.c compares the values).
if "$OBSCURA" render --scene corner --size 22x18 --ao-scale 0.25 --upsample plain --out "$dir/up-plain.png" &&
    "$OBSCURA" render --scene corner --size 22x18 --ao-scale 0.25 --upsample block --out "$dir/up-block.png"; then
    cmp -s "$dir/up-plain.png" "$dir/up-block.png" && ok || bad "--upsample block and plain differ"
else
    bad "render --upsample failed"
fi
rm -f "$dir/up-plain.png" "$dir/up-block.png"
# The --view error and render --help name every view the library has (list --json's, from ob_view_name).
"$OBSCURA" render --scene corner --size 8x8 --out "$dir/out.png" --view bogus 2>"$dir/view.err"
"$OBSCURA" render --help >"$dir/view.help"
if "$OBSCURA" list --json | python3 -c 'import json, re, sys
err, helptext = open(sys.argv[1]).read(), open(sys.argv[2]).read()
views = json.load(sys.stdin)["views"]
miss = [v for v in views if not re.search(r"\b%s\b" % v, err) or not re.search(r"\b%s\b" % v, helptext)]
sys.exit("views missing from the --view error or help: %s (%d views)" % (miss, len(views)) if miss or len(views) < 13 else 0)' \
    "$dir/view.err" "$dir/view.help"; then ok; else bad "--view bogus: $(cat "$dir/view.err")"; fi
expect 2 "out of range" -- "${R[@]}" --set geometry.radius=99
expect 2 "but the filter is geometry" -- "${R[@]}" --set gaussian.sigma=1
expect 2 "no parameter 'nosuch'" -- "${R[@]}" --filter bilateral --set bilateral.nosuch=1
expect 2 "unknown command" -- frobnicate
# "Did you mean ...?" for a slip of the keyboard: commands, options (from the command's own help),
# methods, filters, parameters, scenes (which lists every scene), cameras; none for a stranger.
expect 2 "unknown command 'rendr'; did you mean 'render'\\?" -- rendr
expect 2 "unknown option '--sise'; did you mean '--size'\\?" -- "${R[@]}" --sise 32x24
expect 2 "unknown option '--metods'; did you mean '--methods'\\?" -- compare --metods ssao
expect 2 "unknown method 'vboa'; did you mean 'vbao'\\?" -- "${R[@]}" --method vboa
expect 2 "unknown filter 'creese'; did you mean 'crease'\\?" -- "${R[@]}" --filter creese
expect 2 "no parameter 'radus'; did you mean 'radius'\\?" -- "${R[@]}" --method vbao --set vbao.radus=1
expect 2 "unknown scene 'bunyn'; did you mean 'bunny'\\? \\(built in: cornell, .*named: .*bunny" -- "${R[@]}" --scene bunyn
expect 2 "unknown camera 'fornt' in scene 'sphere-on-plane'; did you mean 'front'\\?" -- "${R[@]}" --scene sphere-on-plane --camera fornt
expect 2 "unknown option '--zzzzzz' \\(see" -- "${R[@]}" --zzzzzz
# Stereo (Belonogov 2018 §5.2): bad modes and values, options that need --stereo or exclude each other.
expect 2 "stereo: expected mirror or single" -- "${R[@]}" --stereo both
expect 2 "ipd: expected a positive number" -- "${R[@]}" --stereo mirror --ipd -0.1
expect 2 "ipd: expected a positive number" -- "${R[@]}" --stereo mirror --ipd abc
expect 2 "convergence: expected a positive number" -- "${R[@]}" --stereo mirror --convergence 0
expect 2 "unknown headset 'rift'" -- "${R[@]}" --stereo mirror --headset rift
expect 2 "need --stereo" -- "${R[@]}" --ipd 0.07
expect 2 "need --stereo" -- "${R[@]}" --headset vive
expect 2 "fov and --headset exclude" -- "${R[@]}" --stereo single --headset vive --fov 70
expect 2 "convergence and --headset exclude" -- "${R[@]}" --stereo mirror --headset vive --convergence 3
expect 2 "stereo and --scaling exclude" -- bench --stereo --scaling --size 32x24
expect 2 "ipd: expected a number > 0" -- bench --stereo --ipd 0 --size 32x24
expect 2 "stereo: expected mirror or single" -- view --stereo left
expect 2 "ipd needs --stereo" -- view --ipd 0.07
# render takes one value of each setting: the list spellings of sheet, compare and bench are not its.
expect 2 "unknown option '--methods'" -- "${R[@]}" --methods ssao,hbao
expect 2 "unknown option '--filters'" -- "${R[@]}" --filters none,geometry
expect 2 "quality: expected low, medium, high or ultra, got 'low,high'" -- "${R[@]}" --quality low,high
expect 2 "eye and --target go together" -- "${R[@]}" --scene corner --eye 1,2,3
expect 2 "ambient env needs --env" -- "${R[@]}" --scene corner --ambient env
expect 3 "cannot read|no such file" -- "${R[@]}" --scene "$dir/missing.obj"
head -c 3000 /dev/urandom >"$dir/corrupt.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 2\nzzz\n' >"$dir/corrupt2.ply"
expect 3 "corrupt.ply" -- "${R[@]}" --scene "$dir/corrupt.ply"
expect 3 "corrupt2.ply" -- "${R[@]}" --scene "$dir/corrupt2.ply"
rm -f "$dir"/corrupt*.ply
echo '{"cameras": [ {"name": "x", "eye": [1, 2]} ]' >"$dir/bad.json"
expect 3 "bad.json" -- "${R[@]}" --scene corner --sidecar "$dir/bad.json"
expect 3 "missing.json" -- "${R[@]}" --scene /usr/share/glmark2/models/bunny.obj --sidecar "$dir/missing.json"
expect 4 "cannot write" -- render --scene corner --size 32x24 --out /nonexistent-dir/x.png
expect 4 "cannot write" -- render --scene corner --size 32x24 --out "$dir/out.png" --ao-out /nonexistent-dir/ao.pfm
# tune: a bad argument is one line, exit 2 and no file; a failing run leaves an existing --out as
# it was; a real run (one pass of 3 steps at 48x36) writes settings that --settings loads.
T=(tune --size 48x36 --method hbao --out "$dir/tuned.json")
expect 2 "no training view" -- "${T[@]}" --params hbao.intensity
expect 2 "leaves the registry" -- "${T[@]}" --params hbao.intensity=0:99 --train corner:diagonal
expect 2 "also a training view" -- "${T[@]}" --params hbao.intensity --train corner:diagonal --validate corner:diagonal
expect 2 "has no parameter 'nosuch'" -- "${T[@]}" --params hbao.nosuch --train corner:diagonal
expect 2 "tune searches numeric and enum" -- tune --method gtao --params gtao.bent_normals --train corner:diagonal --out "$dir/tuned.json"
expect 2 "every option is tried" -- "${T[@]}" --params hbao.noise=0:1 --train corner:diagonal
# The project's check views (scenes/views.json) choose nothing: refused in --train, taken by --check.
expect 2 "train sphere-on-plane:contact is a check view" -- "${T[@]}" --params hbao.intensity --train corner:diagonal,sphere-on-plane:contact
expect 2 "check corner:diagonal is also a training view" -- "${T[@]}" --params hbao.intensity --train corner:diagonal --check corner:diagonal
[ ! -e "$dir/tuned.json" ] && ok || bad "a refused tune left tuned.json"
echo keep >"$dir/keep.json"
"$OBSCURA" tune --size 48x36 --method hbao --params hbao.nosuch --train corner:diagonal --out "$dir/keep.json" 2>/dev/null
[ "$(cat "$dir/keep.json")" = keep ] && ok || bad "a failing tune replaced an existing --out"
if XDG_CACHE_HOME="$dir/cache" "$OBSCURA" tune --size 48x36 --method hbao --params hbao.radius_scale,hbao.noise \
    --train corner:diagonal --validate sphere-on-plane:front --check sphere-on-plane:contact --passes 1 --steps 3 --out "$dir/tuned.json" \
    >"$dir/tune.out" 2>"$dir/tune.err" && python3 - "$dir/tuned.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
assert t["method"] == "hbao", t
assert 0.25 <= t["params"]["radius_scale"] <= 4 and t["params"]["noise"] in ("texture4", "ign"), t["params"]
h = t["tuned"]
# The start is a candidate: tuning never makes the training error worse.
assert h["training"][0]["rmse_tuned"] <= h["training"][0]["rmse_default"] + 1e-9, h
assert h["validation"][0]["view"] == "sphere-on-plane:front" and h["evaluations"] > 2, h
assert h["check"][0]["view"] == "sphere-on-plane:contact" and h["check_rmse_default"] > 0, h
assert abs(h["check_rmse_default"] - h["check"][0]["rmse_default"]) < 1e-12, h
PY
then ok; else bad "tune: $(cat "$dir/tune.err" | tail -2)"; fi
grep -q "mean RMSE" "$dir/tune.out" && ok || bad "tune prints no table"
"$OBSCURA" render --size 48x36 --scene corner --settings "$dir/tuned.json" --out "$dir/tuned.png" 2>"$dir/stderr" &&
    [ -s "$dir/tuned.png" ] && ok || bad "render --settings: $(cat "$dir/stderr")"
rm -f "$dir/tuned.png"
echo '{"method": "hbao", "params": {"intensity": 99}}' >"$dir/bad_settings.json"
expect 2 "bad_settings.json: hbao.intensity = 99 is out of range" -- "${R[@]}" --settings "$dir/bad_settings.json"
echo '{"method": "nosuch", "params": {}}' >"$dir/bad_settings.json"
expect 2 "must name a method" -- "${R[@]}" --settings "$dir/bad_settings.json"
expect 2 "cannot read it|No such file" -- "${R[@]}" --settings "$dir/missing_settings.json"
# --guard PX|F%: whole pixels or a percentage; the enlarged size must fit GL_MAX_TEXTURE_SIZE.
expect 2 "guard: expected pixels >= 0 or a percentage like 10%, got '-4'" -- "${R[@]}" --scene corner --guard -4
expect 2 "guard: expected pixels >= 0 or a percentage like 10%, got 'wide'" -- "${R[@]}" --scene corner --guard wide
expect 2 "guard: expected pixels >= 0 or a percentage like 10%, got '%'" -- "${R[@]}" --scene corner --guard %
expect 2 "guard: expected whole pixels, got '2.5'" -- "${R[@]}" --scene corner --guard 2.5
expect 2 "guard: 150% is more than 100% of the image" -- "${R[@]}" --scene corner --guard 150%
expect 2 "guard: 5000 px is more than 4096" -- "${R[@]}" --scene corner --guard 5000
expect 2 "guard: missing value" -- "${R[@]}" --scene corner --guard
expect 2 "guard expects whole pixels per side, got 'x'" -- "${R[@]}" --scene corner --set guard=x
# llvmpipe's limit is 16384: 8200 + 2 x 4096 is over it. Those targets would take 6 GiB, more than
# the default --max-memory refuses before the GL is asked (tests/test_hostile_memory.sh): a limit
# above them lets the GL's check speak.
expect 2 "guard band 4096 px makes 8200x8 into 16392x8200, above GL_MAX_TEXTURE_SIZE 16384" -- "${R[@]}" \
    --scene corner --gpu sw --guard 4096 --size 8200x8 --max-memory 16G
"$OBSCURA" render --scene corner --size 48x32 --guard 10% --ao-out "$dir/guard.pfm" --out "$dir/guard.png" 2>"$dir/stderr"
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/guard.pfm")
[ "$w $h $c" = "48 32 1" ] && ok || bad "--guard 10%: AO PFM is '$w $h $c' ($(cat "$dir/stderr"))"
rm -f "$dir/guard.pfm" "$dir/guard.png"

# A model without a sidecar stands on a ground the loader added, and the command says so; with a
# sidecar beside it (no "ground") it stands alone and nothing is said.
mkdir -p "$dir/lone"
printf 'v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 1 -1\nv 1 1 -1\nv 1 1 1\nv -1 1 1\nf 1 2 3 4\nf 8 7 6 5\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n' >"$dir/lone/box.obj"
if "$OBSCURA" render --scene "$dir/lone/box.obj" --size 32x24 --method ssao --out "$dir/lone/a.png" >"$dir/stdout" 2>"$dir/stderr" &&
    grep -q "^note: box has no sidecar: it stands on a ground added under it" "$dir/stdout"; then ok
else bad "a model without a sidecar: $(cat "$dir/stdout" "$dir/stderr")"; fi
echo '{"ao_radius": 0.5}' >"$dir/lone/box.obscura.json"
if "$OBSCURA" render --scene "$dir/lone/box.obj" --size 32x24 --method ssao --out "$dir/lone/b.png" >"$dir/stdout" 2>"$dir/stderr" &&
    ! grep -q "no sidecar" "$dir/stdout"; then ok
else bad "a model with a sidecar: $(cat "$dir/stdout" "$dir/stderr")"; fi
rm -rf "$dir/lone"

# --orbit: numbered frames, one per path frame, the camera turning (frames differ), nothing else.
rm -f "$dir"/orbit-*.png
"$OBSCURA" render --scene corner --size 32x24 --method ssao --temporal on --orbit 40 --path-frames 3 \
    --out "$dir/orbit.png" >"$dir/stdout" 2>"$dir/stderr"
if [ $? -eq 0 ] && [ "$(ls "$dir" | grep -c '^orbit-000[0-2]\.png$')" = 3 ] && [ ! -e "$dir/orbit.png" ] &&
    grep -q "3 frames along an orbit of 40 degrees" "$dir/stdout"; then ok
else bad "render --orbit: $(cat "$dir/stderr") $(ls "$dir")"; fi
if [ -f "$dir/orbit-0000.png" ] && awk -v d="$("$IMGCHECK" diff "$dir/orbit-0000.png" "$dir/orbit-0002.png")" 'BEGIN { exit !(d > 1) }'; then ok
else bad "render --orbit: the first and last frames are the same"; fi
rm -f "$dir"/orbit-*.png

# --adaptive: every method but none takes adaptive counts and runs the edge pass, silently.
"$OBSCURA" render --scene corner --size 32x24 --method ssao --adaptive on --timings --out "$dir/adapt.png" \
    >"$dir/stdout" 2>"$dir/stderr"
grep -qE "^edges +[0-9]" "$dir/stdout" && [ ! -s "$dir/stderr" ] && ok || bad "--adaptive with ssao: $(cat "$dir/stderr")"
"$OBSCURA" render --scene corner --size 32x24 --method gtao --adaptive on --timings --out "$dir/adapt.png" \
    >"$dir/stdout" 2>"$dir/stderr"
grep -qE "^edges +[0-9]" "$dir/stdout" && [ ! -s "$dir/stderr" ] && ok || bad "--adaptive with gtao: $(cat "$dir/stderr")"
rm -f "$dir/adapt.png"
# No EGL vendor at all: the context error names what was tried, with its own exit code.
__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent expect 5 "no GPU context" -- "${R[@]}" --scene corner
# --shader-dir (below) that names no directory is refused before anything is rendered.
expect 3 "shader-dir: .*not a readable directory" -- "${R[@]}" --scene corner --shader-dir "$dir/no-such-dir"

# --gpu hw: a hardware device if the machine has one, else exit 5 naming the devices tried.
"$OBSCURA" "${R[@]}" --scene corner --gpu hw -v >/dev/null 2>"$dir/stderr"
code=$?
if [ $code -eq 0 ] || { [ $code -eq 5 ] && grep -q "no GPU context (--gpu hw)" "$dir/stderr"; }; then ok; else bad "--gpu hw: exit $code: $(cat "$dir/stderr")"; fi
rm -f "$dir"/out.png "$dir"/ao.pfm

# Outputs decode to the expected size and values.
if "$OBSCURA" render --scene corner --size 96x64 --gpu sw -v --out "$dir/c.png" --ao-out "$dir/c.pfm" \
    --ao-png "$dir/c_ao.png" --depth-out "$dir/d.pfm" --normal-out "$dir/n.pfm" --timings >"$dir/stdout" 2>"$dir/stderr"; then
    ok
else
    bad "corner render failed: $(cat "$dir/stderr")"
fi
grep -q "llvmpipe" "$dir/stderr" && ok || bad "-v does not print GL_RENDERER: $(cat "$dir/stderr")"
for pass in gbuffer ao filter compose "GPU sum" frame; do
    grep -qE "^$pass +[0-9]+\.[0-9]+" "$dir/stdout" && ok || bad "--timings lacks $pass: $(cat "$dir/stdout")"
done
# --timings warms up 3 frames unless told otherwise.
grep -q "1 frame(s) after 3 warm-up" "$dir/stdout" && ok || bad "--timings without its warm-up: $(cat "$dir/stdout")"
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/c.png")
[ "$w $h $c" = "96 64 4" ] && [ "$hi" -gt 0 ] && ok || bad "final PNG is '$w $h $c $lo $hi'"
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/c_ao.png")
[ "$w $h $c" = "96 64 1" ] && [ "$hi" -eq 255 ] && [ "$lo" -lt 245 ] && ok || bad "AO PNG is '$w $h $c $lo $hi'"
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/c.pfm")
awk -v w="$w" -v h="$h" -v c="$c" -v lo="$lo" -v hi="$hi" 'BEGIN { exit !(w == 96 && h == 64 && c == 1 && lo >= 0 && lo < 0.95 && hi == 1) }' \
    && ok || bad "AO PFM is '$w $h $c $lo $hi'"
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/n.pfm")
awk -v c="$c" -v lo="$lo" -v hi="$hi" 'BEGIN { exit !(c == 3 && lo >= -1.001 && hi <= 1.001) }' && ok || bad "normal PFM is '$c $lo $hi'"
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/d.pfm")
awk -v lo="$lo" -v hi="$hi" 'BEGIN { exit !(lo == 0 && hi > 1) }' && ok || bad "depth PFM is '$lo $hi'"

# --view samples with --adaptive on: a grey image with more than one level.
if "$OBSCURA" render --scene cornell --method ssao --size 96x64 --adaptive on --samples 30 --set ssao.sampling=halton --view samples \
    --out "$dir/samples.png" 2>"$dir/stderr"; then
    read -r w h c lo hi mean < <("$IMGCHECK" "$dir/samples.png")
    [ "$w $h $c" = "96 64 3" ] && [ "$hi" -eq 255 ] && [ "$lo" -lt 128 ] && ok || bad "samples view is '$w $h $c $lo $hi'"
else
    bad "--view samples failed: $(cat "$dir/stderr")"
fi

# The same command twice: identical AO bytes and images.
"$OBSCURA" render --scene corner --size 96x64 --gpu sw --out "$dir/c2.png" --ao-out "$dir/c2.pfm" 2>/dev/null
cmp -s "$dir/c.pfm" "$dir/c2.pfm" && ok || bad "AO differs between two identical runs"
cmp -s "$dir/c.png" "$dir/c2.png" && ok || bad "final image differs between two identical runs"

# --shader-dir: the shaders compiled from a directory. A copy of the source tree's (the build
# tree links share/obscura/shaders beside the binary) gives the built-in bytes; an edited copy (the AO pass
# writes 1 - AO) changes them (a missing directory: above).
cp -rL "$(dirname "$OBSCURA")/share/obscura/shaders" "$dir/sh"
"$OBSCURA" render --scene corner --size 96x64 --gpu sw --shader-dir "$dir/sh" --out "$dir/c3.png" --ao-out "$dir/c3.pfm" 2>"$dir/stderr"
cmp -s "$dir/c.pfm" "$dir/c3.pfm" && ok || bad "--shader-dir with the source shaders: AO differs from the built-in ($(cat "$dir/stderr"))"
sed -i 's/imageStore(ao_out, pix, vec4(ao));/imageStore(ao_out, pix, vec4(1.0 - ao));/' "$dir/sh/visibility_bitmask.glsl"
"$OBSCURA" render --scene corner --size 96x64 --gpu sw --shader-dir "$dir/sh" --out "$dir/c3.png" --ao-out "$dir/c3.pfm" 2>"$dir/stderr"
if cmp -s "$dir/c.pfm" "$dir/c3.pfm"; then bad "--shader-dir with an edited shader: the AO is the built-in's"; else ok; fi
rm -rf "$dir/sh" "$dir"/c3.*

# --view goes through the library's view pass (ob_read_view, as the viewer's ob_present draws it):
# every view decodes at the image size, RGB (final: RGBA as before), and the ao view is exactly the
# grey of --ao-png.
for v in final ao normals depth shadow radiance samples bounce; do
    if "$OBSCURA" render --scene cornell --size 64x48 --view "$v" --out "$dir/view_$v.png" --ao-png "$dir/view_${v}_ao.png" \
        2>"$dir/stderr"; then
        read -r w h c lo hi mean < <("$IMGCHECK" "$dir/view_$v.png")
        want=3
        [ "$v" = final ] && want=4
        [ "$w $h $c" = "64 48 $want" ] && ok || bad "--view $v is '$w $h $c'"
    else
        bad "--view $v failed: $(cat "$dir/stderr")"
    fi
done
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/view_ao.png")
read -r w2 h2 c2 lo2 hi2 mean2 < <("$IMGCHECK" "$dir/view_ao_ao.png")
[ "$lo $hi $mean" = "$lo2 $hi2 $mean2" ] && [ "$lo" -lt 250 ] && ok || bad "ao view '$lo $hi $mean' is not the AO PNG '$lo2 $hi2 $mean2'"
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/view_normals.png")
[ "$hi" -gt "$lo" ] && ok || bad "normals view is flat: $lo..$hi"
rm -f "$dir"/view_*.png

# list --json carries every method with its parameter table, and the built-in scenes.
if "$OBSCURA" list --json >"$dir/list.json" && python3 - "$dir/list.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
names = [m["name"] for m in d["methods"]]
assert "ssao" in names and "none" in names, names
ssao = next(m for m in d["methods"] if m["name"] == "ssao")
p = {x["name"]: x for x in ssao["params"]}
for k in ("radius", "bias", "intensity", "samples"):
    assert k in p, k
    assert p[k]["min"] <= p[k]["default"] <= p[k]["max"], p[k]
scenes = [s["name"] for s in d["builtin_scenes"]]
assert scenes == ["cornell", "corner", "sphere-on-plane", "slab", "bleed", "grille", "vent"], scenes
assert "bunny" in d["named_scenes"] and "fzk-haus" in d["named_scenes"], d["named_scenes"]
PY
then ok; else bad "list --json"; fi
# docs/methods.md and docs/filters.md document every registered method and filter and each of
# their parameters.
for kind in methods filters; do
    if python3 - "$dir/list.json" "$(dirname "$0")/../docs/$kind.md" "$kind" <<'PY'
import json, re, sys
tables = json.load(open(sys.argv[1]))[sys.argv[3]]
doc = open(sys.argv[2]).read()
sections = dict(re.findall(r"^### (\S+)\n(.*?)(?=^### |^## |\Z)", doc, re.S | re.M))
for m in tables:
    assert m["name"] in sections, "no section for " + m["name"]
    for p in m["params"]:
        assert "`%s`" % p["name"] in sections[m["name"]], "%s.%s undocumented" % (m["name"], p["name"])
PY
    then ok; else bad "docs/$kind.md lags the registry"; fi
done
# Mirror: both eyes side by side in every output (2W x H), with the stereo frame's ms and the
# consistency (a small number: the default method's eyes agree to a few hundredths); single: the left
# eye (W x H).
if "$OBSCURA" render --scene cornell --size 48x40 --stereo mirror --ipd 0.05 --out "$dir/sm.png" \
        --ao-out "$dir/sm.pfm" >"$dir/stdout" 2>"$dir/stderr"; then
    read -r w h c lo hi mean < <("$IMGCHECK" "$dir/sm.png")
    [ "$w $h" = "96 40" ] && ok || bad "stereo mirror PNG is ${w}x$h, want 96x40"
    read -r w h c lo hi mean < <("$IMGCHECK" "$dir/sm.pfm")
    [ "$w $h $c" = "96 40 1" ] && ok || bad "stereo mirror AO PFM is '$w $h $c'"
    grep -qE "^stereo frame \(mirror, 48x40 per eye.*left [0-9.]+, right [0-9.]+, both [0-9.]+" "$dir/stdout" && ok \
        || bad "no stereo frame line: $(cat "$dir/stdout")"
    grep -qE "^stereo consistency \(vbao\): mean .* 0\.0[0-9]+ over [0-9.]+ %" "$dir/stdout" && ok \
        || bad "no (or a large) consistency: $(cat "$dir/stdout")"
else
    bad "render --stereo mirror failed: $(cat "$dir/stderr")"
fi
if "$OBSCURA" render --scene cornell --size 48x40 --stereo single --ipd 0.05 --out "$dir/ss.png" >"$dir/stdout" 2>"$dir/stderr"; then
    read -r w h c lo hi mean < <("$IMGCHECK" "$dir/ss.png")
    [ "$w $h" = "48 40" ] && ok || bad "stereo single PNG is ${w}x$h, want 48x40"
else
    bad "render --stereo single failed: $(cat "$dir/stderr")"
fi
# bench --floor (issue 18): the ratio table on stdout and floor_ms / floor_ratio in the JSON for
# every configuration with a sample count (none has none); with --stereo and --scaling too.
B=(bench --scene cornell --cameras front --size 32x24 --frames 2 --warmup 1 --samples 16 --radius 4
   --filter none --shadow none --hdr off --floor)
if "$OBSCURA" "${B[@]}" --methods ssao,hbao --json "$dir/floor.json" >"$dir/stdout" 2>"$dir/stderr"; then
    grep -q "ssao: AO pass / floor" "$dir/stdout" && grep -qE "^N = 16 +[0-9.]+x \([0-9.]+, 16\)" "$dir/stdout" &&
        ok || bad "bench --floor: no ratio column: $(cat "$dir/stdout")"
    python3 - "$dir/floor.json" <<'PY' && ok || bad "bench --floor JSON"
import json, math, sys
d = json.load(open(sys.argv[1]))
assert d["floor"] is True
by = {c["method"]: c for c in d["configurations"]}
assert by["none"]["floor_ms"] is None and by["none"]["floor_ratio"] is None
for m, pattern in (("ssao", "disk"), ("hbao", "rays")):
    c = by[m]
    f = c["floor_ms"]
    assert 0 < f["min"] <= f["median"] <= f["max"] and math.isfinite(f["max"]), (m, f)
    # The median of each frame's AO pass over the floor frame beside it: inside what any frame's
    # ratio can be.
    ao = next(p for p in c["passes"] if p["name"] == "ao")
    lo, hi = ao["min"] / f["max"], ao["max"] / f["min"]
    assert lo * (1 - 1e-9) <= c["floor_ratio"] <= hi * (1 + 1e-9), (m, lo, c["floor_ratio"], hi)
    assert c["floor_taps"] == 16 and c["floor_pattern"] == pattern, (m, c["floor_taps"], c["floor_pattern"])
PY
else
    bad "bench --floor failed: $(cat "$dir/stderr")"
fi
for mode in --stereo --scaling; do
    if "$OBSCURA" "${B[@]}" --methods ssao $mode --sizes 32x24 --json "$dir/floor.json" >"$dir/stdout" 2>"$dir/stderr"; then
        python3 -c 'import json, sys; c = [c for c in json.load(open(sys.argv[1]))["configurations"] if c["method"] == "ssao"]; assert c and all(x["floor_ratio"] > 0 for x in c)' "$dir/floor.json" &&
            ok || bad "bench --floor $mode: no floor_ratio"
    else
        bad "bench --floor $mode failed: $(cat "$dir/stderr")"
    fi
done
"$OBSCURA" list | grep -q "ssao" && ok || bad "list"
# scenes/views.json (the choose and check views): every view is a scene obscura lists with that
# camera (a named scene whose model is missing lists none), in one set only.
if "$OBSCURA" list --json >"$dir/list.json" 2>"$dir/stderr" && python3 - "$dir/list.json" "$(dirname "$0")/../scenes/views.json" <<'PY'
import json, sys
listed = {s["name"]: s["cameras"] for s in json.load(open(sys.argv[1]))["scenes"]}
sets = json.load(open(sys.argv[2]))
assert len(sets["choose"]) >= 16 and len(sets["check"]) >= 14, {k: len(v) for k, v in sets.items() if k != "about"}
assert not set(sets["choose"]) & set(sets["check"]), set(sets["choose"]) & set(sets["check"])
for view in sets["choose"] + sets["check"]:
    scene, camera = view.rsplit(":", 1)
    assert scene in listed, f"{view}: no scene {scene} in obscura list"
    assert camera in listed[scene], f"{view}: {scene} has cameras {listed[scene]}"
PY
then ok; else bad "scenes/views.json names a view obscura does not list: $(cat "$dir/stderr")"; fi
"$OBSCURA" render --help | grep -q -- "--ao-out" && ok || bad "render --help"
"$OBSCURA" list --help | grep -q -- "--json" && ok || bad "list --help"

echo "test_cli: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
