#!/usr/bin/env python3
"""Hostile model and environment files for tests/test_hostile_models.sh (issue 19).

Usage: make_corpus.py OUTDIR

Writes every case into OUTDIR (all small: nothing large is committed or generated) and
OUTDIR/cases.tsv, one case per line, tab-separated:

    NAME  EXIT  GROUP  ARG...

EXIT is the documented exit code (README: 3 = missing, unreadable or corrupt model or sidecar),
GROUP is "cpu" (fails before any GL context: runs in the ASan build too) or "gpu" (needs a
context: an environment map, or a positive control that renders), ARG... are the arguments to
`obscura render` after the output options the test adds. The message on stderr must name the
file given as NAME's target, which is the first ARG naming a file in OUTDIR.

OUTDIR/expect.tsv holds, for some cases, a piece of the message they must give: NAME  TEXT.

Other hostile-input harnesses (command lines, outputs, sidecars: tests/test_hostile_outputs.sh)
can add their own cases with add_case() and the same runner.
Python 3 standard library only.
"""
import base64
import io
import json
import os
import struct
import sys
import zipfile

OUT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "hostile-corpus")
CASES = []
EXPECT = []


def path(*parts):
    p = os.path.join(OUT, *parts)
    os.makedirs(os.path.dirname(p), exist_ok=True)
    return p


