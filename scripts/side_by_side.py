#!/usr/bin/env python3
"""Put PNGs of one size side by side, left to right, 4 px of mid grey between them (make demo's
"without AO | with AO | AO map" strips).

usage: side_by_side.py OUT.png IN.png IN.png [IN.png ...]

Grey inputs become grey RGB, alpha is dropped. Exit 2 on bad usage, an unreadable input or inputs
of different sizes (one line on stderr naming the file); OUT is written whole or not at all.
Python 3 standard library only."""
import os
import struct
import sys
import zlib

from ao_visibility import PngError, colour, read_png

GAP = 4  # mid grey: visible against the white of an AO map and the dark of a final image


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


def main(argv):
    if len(argv) < 3:
        print("usage: side_by_side.py OUT.png IN.png IN.png [IN.png ...]", file=sys.stderr)
        return 2
    out, inputs = argv[0], argv[1:]
    try:
        images = [read_png(f) for f in inputs]
    except PngError as e:
        print(f"side_by_side: {e}", file=sys.stderr)
        return 2
    w, h = images[0][0], images[0][1]
    for f, im in zip(inputs, images):
        if (im[0], im[1]) != (w, h):
            print(f"side_by_side: {f} is {im[0]}x{im[1]}, {inputs[0]} is {w}x{h}", file=sys.stderr)
            return 2
    pixels = [colour(im) for im in images]
    gap = b"\x80" * (3 * GAP)
    rows = []
    for y in range(h):
        row = [b"\x00"]
        for k, px in enumerate(pixels):
            if k:
                row.append(gap)
            row.append(b"".join(px[y * w:(y + 1) * w]))
        rows.append(b"".join(row))
    width = len(images) * w + (len(images) - 1) * GAP
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, h, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(b"".join(rows), 6)) + chunk(b"IEND", b""))
    tmp = f"{out}.tmp-{os.getpid()}"
    try:
        with open(tmp, "wb") as f:
            f.write(png)
        os.replace(tmp, out)
    except OSError as e:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        print(f"side_by_side: cannot write {out}: {e.strerror}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
