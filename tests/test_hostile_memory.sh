#!/bin/sh
# --max-memory bounds what a file or an option can make a run allocate (issue 44, class 3): small
# hostile inputs written here at test time (a 300 kB PNG declaring 16384 x 16384 texels, which
# decodes to 1 GiB; an OBJ naming it from four materials; a .glb and a .pk3 embedding it) and
# options that ask for gigabytes (--size, --guard, --shadow-size, compare's --path-frames). Each
# refusal must give its exit code, exactly one stderr line naming the file or option and the
# largest items, no output left behind and a small peak resident memory: it happens before the
# texture is decoded or a target is made. The controls (the demo's sizes under --max-memory 512M,
# a texture four materials share, a GL_MAX_TEXTURE_SIZE-wide texture) must still render, and a
# texture wider than GL_MAX_TEXTURE_SIZE must be refused instead of drawing the model black.
#
# usage: test_hostile_memory.sh OBSCURA [cpu|gpu|all]
#   cpu: the refusals (no GL context: the ASan build runs these); gpu: the cases that render.
set -u
BIN=$1
GROUP=${2:-all}
# The ceiling of a refusal's peak memory: every input here is under 1 MB and each refusal comes
# before any decode or allocation it refuses (today's refusals peak at 15-30 MB; before issue
# 44 the same inputs reached gigabytes). A sanitized build keeps shadow memory and a quarantine.
case "$BIN" in
*asan*) CEILING_KB=1048576 LIMIT_AS= ;;
*) CEILING_KB=262144 LIMIT_AS=${OB_MEMORY_TEST_AS:-4000000000} ;;
esac

WORK=$(mktemp -d "${TMPDIR:-/tmp}/obscura_memory_XXXXXX")
trap 'rm -rf "$WORK"' EXIT
IN=$WORK/in
export XDG_CACHE_HOME=$WORK/cache # compare's reference cache

python3 - "$IN" <<'PY' || { echo "FAIL: writing the inputs"; exit 1; }
import io, json, os, struct, sys, zipfile, zlib

OUT = sys.argv[1]


