#!/usr/bin/env python3
"""How much of the AO reaches the final image (issue 20): for one view, compare the final image
with AO against the same frame without AO, and look where the ray-traced reference says the
occlusion is.

usage: ao_visibility.py [--label TEXT] [--min-mean M] [--min-share S] [--contrast] [--max-open L]
                        FINAL.png NOAO.png REF_AO.png

  FINAL.png   the final image with AO (8-bit RGB/RGBA/grey PNG)
  NOAO.png    the same frame with --method none (scripts/noao_frame.sh: at FINAL's exposure)
  REF_AO.png  the reference AO_R as an 8-bit grey PNG (obscura compare writes VIEW/reference_ao.png)

Prints one line:
  LABEL: mean |final - no-AO| X.XX/255; Y.Y % of pixels with AO_R < 0.75 change by > 8 levels
         (mean change Z.Z levels where AO_R < 0.75, W.W where AO_R > 0.95)

The mean is over every colour value of every pixel (sky included, as issue 20 measured it); a
pixel's change is the largest difference of its colour channels. A pixel with AO_R < 0.75 has at
least a quarter of its ambient light blocked (so the AO there should show); AO_R > 0.95 is open.

--min-mean / --min-share: exit 1 (after printing) when the mean or the share is below the value,
--contrast: exit 1 unless the mean change where AO_R < 0.75 is above that where AO_R > 0.95, and
--max-open L: exit 1 when the mean change where AO_R > 0.95 is above L levels (the AO barely
touches those pixels, so a larger change there is the two frames' exposures differing).
Exit 2 on bad usage or an unreadable image (one line on stderr naming the file).

Python 3 standard library only (zlib): the PNGs obscura writes are 8-bit, not interlaced.
"""
import struct
import sys
import zlib

OCCLUDED = 0.75   # AO_R below this: at least a quarter of the hemisphere blocked within R
OPEN = 0.95       # AO_R above this: next to nothing blocked
LEVELS = 8        # a change of more than 8 of 255 levels is plain to see side by side


class PngError(Exception):
    pass


