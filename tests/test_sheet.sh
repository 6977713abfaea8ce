#!/usr/bin/env bash
# `obscura sheet` tests: the sheet decodes to the size its layout gives, has dark label text, the
# AO tile of `none` is all white and that of ssao is not; bad input gives one line, its exit code
# and no file.
set -u
OBSCURA=$1
IMGCHECK=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# The layout constants of app/sheet.c: width 2*TW + 3*PAD, height STRIP + rows*(STRIP + TH) + PAD.
PAD=4
STRIP=24
TW=64
TH=48
sheet_w() { echo $((2 * TW + 3 * PAD)); }
sheet_h() { echo $((STRIP + $1 * (STRIP + TH) + PAD)); }

# expect CODE PATTERN -- ARGS...: exit code, a one-line stderr matching PATTERN, no output left.
expect() {
    local code=$1 pattern=$2
    shift 3
    rm -f "$dir"/out.png
    "$OBSCURA" "$@" >"$dir/stdout" 2>"$dir/stderr"
    local got=$?
    local lines
    lines=$(wc -l <"$dir/stderr")
    if [ "$got" -ne "$code" ]; then bad "obscura $* exited $got, want $code: $(cat "$dir/stderr")"; return; fi
    if [ "$lines" -ne 1 ]; then bad "obscura $* printed $lines lines on stderr: $(cat "$dir/stderr")"; return; fi
    if ! grep -qiE "$pattern" "$dir/stderr"; then bad "obscura $*: '$(cat "$dir/stderr")' lacks /$pattern/"; return; fi
    if ls "$dir" | grep -qE '\.png|tmp-'; then bad "obscura $* left files: $(ls "$dir")"; return; fi
    ok
}

S=(sheet --scene corner --size ${TW}x${TH} --gpu sw --out "$dir/out.png")
expect 2 "unknown method 'nosuch'" -- "${S[@]}" --methods none,nosuch
expect 2 "quality: expected" -- "${S[@]}" --quality extreme
expect 2 "not in --methods" -- "${S[@]}" --methods none --set ssao.radius=0.5
expect 2 "unknown method 'foo'" -- "${S[@]}" --set foo.radius=0.5
expect 2 "METHOD.PARAM=VALUE" -- "${S[@]}" --set radius=0.5
expect 2 "out of range" -- "${S[@]}" --methods ssao --set ssao.radius=-1
expect 2 "listed twice" -- "${S[@]}" --methods ssao,ssao
expect 2 "WIDTHxHEIGHT" -- "${S[@]}" --size 0x4
expect 2 "unknown camera" -- "${S[@]}" --camera nosuch
# No --scene: the default scene of every command, cornell (its help says so).
"$OBSCURA" sheet --help | grep -q "(default cornell)" && ok || bad "sheet --help: no default scene"
expect 2 "unknown scene 'nosuch'" -- sheet --scene nosuch --out "$dir/out.png"
expect 4 "cannot write" -- sheet --scene corner --size ${TW}x${TH} --out /nonexistent-dir/sheet.png
expect 2 "unknown filter 'nosuch'" -- "${S[@]}" --filter nosuch
expect 2 "empty element in 'none,,geometry'" -- "${S[@]}" --filters none,,geometry
expect 2 "eye and --target go together" -- "${S[@]}" --eye 1,1,1

# none and ssao: two rows; stdout names each method with its median AO time ("-" for none, which
# runs no AO pass). A wide radius makes the corner's occlusion plain at this size.
if "$OBSCURA" "${S[@]}" --methods none,ssao --quality low --set ssao.radius=2 >"$dir/stdout" 2>"$dir/stderr"; then ok; else bad "sheet failed: $(cat "$dir/stderr")"; fi
read -r w h c lo hi mean < <("$IMGCHECK" "$dir/out.png")
[ "$w $h" = "$(sheet_w) $(sheet_h 2)" ] && ok || bad "sheet is ${w}x$h, want $(sheet_w)x$(sheet_h 2)"
# Dark label text on the light strips.
[ "${lo:-255}" -lt 60 ] && [ "${hi:-0}" -eq 255 ] && ok || bad "sheet values $lo..$hi: no dark text or no white"
[ "$(wc -l <"$dir/stdout")" -eq 2 ] && grep -qE '^none +ao +- ms$' "$dir/stdout" \
    && grep -qE '^ssao +ao +[0-9]+\.[0-9]+ ms$' "$dir/stdout" && ok || bad "stdout: $(cat "$dir/stdout")"