def write(rel, data):
    p = os.path.join(OUT, rel)
    os.makedirs(os.path.dirname(p), exist_ok=True)
    with open(p, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def png(w, h):
    """An 8-bit grey PNG of w x h texels of one value: the first row, then rows of filter 2 ('up',
    all zeros), which deflate about 1000:1: 16384 x 16384 is 300 kB and decodes to 1 GiB RGBA."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    z = zlib.compressobj(9)
    parts = [z.compress(b"\0" + b"\x80" * w)]
    up = b"\2" + b"\0" * w
    parts += [z.compress(up) for _ in range(h - 1)]
    parts.append(z.flush())
    ihdr = struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", b"".join(parts)) + chunk(b"IEND", b"")


def obj(rel, maps):
    """An OBJ with one textured triangle per entry of maps, each its own material naming that file."""
    stem = os.path.splitext(os.path.basename(rel))[0]
    mtl = "".join("newmtl m%d\nKd 1 1 1\nmap_Kd %s\n" % (i, m) for i, m in enumerate(maps))
    lines = ["mtllib %s.mtl" % stem]
    for i in range(len(maps)):
        lines += ["v %d 0 0" % (2 * i), "v %d 0 0" % (2 * i + 1), "v %d 1 0" % (2 * i)]
    lines += ["vt 0 0", "vt 1 0", "vt 0 1", "vn 0 0 1"]
    for i in range(len(maps)):
        a = 3 * i + 1
        lines += ["usemtl m%d" % i, "f %d/1/1 %d/2/1 %d/3/1" % (a, a + 1, a + 2)]
    write(rel, "\n".join(lines) + "\n")
    write(os.path.splitext(rel)[0] + ".mtl", mtl)


def glb(image, materials):
    """A binary glTF: one triangle per material, every material's base colour the one PNG embedded
    in the binary chunk (a bufferView image)."""
    blob, views = bytearray(), []

    def view(data):
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        blob.extend(data + b"\0" * (-len(data) % 4))
        return len(views) - 1
    accessors = [{"bufferView": view(struct.pack("<6f", 0, 0, 1, 0, 0, 1)), "componentType": 5126, "count": 3,
                  "type": "VEC2"},
                 {"bufferView": view(struct.pack("<3H", 0, 1, 2)), "componentType": 5123, "count": 3,
                  "type": "SCALAR"}]
    prims = []
    for i in range(materials):
        pos = struct.pack("<9f", 2 * i, 0, 0, 2 * i + 1, 0, 0, 2 * i, 1, 0)
        accessors.append({"bufferView": view(pos), "componentType": 5126, "count": 3, "type": "VEC3",
                          "min": [2 * i, 0, 0], "max": [2 * i + 1, 1, 0]})
        prims.append({"attributes": {"POSITION": len(accessors) - 1, "TEXCOORD_0": 0}, "indices": 1,
                      "material": i})
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": prims}], "bufferViews": views, "accessors": accessors,
           "images": [{"bufferView": view(image), "mimeType": "image/png"}], "textures": [{"source": 0}],
           "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}] * materials}
    doc["buffers"] = [{"byteLength": len(blob)}]
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(blob), b"BIN\0") + bytes(blob)
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def pk3(texture, image):
    """A Quake 3 map (one triangle, version 46, 17 lumps) whose face names `texture`, zipped with
    the image Assimp then embeds."""
    tex = texture.ljust(64, b"\0") + struct.pack("<ii", 0, 1)
    verts = b"".join(struct.pack("<3f2f2f3f4B", *p, 0, 0, 0, 0, 0, 0, 1, 255, 255, 255, 255)
                     for p in [(0, 0, 0), (64, 0, 0), (0, 64, 0)])
    face = struct.pack("<8i4i12f2i", 0, -1, 1, 0, 3, 0, 3, -1, 0, 0, 0, 0, *([0.0] * 11 + [1.0]), 0, 0)
    lumps = {0: b'{\n"classname" "worldspawn"\n}\n\0', 1: tex, 10: verts, 11: struct.pack("<3i", 0, 1, 2), 13: face}
    table, data = [], b""
    for k in range(17):
        chunk = lumps.get(k, b"")
        table.append((8 + 17 * 8 + len(data), len(chunk)))
        data += chunk + b"\0" * (-len(chunk) % 4)
    bsp = b"IBSP" + struct.pack("<i", 46) + b"".join(struct.pack("<ii", *t) for t in table) + data
    b = io.BytesIO()
    with zipfile.ZipFile(b, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("maps/m.bsp", bsp)
        z.writestr(texture.decode() + ".png", image)
    return b.getvalue()


HUGE = png(16384, 16384)
SMALL = png(64, 64)
write("tex/huge.png", HUGE)
write("tex/huge2.png", HUGE)            # the same bytes, another file: decoded twice
obj("tex/four.obj", ["huge.png"] * 4)   # one file, four materials: decoded once
obj("tex/two_files.obj", ["huge.png", "huge2.png", "huge.png", "huge2.png"])
write("glb/huge.glb", glb(HUGE, 4))
write("maps/huge.pk3", pk3(b"textures/base/huge", HUGE))
write("maps/small.pk3", pk3(b"textures/base/small", SMALL))
write("small/small.png", SMALL)
obj("small/four_small.obj", ["small.png"] * 4)
write("shared/mid.png", png(4096, 4096))  # 64 MiB decoded
obj("shared/shared.obj", ["mid.png"] * 4)
write("wide/wide.png", png(16385, 1))     # one texel wider than llvmpipe's GL_MAX_TEXTURE_SIZE
obj("wide/wide.obj", ["wide.png"])
write("wide/edge.png", png(16384, 1))     # as wide as it: drawn
obj("wide/edge.obj", ["edge.png"])
# An environment map declaring 8192 x 8192 (1.5 GiB at its peak), as long as the smallest run-length
# encoding of that many pixels (4 + 8 x 65 bytes a line): only its header is read.
write("env/big.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 8192\n" + bytes(524 * 8192))
write("lights/lights.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 3 2\nf 1 4 3\n")
write("lights/lights.obscura.json", json.dumps({"lights": [
    {"type": "point", "position": [0.5, 0.8, 0.5 + 0.01 * i]} for i in range(8)]}))
PY

fail=0 ran=0 worst_kb=0 worst_case=""

# run NAME GROUP EXIT CEILING_KB PIECES -- ARGS...: obscura ARGS, with --out/--report under the
# case's directory (OUT in ARGS is replaced by it). PIECES: '|'-separated texts the one stderr
# line must hold (refusals), or '' for a control (exit 0, output written).
run() {
    name=$1 group=$2 expect=$3 ceiling=$4 pieces=$5
    shift 6
    [ "$GROUP" != all ] && [ "$group" != "$GROUP" ] && return 0
    ran=$((ran + 1))
    dir=$WORK/out/$name
    mkdir -p "$dir"
    first=1
    for a in "$@"; do
        [ $first = 1 ] && { set --; first=0; }
        case "$a" in OUT*) a=$dir/result${a#OUT} ;; esac
        set -- "$@" "$a"
    done
    # An address-space limit keeps a regression (or today's code) that does allocate from taking
    # the machine: for the refusals only, which never make a GL context (a GPU driver may map
    # more address space than that on its own).
    limit=""
    [ "$group" = cpu ] && [ -n "$LIMIT_AS" ] && command -v prlimit >/dev/null && limit="prlimit --as=$LIMIT_AS"
    # shellcheck disable=SC2086
    timeout 300 /usr/bin/time -f %M -o "$dir/mem" $limit "$BIN" "$@" >"$dir/stdout" 2>"$dir/stderr" </dev/null
    code=$?
    kb=$(tail -n 1 "$dir/mem" 2>/dev/null)
    case "$kb" in '' | *[!0-9]*) kb=0 ;; esac
    why=""
    [ "$code" = "$expect" ] || why="exit $code, expected $expect"
    if [ -n "$pieces" ]; then
        lines=$(wc -l <"$dir/stderr")
        [ "$lines" = 1 ] || why="$why; $lines stderr lines, expected 1"
        old_ifs=$IFS
        IFS='|'
        for p in $pieces; do
            grep -qF -- "$p" "$dir/stderr" || why="$why; stderr does not say '$p'"
        done
        IFS=$old_ifs
        leftover=$(ls -A "$dir" | grep -v -e '^mem$' -e '^stdout$' -e '^stderr$')
        [ -z "$leftover" ] || why="$why; left behind: $leftover"
    else
        [ -e "$dir/result.png" ] || [ -e "$dir/result/index.html" ] || why="$why; no output written"
    fi
    [ "$kb" -le "$ceiling" ] || why="$why; peak memory ${kb} KB over the ${ceiling} KB ceiling"
    if [ "$kb" -gt "$worst_kb" ]; then worst_kb=$kb worst_case=$name; fi
    if [ -n "$why" ]; then
        fail=$((fail + 1))
        echo "FAIL $name: ${why#; }"
        sed 's/^/    stderr: /' "$dir/stderr" | head -n 5
    else
        printf 'ok   %-28s exit %s %7d KB  %s\n' "$name" "$code" "$kb" "$(head -n 1 "$dir/stderr")"
    fi
}

C=$CEILING_KB
# ---- textures: all of them held against the limit with the rest of the run, before one is decoded
run tex_obj_one_file_x4 cpu 3 "$C" "four.obj|huge.png 16384x16384 x4 materials|more than --max-memory 2.00 GiB" -- \
    render --scene "$IN/tex/four.obj" --max-memory 2G --out OUT.png
run tex_obj_two_files_default cpu 3 "$C" "two_files.obj|huge.png 16384x16384 x2 materials|huge2.png 16384x16384 x2 materials|(the default)" -- \
    render --scene "$IN/tex/two_files.obj" --out OUT.png
run tex_glb_embedded cpu 3 "$C" "huge.glb|embedded image 0 16384x16384 x4 materials|more than --max-memory 512.0 MiB" -- \
    render --scene "$IN/glb/huge.glb" --max-memory 512M --out OUT.png
run tex_pk3_embedded cpu 3 "$C" "huge.pk3|16384x16384|more than --max-memory 512.0 MiB" -- \
    render --scene "$IN/maps/huge.pk3" --max-memory 512M --out OUT.png
# Textures and render targets fit the limit each, not together.
run tex_glb_with_targets cpu 3 "$C" "huge.glb|textures 3.33 GiB|render targets|--size 4096x4096" -- \
    render --scene "$IN/glb/huge.glb" --size 4096x4096 --max-memory 3500M --out OUT.png

# ---- options: refused before any allocation (exit 2), with --max-memory and with its default
run opt_size_512m cpu 2 "$C" "--max-memory 512M|render targets|--size 16384x16384" -- \
    render --scene cornell --size 16384x16384 --max-memory 512M --out OUT.png
run opt_size_default cpu 2 "$C" "--max-memory (default|--size 16384x16384" -- \
    render --scene cornell --size 16384x16384 --out OUT.png
run opt_guard_512m cpu 2 "$C" "--max-memory 512M|--guard 4096" -- \
    render --scene cornell --guard 4096 --max-memory 512M --out OUT.png
run opt_guard_default cpu 2 "$C" "--max-memory (default|--size 4096x4096, --guard 4096" -- \
    render --scene cornell --size 4096x4096 --guard 4096 --out OUT.png
run opt_path_frames_512m cpu 2 "$C" "--max-memory 512M|path frames|--path-frames 10000" -- \
    compare --scene cornell --methods ssao --orbit 90 --path-frames 10000 --max-memory 512M --report OUT
run opt_path_frames_default cpu 2 "$C" "--max-memory (default|path frames|--path-frames 10000" -- \
    compare --scene cornell --methods ssao --orbit 90 --path-frames 10000 --report OUT
run opt_shadow_size_default cpu 2 "$C" "--max-memory (default|shadow maps|--shadow-size 16384" -- \
    render --scene cornell --shadow-size 16384 --light "point pos=0,1,0 intensity=1" --out OUT.png

# Every renderer a command holds at once counts: both eyes of --stereo (one eye's 1.8 GiB fits 2G,
# two do not), each view of tune (four at 2048x2048), bench --scaling's largest --sizes.
run opt_stereo_two_renderers cpu 2 "$C" "--max-memory 2G|2 renderers of --size 4096x4096" -- \
    render --scene cornell --size 4096x4096 --stereo mirror --max-memory 2G --out OUT.png
run opt_tune_renderer_per_view cpu 2 "$C" "--max-memory 1G|4 renderers of --size 2048x2048" -- \
    tune --method ssao --params ssao.intensity --train cornell,corner --validate sphere-on-plane,slab \
    --size 2048x2048 --max-memory 1G --out OUT.json
run opt_bench_scaling_largest cpu 2 "$C" "--max-memory 512M|--sizes up to 3840x2160" -- \
    bench --scene cornell --scaling --max-memory 512M --json OUT.json

# A sidecar's own lights cast shadows too: eight point lights at 4096 (1.73 GB and exit 0 under
# --max-memory 1G before); the estimate before the scene counted the key light's map alone.
run scene_lights_shadow_maps gpu 3 262144 "--max-memory 1G|scene 'lights' has 8 lights|shadow maps take" -- \
    render --scene "$IN/lights/lights.obj" --shadow-size 4096 --size 32x24 --max-memory 1G --out OUT.png

# An environment map counts with the rest of the run, sized from its header (it was decoded
# without a word: 1.5 GiB here).
run env_map_512m cpu 2 "$C" "--max-memory 512M|environment map 1.50 GiB|big.hdr 8192x8192" -- \
    render --scene cornell --ambient env --env "$IN/env/big.hdr" --max-memory 512M --out OUT.png

# ---- what renders: the demo's sizes under a small limit, a texture four materials share (decoded
# once: about 300 MB at the peak; four decodes were 760 MB), the widest texture the GL takes, and
# one texel more, refused (it drew the model black).
run control_render_512m gpu 0 1048576 "" -- render --scene cornell --size 640x480 --max-memory 512M --out OUT.png
run control_render_default gpu 0 1048576 "" -- render --scene cornell --size 640x480 --out OUT.png
run control_textured_512m gpu 0 1048576 "" -- \
    render --scene "$IN/small/four_small.obj" --size 640x480 --max-memory 512M --out OUT.png
run control_pk3_512m gpu 0 1048576 "" -- render --scene "$IN/maps/small.pk3" --max-memory 512M --out OUT.png
run control_compare_path_512m gpu 0 1048576 "" -- \
    compare --scene cornell --size 320x240 --methods ssao --orbit 30 --path-frames 3 --spp 4 --no-cache \
    --max-memory 512M --report OUT
run shared_texture_decoded_once gpu 0 460800 "" -- \
    render --scene "$IN/shared/shared.obj" --max-memory 400M --out OUT.png
run texture_at_max_size gpu 0 1048576 "" -- render --gpu sw --scene "$IN/wide/edge.obj" --out OUT.png
run texture_over_max_size gpu 3 1048576 "'wide.png'|16385x1|GL_MAX_TEXTURE_SIZE 16384" -- \
    render --gpu sw --scene "$IN/wide/wide.obj" --out OUT.png

echo "hostile memory: $ran cases, $fail failed; worst peak memory ${worst_kb} KB ($worst_case)"
[ "$ran" -gt 0 ] || { echo "FAIL: no cases ran"; exit 1; }
[ "$fail" = 0 ]