def read_png(path):
    """(width, height, channels, bytes of rows top first). 8-bit grey/grey+alpha/RGB/RGBA only."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise PngError(f"{path}: cannot read: {e.strerror}")
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise PngError(f"{path}: not a PNG file")
    pos, idat, header = 8, [], None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length:
            raise PngError(f"{path}: truncated {kind.decode('latin-1')} chunk")
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + length
    if header is None:
        raise PngError(f"{path}: no IHDR chunk")
    w, h, depth, colour, _, _, interlace = header
    channels = {0: 1, 4: 2, 2: 3, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        raise PngError(f"{path}: only 8-bit grey/RGB(A) non-interlaced PNGs are read "
                       f"(bit depth {depth}, colour type {colour}, interlace {interlace})")
    try:
        raw = zlib.decompress(b"".join(idat))
    except zlib.error as e:
        raise PngError(f"{path}: corrupt image data: {e}")
    stride = w * channels
    if len(raw) != h * (stride + 1):
        raise PngError(f"{path}: image data is {len(raw)} bytes, want {h * (stride + 1)}")
    out = bytearray(h * stride)
    prev = bytearray(stride)
    for y in range(h):
        ftype = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if ftype == 1:
            for i in range(channels, stride):
                line[i] = (line[i] + line[i - channels]) & 255
        elif ftype == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 255
        elif ftype == 3:
            for i in range(stride):
                left = line[i - channels] if i >= channels else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif ftype == 4:
            for i in range(stride):
                a = line[i - channels] if i >= channels else 0
                b = prev[i]
                c = prev[i - channels] if i >= channels else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        elif ftype != 0:
            raise PngError(f"{path}: row {y} has unknown filter type {ftype}")
        out[y * stride:(y + 1) * stride] = line
        prev = line
    return w, h, channels, bytes(out)


def colour(img):
    """Rows of RGB values: grey is repeated, alpha dropped."""
    w, h, c, px = img
    if c >= 3:
        return [px[i:i + 3] for i in range(0, w * h * c, c)]
    return [bytes((px[i],) * 3) for i in range(0, w * h * c, c)]


def measure(final, noao, ref):
    """(mean |final - noao| over colour values, share of occluded pixels changing by > LEVELS,
    mean change where occluded, mean change where open, occluded pixel count)."""
    a, b = colour(final), colour(noao)
    rw, rh, rc, rpx = ref
    total, occluded, changed, occ_sum, open_sum, open_n = 0, 0, 0, 0, 0, 0
    for i, (pa, pb) in enumerate(zip(a, b)):
        d = (abs(pa[0] - pb[0]), abs(pa[1] - pb[1]), abs(pa[2] - pb[2]))
        total += d[0] + d[1] + d[2]
        change = max(d)
        ao = rpx[i * rc] / 255.0
        if ao < OCCLUDED:
            occluded += 1
            occ_sum += change
            changed += change > LEVELS
        elif ao > OPEN:
            open_n += 1
            open_sum += change
    n = len(a)
    return (total / (3.0 * n), 100.0 * changed / occluded if occluded else 0.0,
            occ_sum / occluded if occluded else 0.0, open_sum / open_n if open_n else 0.0, occluded)


def main(argv):
    label, min_mean, min_share, max_open, contrast, files = None, None, None, None, False, []
    it = iter(argv)
    for arg in it:
        if arg in ("--label", "--min-mean", "--min-share", "--max-open"):
            value = next(it, None)
            if value is None:
                print(f"ao_visibility: {arg} needs a value", file=sys.stderr)
                return 2
            if arg == "--label":
                label = value
                continue
            try:
                number = float(value)
            except ValueError:
                print(f"ao_visibility: {arg}: expected a number, got '{value}'", file=sys.stderr)
                return 2
            if arg == "--min-mean":
                min_mean = number
            elif arg == "--min-share":
                min_share = number
            else:
                max_open = number
        elif arg == "--contrast":
            contrast = True
        elif arg.startswith("--"):
            print(f"ao_visibility: unknown option '{arg}'", file=sys.stderr)
            return 2
        else:
            files.append(arg)
    if len(files) != 3:
        print("usage: ao_visibility.py [--label TEXT] [--min-mean M] [--min-share S] [--contrast] "
              "[--max-open L] FINAL.png NOAO.png REF_AO.png", file=sys.stderr)
        return 2
    try:
        images = [read_png(f) for f in files]
    except PngError as e:
        print(f"ao_visibility: {e}", file=sys.stderr)
        return 2
    sizes = {(im[0], im[1]) for im in images}
    if len(sizes) != 1:
        print("ao_visibility: the images differ in size: " +
              ", ".join(f"{f} {im[0]}x{im[1]}" for f, im in zip(files, images)), file=sys.stderr)
        return 2
    mean, share, occ, opn, count = measure(*images)
    print(f"{label or files[0]}: mean |final - no-AO| {mean:.2f}/255; {share:.1f} % of pixels with "
          f"AO_R < {OCCLUDED} change by > {LEVELS} levels (mean change {occ:.1f} levels there over "
          f"{count} px, {opn:.1f} where AO_R > {OPEN})")
    failed = []
    if min_mean is not None and mean < min_mean:
        failed.append(f"mean {mean:.2f} < {min_mean}")
    if min_share is not None and share < min_share:
        failed.append(f"share {share:.1f} % < {min_share} %")
    if max_open is not None and opn > max_open:
        failed.append(f"the open pixels change by {opn:.1f} levels > {max_open} (a different exposure?)")
    if contrast and not occ > opn:
        failed.append(f"the occluded pixels change no more than the open ones ({occ:.1f} <= {opn:.1f})")
    if failed:
        print(f"ao_visibility: {label or files[0]}: " + "; ".join(failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
