#!/usr/bin/env python3
"""Print sidecar camera presets at a Quake 3 map's player spawn points.

Usage: scripts/oa-spawn-cameras.py data/oa_dm1.pk3 [maps/oa_dm1.bsp]

Reads the BSP's entity lump (lump 0: plain text) from the .pk3 and prints one camera per
info_player_deathmatch / info_player_start, ready to paste into scenes/NAME.obscura.json.
Quake is Z-up in units of about an inch; the sidecar's coordinates are in the scene's final
Y-up frame, so (x, y, z) becomes (x, z, -y), as the importer's "up": "z" rotation does.
"""
import json
import math
import re
import struct
import sys
import zipfile

EYE_HEIGHT = 26.0   # Quake 3's DEFAULT_VIEWHEIGHT above the spawn origin
LOOK_DISTANCE = 256.0


def entities(bsp):
    if bsp[:4] != b"IBSP":
        sys.exit("not a Quake 3 BSP")
    offset, length = struct.unpack("<ii", bsp[8:16])
    text = bsp[offset:offset + length].decode("latin-1")
    for body in re.findall(r"\{([^{}]*)\}", text):
        yield dict(re.findall(r'"([^"]*)"\s+"([^"]*)"', body))


def to_y_up(p):
    return [p[0], p[2], -p[1]]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    with zipfile.ZipFile(sys.argv[1]) as pk3:
        name = sys.argv[2] if len(sys.argv) > 2 else next(
            n for n in pk3.namelist() if n.startswith("maps/") and n.endswith(".bsp"))
        bsp = pk3.read(name)
    k = 0
    for ent in entities(bsp):
        if ent.get("classname") not in ("info_player_deathmatch", "info_player_start"):
            continue
        x, y, z = (float(v) for v in ent["origin"].split())
        yaw = math.radians(float(ent.get("angle", "0")))
        eye = (x, y, z + EYE_HEIGHT)
        target = (eye[0] + LOOK_DISTANCE * math.cos(yaw), eye[1] + LOOK_DISTANCE * math.sin(yaw),
                  eye[2])
        k += 1
        cam = {"_comment": f"{ent['classname']} at {ent['origin']}, angle {ent.get('angle', '0')}",
               "name": f"spawn{k}", "eye": [round(v, 1) for v in to_y_up(eye)],
               "target": [round(v, 1) for v in to_y_up(target)], "fov": 75}
        print(json.dumps(cam) + ",")


if __name__ == "__main__":
    main()