# Regions of the sheet, decoded with zlib (no PIL): the AO tile of row 0 (none) is all 255; that
# of row 1 (ssao) has occlusion; every strip holds text darker than 60.
if python3 - "$dir/out.png" "$PAD" "$STRIP" "$TW" "$TH" <<'PY'
import struct, sys, zlib
path, pad, strip, tw, th = sys.argv[1], *map(int, sys.argv[2:])
data = open(path, "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n"
pos, idat = 8, b""
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
assert depth == 8 and ctype == 2 and interlace == 0, (depth, ctype, interlace)
bpp, raw, rows, prev = 3, zlib.decompress(idat), [], bytearray(w * 3)
for y in range(h):
    start = y * (w * bpp + 1)
    f, line = raw[start], bytearray(raw[start + 1:start + 1 + w * bpp])
    for i in range(len(line)):
        a = line[i - bpp] if i >= bpp else 0
        b = prev[i]
        c = prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    prev = line
def region(x0, y0, x1, y1):
    return [v for y in range(y0, y1) for v in rows[y][x0 * 3:x1 * 3]]
def tile_y(row):
    return strip + row * (strip + th) + strip
ao_x = 2 * pad + tw
none_ao = region(ao_x, tile_y(0), ao_x + tw, tile_y(0) + th)
assert min(none_ao) == 255, f"none's AO tile is not all white: min {min(none_ao)}"
ssao_ao = region(ao_x, tile_y(1), ao_x + tw, tile_y(1) + th)
assert min(ssao_ao) < 230 and max(ssao_ao) == 255, f"ssao's AO tile is {min(ssao_ao)}..{max(ssao_ao)}"
for name, y0 in (("header", 0), ("none label", strip), ("ssao label", 2 * strip + th)):
    assert min(region(0, y0, w, y0 + strip)) < 60, f"{name} strip has no dark text"
PY
then ok; else bad "sheet regions"; fi

# --filter takes effect: ssao with no filter is another AO tile than with the default geometry
# filter. Lists give a row per combination, labelled with what varies.
"$OBSCURA" "${S[@]}" --methods ssao --quality low --set ssao.radius=2 >/dev/null 2>&1 && mv "$dir/out.png" "$dir/geometry.png"
if "$OBSCURA" "${S[@]}" --methods ssao --quality low --set ssao.radius=2 --filter none >"$dir/stdout" 2>"$dir/stderr"; then
    mv "$dir/out.png" "$dir/none.png"
    read -r d < <("$IMGCHECK" diff "$dir/geometry.png" "$dir/none.png")
    awk -v d="${d:-0}" 'BEGIN { exit !(d > 0) }' && grep -qE '^ssao +ao ' "$dir/stdout" && ok || bad "--filter none changed nothing ($d)"
else
    bad "sheet --filter none failed: $(cat "$dir/stderr")"
fi
rm -f "$dir/geometry.png" "$dir/none.png"
if "$OBSCURA" "${S[@]}" --methods ssao --filters none,geometry --ao-scale 0.5 >"$dir/stdout" 2>"$dir/stderr"; then
    read -r w h c lo hi mean < <("$IMGCHECK" "$dir/out.png")
    [ "$w $h" = "$(sheet_w) $(sheet_h 2)" ] && grep -qE '^ssao, filter none +ao ' "$dir/stdout" \
        && grep -qE '^ssao, filter geometry +ao ' "$dir/stdout" && ok || bad "sheet --filters: ${w}x$h, $(cat "$dir/stdout")"
else
    bad "sheet --filters failed: $(cat "$dir/stderr")"
fi
rm -f "$dir/out.png"

# Default --methods: every registered method, one row each.
count=$("$OBSCURA" list --json | python3 -c 'import json, sys; print(len(json.load(sys.stdin)["methods"]))')
rm -f "$dir/out.png"
TW=32 TH=24
if "$OBSCURA" sheet --scene corner --size ${TW}x${TH} --gpu sw --out "$dir/all.png" >"$dir/stdout" 2>"$dir/stderr"; then
    read -r w h c lo hi mean < <("$IMGCHECK" "$dir/all.png")
    [ "$w $h" = "$(sheet_w) $(sheet_h "$count")" ] && [ "$(wc -l <"$dir/stdout")" -eq "$count" ] && ok \
        || bad "default sheet is ${w}x$h with $(wc -l <"$dir/stdout") stdout lines, want $(sheet_w)x$(sheet_h "$count") and $count"
else
    bad "default sheet failed: $(cat "$dir/stderr")"
fi
"$OBSCURA" sheet --help | grep -q -- "--methods" && ok || bad "sheet --help"

echo "test_sheet: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