def write(rel, data):
    p = path(rel)
    with open(p, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    return p


def add_case(name, exit_code, group, *args, expect=None):
    """expect: a piece of the one-line message the case must give (written to expect.tsv)."""
    CASES.append((name, str(exit_code), group) + tuple(str(a) for a in args))
    if expect:
        EXPECT.append((name, expect))


# ---- shared pieces -------------------------------------------------------------------------------

# One triangle: 3 float VEC3 positions (36 bytes) and 3 ushort indices (6 bytes, padded to 8).
TRI_POS = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
TRI_IDX = struct.pack("<3H", 0, 1, 2) + b"\0\0"
TRI_BIN = TRI_POS + TRI_IDX
# A 1x1 PNG (grey), written by hand so no image library is needed.
PNG_1X1 = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAAAAAA6fptVAAAACklEQVR4nGNoAAAAggCBd81ytgAAAABJRU5ErkJggg==")


def gltf(buffer_uri, byte_length=len(TRI_BIN), pos_count=3, image_uri=None, version="2.0"):
    doc = {
        "asset": {"version": version},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": byte_length}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": pos_count, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    if buffer_uri is not None:
        doc["buffers"][0]["uri"] = buffer_uri
    if image_uri is not None:
        doc["images"] = [{"uri": image_uri}]
        doc["textures"] = [{"source": 0}]
        doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        doc["meshes"][0]["primitives"][0]["material"] = 0
    return json.dumps(doc)


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def obj_tri(coords):
    lines = ["v %s %s %s" % c for c in coords]
    return "\n".join(lines) + "\nf 1 2 3\n"


# ---- confinement ---------------------------------------------------------------------------------

# The "secret" files a hostile model reaches for: outside every model directory below, and valid
# data, so that with --allow-external-files the same model imports (the positive control).
SECRET_BIN = write("secret/secret.bin", TRI_BIN)
SECRET_PNG = write("secret/secret.png", PNG_1X1)
write("secret/secret.mtl", "newmtl m\nKd 1 0 0\n")

m = write("models/a/b/buffer_escape.gltf", gltf("../../../secret/secret.bin"))
add_case("gltf_buffer_dotdot", 3, "cpu", "--scene", m)
add_case("gltf_buffer_dotdot_allowed", 0, "gpu", "--scene", m, "--allow-external-files")
m = write("models/buffer_absolute.gltf", gltf(SECRET_BIN))
add_case("gltf_buffer_absolute", 3, "cpu", "--scene", m)
m = write("models/buffer_file_uri.gltf", gltf("file://" + SECRET_BIN))
add_case("gltf_buffer_file_uri", 3, "cpu", "--scene", m)
m = write("models/image_escape.gltf", gltf(data_uri(TRI_BIN), image_uri="../secret/secret.png"))
add_case("gltf_image_dotdot", 3, "cpu", "--scene", m)
m = write("models/image_absolute.gltf", gltf(data_uri(TRI_BIN), image_uri=SECRET_PNG))
add_case("gltf_image_absolute", 3, "cpu", "--scene", m)

tri = obj_tri([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
m = write("models/mtl_escape.obj", "mtllib ../secret/secret.mtl\nusemtl m\n" + tri)
add_case("obj_mtl_dotdot", 3, "cpu", "--scene", m)
write("models/tex/inside.mtl", "newmtl m\nKd 1 1 1\nmap_Kd ../../secret/secret.png\n")
m = write("models/tex/texture_escape.obj", "mtllib inside.mtl\nusemtl m\n" + tri)
add_case("obj_texture_dotdot", 3, "cpu", "--scene", m)
write("models/texabs/inside.mtl", "newmtl m\nKd 1 1 1\nmap_Kd %s\n" % SECRET_PNG)
m = write("models/texabs/texture_absolute.obj", "mtllib inside.mtl\nusemtl m\n" + tri)
add_case("obj_texture_absolute", 3, "cpu", "--scene", m)

# A symlink inside the model's directory that points out of it.
link = path("models/link/secret.bin")
if os.path.lexists(link):
    os.remove(link)
os.symlink(SECRET_BIN, link)
m = write("models/link/symlink_escape.gltf", gltf("secret.bin"))
add_case("gltf_buffer_symlink_escape", 3, "cpu", "--scene", m)
# A FIFO inside the directory: would block a plain open() forever.
fifo = path("models/fifo/buffer.bin")
if not os.path.exists(fifo):
    os.mkfifo(fifo)
m = write("models/fifo/fifo_buffer.gltf", gltf("buffer.bin"))
add_case("gltf_buffer_fifo", 3, "cpu", "--scene", m)
# A device through a symlink inside the directory: outside the tree and not a regular file.
dev = path("models/dev/zero.bin")
if os.path.lexists(dev):
    os.remove(dev)
os.symlink("/dev/zero", dev)
m = write("models/dev/device_buffer.gltf", gltf("zero.bin", byte_length=1 << 30))
add_case("gltf_buffer_dev_zero", 3, "cpu", "--scene", m)
add_case("gltf_buffer_dev_zero_allowed", 3, "cpu", "--scene", m, "--allow-external-files")

# Positive control: the same layout inside the tree renders.
write("models/ok/tri.bin", TRI_BIN)
m = write("models/ok/inside.gltf", gltf("tri.bin"))
add_case("gltf_inside_control", 0, "gpu", "--scene", m)

# ---- bounds before allocation --------------------------------------------------------------------

PLY_HEAD = "ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n" \
           "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
m = write("models/ply_1e9_vertices.ply", PLY_HEAD % ("ascii", 10**9, 1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
add_case("ply_1e9_vertices_ascii", 3, "cpu", "--scene", m)
m = write("models/ply_2e9_faces.ply", (PLY_HEAD % ("binary_little_endian", 3, 2 * 10**9)).encode() + TRI_POS +
          struct.pack("<B3i", 3, 0, 1, 2))
add_case("ply_2e9_faces_binary", 3, "cpu", "--scene", m)
m = write("models/ply_count_overflow.ply", PLY_HEAD % ("ascii", 3, 2**40) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
add_case("ply_count_over_2e32", 3, "cpu", "--scene", m)
m = write("models/ply_truncated.ply", (PLY_HEAD % ("binary_little_endian", 1000, 1)).encode() + TRI_POS)
add_case("ply_truncated_binary", 3, "cpu", "--scene", m)
# A list count in the body that the bytes after it cannot hold: Assimp reserves the list before
# reading it (found by tests/fuzz/fuzz_model.c: 7.8 GB for a 681-byte file). ASCII, binary, and a
# negative count of a signed type (read as huge), each refused before Assimp opens the file.
m = write("models/ply_list_1e9_ascii.ply", PLY_HEAD % ("ascii", 3, 1) + "0 0 0\n1 0 0\n0 1 0\n1000000000 0 1 2\n")
add_case("ply_list_count_1e9_ascii", 3, "cpu", "--scene", m,
         expect="PLY 'face' 0 declares a list of 1000000000 values")
PLY_HEAD_INT = PLY_HEAD.replace("list uchar int", "list int int")
m = write("models/ply_list_1e9_binary.ply", (PLY_HEAD_INT % ("binary_little_endian", 3, 1)).encode() + TRI_POS +
          struct.pack("<i3i", 10**9, 0, 1, 2))
add_case("ply_list_count_1e9_binary", 3, "cpu", "--scene", m,
         expect="PLY 'face' 0 declares a list of 1000000000 values")
m = write("models/ply_list_negative_be.ply", (PLY_HEAD_INT % ("binary_big_endian", 3, 1)).encode() +
          struct.pack(">9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack(">i3i", -3, 0, 1, 2))
add_case("ply_list_count_negative_binary", 3, "cpu", "--scene", m, expect="declares a list of 4294967293 values")
# Found by tests/fuzz/fuzz_model.c: two faces declared, the face line cut into the last vertex's;
# Assimp makes faces with no corner and its Triangulate step aborts the process (ai_assert).
m = write("models/ply_faces_cut_short.ply", (PLY_HEAD % ("ascii", 3, 2)).encode() +
          b"0 0 0\n1 0 0\n0 1 0\xfe\xcc 0 1 2\n")
add_case("ply_faces_cut_short", 3, "cpu", "--scene", m)
# Found by fuzz_model: an OFF face naming vertex 5 of 3; a raw Assimp import crashes (SIGSEGV).
m = write("models/off_bad_index.off", "OFF\n3 1 0\n0 5 4\n1 0 0\n0 1 0\n0 0\n0 1 0\n3 5 ")
add_case("off_face_index_out_of_range", 3, "cpu", "--scene", m)
# Assimp's OFF reader allocates four arrays from the header's counts before reading a line:
# assimp-testmodels' invalid/OutOfMemory.off (3.5e12 vertices) took 16 GB under fuzz_model.
m = write("models/off_count_3e12.off", "OFF\n3535352353358 6 0\n-0.5 -0.5 0.5\n0.5 -0.5 0.5\n")
add_case("off_count_over_2e32", 3, "cpu", "--scene", m, expect="OFF header declares a count over 2^32")
m = write("models/off_1e9_vertices.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
add_case("off_1e9_vertices", 3, "cpu", "--scene", m, expect="OFF header declares 1000000000 vertices and 1 faces")
# Found by fuzz_model: Assimp's PLY reader never returns on this header.
m = write("models/ply_header_loops.ply", b"ply\xff\xff~\xb8N\xf9\xf9$\nformat ascii 1prope" + b"j\0\0\0rty$clr.am\xe0\xd8"
          b"\xf9N\xb8\x7f\0\x000\n1 0 0\n0 1 0\n3 0 1 2\n")
add_case("ply_header_assimp_loops", 3, "cpu", "--scene", m)
m = write("models/ply_no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n" + "comment x\n" * 8000)
add_case("ply_header_never_ends", 3, "cpu", "--scene", m)

m = write("models/gltf_accessor_1e9.gltf", gltf(data_uri(TRI_BIN), pos_count=10**9))
add_case("gltf_accessor_count_1e9", 3, "cpu", "--scene", m)
m = write("models/gltf_buffer_short.gltf", gltf(data_uri(TRI_BIN), byte_length=10**9))
add_case("gltf_buffer_bytelength_1e9", 3, "cpu", "--scene", m)
m = write("models/gltf_not_json.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [")
add_case("gltf_truncated_json", 3, "cpu", "--scene", m)


def glb(json_doc, bin_data, version=2, declared=None):
    j = json_doc.encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<I4s", len(j), b"JSON") + j
    if bin_data is not None:
        b = bin_data + b"\0" * (-len(bin_data) % 4)
        body += struct.pack("<I4s", len(b), b"BIN\0") + b
    total = 12 + len(body)
    return struct.pack("<4sII", b"glTF", version, declared if declared is not None else total) + body


m = write("models/glb_truncated.glb", glb(gltf(None), TRI_BIN)[:60])
add_case("glb_truncated", 3, "cpu", "--scene", m)
m = write("models/glb_bin_short.glb", glb(gltf(None, byte_length=10**8), TRI_BIN))
add_case("glb_bin_chunk_short", 3, "cpu", "--scene", m)
m = write("models/glb_version1.glb", glb(gltf(None, version="1.0"), TRI_BIN, version=1))
add_case("glb_gltf1", 3, "cpu", "--scene", m)

m = write("models/stl_truncated.stl", b"\0" * 80 + struct.pack("<I", 1000) + b"\0" * 50)
add_case("stl_truncated", 3, "cpu", "--scene", m)
m = write("models/garbage.fbx", b"Kaydara FBX Binary  \0\x1a\0" + b"\xff" * 64)
add_case("fbx_garbage", 3, "cpu", "--scene", m)

# Memory ceiling: a legitimate 100x100 grid (60 000 face corners) over a 16 MiB limit. Without
# shadows: --max-memory holds the whole run, and the key light's default 2048^2 map alone is 16 MiB.
n = 100
grid = ["v %d %d 0" % (i, j) for j in range(n + 1) for i in range(n + 1)]
for j in range(n):
    for i in range(n):
        a = j * (n + 1) + i + 1
        grid.append("f %d %d %d\nf %d %d %d" % (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1))
m = write("models/grid.obj", "\n".join(grid) + "\n")
add_case("obj_over_max_memory", 3, "cpu", "--scene", m, "--max-memory", "16M", "--shadow", "none")
add_case("obj_under_max_memory_control", 0, "gpu", "--scene", m, "--max-memory", "1G")

def dae_tri(array_count_attr, p="0 1 2", triangles=1):
    """A one-triangle Collada file; array_count_attr: the float_array's count attribute; p: the
    index list; triangles: the primitive count."""
    return """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="tri" name="tri"><mesh>
      <source id="tri-pos">
        <float_array id="tri-pos-array"%s>0 0 0 1 0 0 0 1 0</float_array>
        <technique_common><accessor source="#tri-pos-array" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
      <triangles count="%d"><input semantic="VERTEX" source="#tri-vtx" offset="0"/><p>%s</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#tri"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
""" % (array_count_attr, triangles, p)


# Found by fuzz_model: a float_array without its count attribute is an empty array to Assimp
# 5.2.5, and its accessor reads 9 values from it: SIGSEGV. A count of 3 reads past it silently.
m = write("models/dae_array_no_count.dae", dae_tri(""))
add_case("dae_array_without_count", 3, "cpu", "--scene", m,
         expect="Collada accessor of 'tri-pos-array' reads 9 values; the array declares 0")
m = write("models/dae_array_short.dae", dae_tri(' count="3"'))
add_case("dae_accessor_past_array", 3, "cpu", "--scene", m, expect="reads 9 values; the array declares 3")
# Found by fuzz_model: a byte in <p> that is no digit stops Assimp's index reader without moving
# it on: an endless loop that grew the index vector to 2.2 GB.
m = write("models/dae_p_letter.dae", dae_tri(' count="9"', p="0 1 2H"))
add_case("dae_index_list_endless", 3, "cpu", "--scene", m, expect="Collada <p> index list holds byte 0x48")
m = write("models/dae_triangles_1e9.dae", dae_tri(' count="9"', triangles=10**9))
add_case("dae_triangle_count_1e9", 3, "cpu", "--scene", m, expect="Collada <triangles> declares a count of 1000000000")
# A million '<' and one '>': the pre-import scan read the rest of the file once per '<' (about
# 10^12 byte reads; it is linear now) before Assimp's XML reader refuses the file.
m = write("models/dae_open_angles.dae", '<?xml version="1.0"?><COLLADA>' + "<" * 1000000 + "></COLLADA>")
add_case("dae_many_open_angles", 3, "cpu", "--scene", m, expect="malformed XML")
m = write("models/dae_ok.dae", dae_tri(' count="9"'))
add_case("dae_control", 0, "gpu", "--scene", m)


# ---- Quake 3 maps (.pk3 = a zip holding maps/NAME.bsp; src/scene/bsp_check.c) --------------------


def bsp(version=46, magic=b"IBSP", lumps=None, face=None, meshverts=(0, 1, 2), tex_name=b"textures/base/floor"):
    """A one-triangle Quake 3 BSP (version 46, 17 lumps): one texture, three vertices, three mesh
    vertices, one polygon face. lumps: {index: (offset, length)} patched into the lump table."""
    tex = tex_name.ljust(64, b"\0")[:64] + struct.pack("<ii", 0, 1)
    verts = b"".join(struct.pack("<3f2f2f3f4B", *p, 0, 0, 0, 0, 0, 0, 1, 255, 255, 255, 255)
                     for p in [(0, 0, 0), (64, 0, 0), (0, 64, 0)])
    f = {"tex": 0, "type": 1, "first": 0, "count": 3}
    f.update(face or {})
    faces = struct.pack("<8i4i12f2i", f["tex"], -1, f["type"], 0, 3, f["first"], f["count"], -1,
                        0, 0, 0, 0, *([0.0] * 11 + [1.0]), 0, 0)
    body = {0: b'{\n"classname" "worldspawn"\n}\n\0', 1: tex, 10: verts,
            11: struct.pack("<%di" % len(meshverts), *meshverts), 13: faces}
    table, data = [], b""
    for k in range(17):
        chunk = body.get(k, b"")
        table.append((8 + 17 * 8 + len(data), len(chunk)))
        data += chunk + b"\0" * (-len(chunk) % 4)
    for k, v in (lumps or {}).items():
        table[k] = v
    return magic + struct.pack("<i", version) + b"".join(struct.pack("<ii", *t) for t in table) + data


def pk3(entries, method=zipfile.ZIP_DEFLATED):
    b = io.BytesIO()
    with zipfile.ZipFile(b, "w", method) as z:
        for name, data in entries:
            z.writestr(name, data)
    return b.getvalue()


def zip_patch(data, field, value, fmt="<I"):
    """Set a field (offset in the header) of the first local and central headers to value."""
    data = bytearray(data)
    for sig, at in ((b"PK\3\4", {"crc": 14, "csize": 18, "usize": 22}),
                    (b"PK\1\2", {"crc": 16, "csize": 20, "usize": 24})):
        i = data.find(sig)
        struct.pack_into(fmt, data, i + at[field], value)
    return bytes(data)


BSP_OK = bsp()
BSP_LEN = len(BSP_OK)
m = write("maps/ok/tri.pk3", pk3([("maps/tri.bsp", BSP_OK)]))
add_case("pk3_control", 0, "gpu", "--scene", m)
# The lump table: past the end, a negative length (Assimp divides it unsigned: ~2^64 elements,
# std::bad_alloc), a mesh-vertex lump that is no whole number of ints (Assimp copies it whole
# into length/4 of them: a heap overflow).
m = write("maps/lump_past_end.pk3", pk3([("maps/m.bsp", bsp(lumps={10: (BSP_LEN - 40, 132)}))]))
add_case("pk3_lump_past_end", 3, "cpu", "--scene", m,
         expect='lump 10 (vertices) spans bytes')
m = write("maps/lump_negative.pk3", pk3([("maps/m.bsp", bsp(lumps={14: (200, -49152)}))]))
add_case("pk3_lump_length_negative", 3, "cpu", "--scene", m,
         expect='lump 14 (lightmaps) has a negative offset or length')
m = write("maps/lump_partial.pk3", pk3([("maps/m.bsp", bsp(lumps={11: (8 + 17 * 8, 6)}))]))
add_case("pk3_mesh_vertices_partial_int", 3, "cpu", "--scene", m,
         expect='lump 11 (mesh vertices) is 6 bytes, not a whole number of 4-byte elements')
# Counts that would need gigabytes: a face whose 2e9 mesh vertices the lump does not hold, and
# 10^5 faces that each use all 2*10^4 mesh vertices (a 2e9-corner mesh, about 600 GB to import)
# from a 10 MB BSP that deflates to 40 KB.
m = write("maps/face_count_2e9.pk3", pk3([("maps/m.bsp", bsp(face={"count": 2 * 10**9}))]))
add_case("pk3_face_count_2e9", 3, "cpu", "--scene", m,
         expect="face 0's mesh vertices 0 to 2000000000 lie outside")
many = bytearray(bsp(meshverts=(0, 1, 2) * 6667, face={"count": 20001}))
at, _ = struct.unpack_from("<ii", many, 8 + 13 * 8)
face = bytes(many[at:at + 104])
struct.pack_into("<ii", many, 8 + 13 * 8, len(many), 104 * 10**5)  # the faces lump: appended
many += face * 10**5
m = write("maps/corners_2e9.pk3", pk3([("maps/m.bsp", bytes(many))]))
add_case("pk3_faces_need_600gb", 3, "cpu", "--scene", m,
         expect='more than the limit of 4.00 GiB (--max-memory)')
m = write("maps/face_texture.pk3", pk3([("maps/m.bsp", bsp(face={"tex": 7}))]))
add_case("pk3_face_texture_out_of_range", 3, "cpu", "--scene", m,
         expect='face 0 names texture 7')
m = write("maps/face_vertex.pk3", pk3([("maps/m.bsp", bsp(meshverts=(0, 1, 2**31 - 1)))]))
add_case("pk3_face_vertex_out_of_range", 3, "cpu", "--scene", m,
         expect='face 0 corner 2 names vertex 2147483647')
m = write("maps/texture_name.pk3", pk3([("maps/m.bsp", bsp(tex_name=b"x" * 64))]))
add_case("pk3_texture_name_unterminated", 3, "cpu", "--scene", m,
         expect="texture 0's name is not terminated")
m = write("maps/bad_magic.pk3", pk3([("maps/m.bsp", bsp(magic=b"RBSP"))]))
add_case("pk3_bsp_magic", 3, "cpu", "--scene", m,
         expect="not a Quake 3 BSP: it begins 'RBSP'")
m = write("maps/bad_version.pk3", pk3([("maps/m.bsp", bsp(version=47))]))
add_case("pk3_bsp_version", 3, "cpu", "--scene", m,
         expect='BSP version 47')
m = write("maps/short_header.pk3", pk3([("maps/m.bsp", b"IBSP" + struct.pack("<i", 46) + b"\0" * 40)]))
add_case("pk3_bsp_header_short", 3, "cpu", "--scene", m,
         expect='too short for a Quake 3 BSP header')
# The zip: an entry claiming 4 GB uncompressed (Assimp allocates the claim before inflating), one
# claiming 100 MB over a 64 MiB --max-memory, one whose data inflates past its claim and one that
# fails its CRC (both end in an ai_assert in Assimp: the process aborts), a truncated archive.
z = pk3([("maps/m.bsp", BSP_OK)])
m = write("maps/claims_4g.pk3", zip_patch(z, "usize", 0xFFFFFF00))
add_case("pk3_entry_claims_4gb", 3, "cpu", "--scene", m,
         expect="zip entry 'maps/m.bsp' claims 4294967040 bytes uncompressed")
m = write("maps/claims_100m.pk3", zip_patch(pk3([("maps/m.bsp", BSP_OK + bytes(100 << 20))]),
                                            "usize", 100 << 20))
add_case("pk3_entry_over_max_memory", 3, "cpu", "--scene", m, "--max-memory", "64M",
         expect='claims 100.0 MiB uncompressed, more than the limit of 64.0 MiB')
m = write("maps/longer_than_claim.pk3", zip_patch(z, "usize", BSP_LEN - 8))
add_case("pk3_entry_longer_than_claimed", 3, "cpu", "--scene", m,
         expect='inflates to more than its declared')
m = write("maps/crc.pk3", zip_patch(z, "crc", 0x12345678))
add_case("pk3_entry_crc", 3, "cpu", "--scene", m,
         expect='fails its CRC check')
m = write("maps/truncated.pk3", bytes(z[:len(z) // 2]) + bytes(z[-22:]))
add_case("pk3_truncated", 3, "cpu", "--scene", m,
         expect='zip end record declares a central directory')
m = write("maps/not_zip.pk3", BSP_OK)
add_case("pk3_not_a_zip", 3, "cpu", "--scene", m,
         expect='not a .pk3 (zip) archive')
m = write("maps/bare.bsp", BSP_OK)
add_case("bsp_bare", 3, "cpu", "--scene", m,
         expect='a bare .bsp')
m = write("maps/bare_past_end.bsp", bsp(lumps={13: (200, 104 * 1000)}))
add_case("bsp_bare_lump_past_end", 3, "cpu", "--scene", m,
         expect='lump 13 (faces) spans bytes 200 to 104200')

# ---- scene sanity --------------------------------------------------------------------------------

for name, coords in [
        ("nan", [(0, 0, 0), ("nan", 0, 0), (0, 1, 0)]),
        ("inf", [(0, 0, 0), ("inf", 0, 0), (0, 1, 0)]),
        ("huge_3e37", [(0, 0, 0), (3e37, 0, 0), (0, 3e37, 0)]),
        ("tiny_1e-30", [(0, 0, 0), (1e-30, 0, 0), (0, 1e-30, 0)]),
        ("far_offset", [(1e9, 0, 0), (1e9 + 1, 0, 0), (1e9, 1, 0)]),
        ("overflow_1e39", [(0, 0, 0), ("1e39", 0, 0), (0, 1, 0)])]:
    m = write("models/coords_%s.obj" % name, obj_tri(coords))
    add_case("obj_coords_" + name, 3, "cpu", "--scene", m)
# A glTF whose node matrix carries the vertices out of range (valid JSON has no NaN).
doc = json.loads(gltf(data_uri(TRI_BIN)))
doc["nodes"][0]["scale"] = [1e38, 1e38, 1e38]
m = write("models/node_scale_1e38.gltf", json.dumps(doc))
add_case("gltf_node_scale_1e38", 3, "cpu", "--scene", m)

# Not a file at all.
os.makedirs(path("models/a_directory.obj"), exist_ok=True)
add_case("model_is_directory", 3, "cpu", "--scene", path("models/a_directory.obj"))
fifo = path("models/model_fifo.obj")
if not os.path.exists(fifo):
    os.mkfifo(fifo)
add_case("model_is_fifo", 3, "cpu", "--scene", fifo)
add_case("model_is_dev_null", 3, "cpu", "--scene", "/dev/null")
m = write("models/empty.obj", "")
add_case("model_empty", 3, "cpu", "--scene", m)

# ---- environment maps (need a GL context: gpu) ---------------------------------------------------


def hdr_header(w, h):
    return ("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w)).encode()


m = write("env/truncated_10000.hdr", hdr_header(10000, 10000) + b"\x02\x02\x27\x10" + b"\x80" * 40)
add_case("hdr_claims_10000x10000", 3, "gpu", "--scene", "corner", "--env", m, "--ambient", "env")
# 64x32 flat, half the pixels missing: passes the size bound, stb would zero-fill the rest.
m = write("env/truncated_half.hdr", hdr_header(64, 32) + b"\x80\x80\x80\x81" * (64 * 16))
add_case("hdr_truncated_half", 3, "gpu", "--scene", "corner", "--env", m, "--ambient", "env")
# Wider than any GL_MAX_TEXTURE_SIZE we meet (llvmpipe 16384, GPUs 16384-32768), yet small:
# one run-length scanline.
w = 40000
line = b"\x02\x02" + struct.pack(">H", w & 0xFFFF)
runs = b""
left = w
while left > 0:
    k = min(127, left)
    runs += bytes([128 + k, 0x80])
    left -= k
m = write("env/too_wide.hdr", hdr_header(w, 1) + line + runs * 4)
add_case("hdr_wider_than_max_texture", 3, "gpu", "--scene", "corner", "--env", m, "--ambient", "env")
m = write("env/not_hdr.hdr", b"P6\n2 2\n255\n" + b"\0" * 12)
add_case("hdr_not_radiance", 3, "gpu", "--scene", "corner", "--env", m, "--ambient", "env")
add_case("hdr_is_directory", 3, "gpu", "--scene", "corner", "--env", path("env"), "--ambient", "env")
m = write("env/ok.hdr", hdr_header(8, 4) + b"\x80\x80\x80\x81" * 32)
add_case("hdr_control", 0, "gpu", "--scene", "corner", "--env", m, "--ambient", "env")

with open(os.path.join(OUT, "cases.tsv"), "w") as f:
    for c in CASES:
        f.write("\t".join(c) + "\n")
with open(os.path.join(OUT, "expect.tsv"), "w") as f:
    for name, text in EXPECT:
        f.write(name + "\t" + text + "\n")
print(len(CASES))
