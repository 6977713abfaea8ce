#!/usr/bin/env python3
"""make demo's front page: OUT/index.html shows every shot as "without AO | with AO | AO map",
the shot whose AO changes its final image most first, so that the first AO image one opens is the
clearest one (issue 48: the bunny alone on its floor, which sorts first in a file listing, changed
by 0.37/255).

usage: demo_index.py OUT_DIR SHOT...

For each SHOT, OUT_DIR holds SHOT.png (with AO), SHOT_noao.png (the same frame without AO at the
same exposure, scripts/noao_frame.sh) and SHOT_sidebyside.png. The order is by the mean
|final - no-AO| over every colour value (scripts/ao_visibility.py's measure), measured here on this
run's images, never fixed in advance. Prints one line per shot, strongest first. OUT_DIR/index.html
is written whole (a temporary file renamed) or not at all. Exit 2 on bad usage or an unreadable
image, with one line on stderr naming the file. Python 3 standard library only."""
import html
import os
import sys

from ao_visibility import PngError, colour, read_png


def mean_change(final_path, noao_path):
    """Mean |final - no-AO| over every colour value, in 8-bit levels."""
    a, b = read_png(final_path), read_png(noao_path)
    if (a[0], a[1]) != (b[0], b[1]):
        raise PngError(f"{noao_path}: {b[0]}x{b[1]}, but {final_path} is {a[0]}x{a[1]}")
    total = 0
    pa, pb = colour(a), colour(b)
    for x, y in zip(pa, pb):
        total += abs(x[0] - y[0]) + abs(x[1] - y[1]) + abs(x[2] - y[2])
    return total / (3.0 * len(pa))


def main(argv):
    if len(argv) < 2:
        print("usage: demo_index.py OUT_DIR SHOT...", file=sys.stderr)
        return 2
    out, shots = argv[0], argv[1:]
    rows = []
    try:
        for shot in shots:
            rows.append((mean_change(os.path.join(out, shot + ".png"), os.path.join(out, shot + "_noao.png")), shot))
    except PngError as e:
        print(f"demo_index: {e}", file=sys.stderr)
        return 2
    rows.sort(key=lambda r: -r[0])
    parts = ["<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>obscura: make demo</title>\n"
             "<style>body{font-family:sans-serif;margin:1.5em;max-width:1400px}img{max-width:100%;"
             "display:block}figure{margin:0 0 2em 0}figcaption{margin:.3em 0}.n{color:#555}</style></head><body>\n"
             "<h1>make demo</h1>\n<p>Each shot: <b>without AO | with AO | the AO map</b> (white = open, black = "
             "occluded), both frames at the with-AO frame's exposure, so that they differ by the AO alone. The shot "
             "whose AO changes its image most comes first; the number is the mean change of the final image, in "
             "8-bit levels, measured on this run's images. Every method against the ray-traced ground truth: "
             "<a href=\"report/index.html\">report/index.html</a>; every method side by side: the "
             "<code>sheet_*.png</code> contact sheets.</p>\n"]
    for mean, shot in rows:
        name = html.escape(shot)
        parts.append(f"<figure><figcaption><b>{name}</b> <span class=\"n\">mean |with AO &minus; without| "
                     f"{mean:.2f}/255</span></figcaption><a href=\"{name}_sidebyside.png\">"
                     f"<img src=\"{name}_sidebyside.png\" alt=\"{name}: without AO, with AO, the AO map\"></a>"
                     f"</figure>\n")
    parts.append("</body></html>\n")
    path = os.path.join(out, "index.html")
    tmp = path + ".tmp-demo"
    try:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write("".join(parts))
        os.replace(tmp, path)
    except OSError as e:
        print(f"demo_index: {path}: cannot write: {e.strerror}", file=sys.stderr)
        try:
            os.remove(tmp)
        except OSError:
            pass
        return 2
    for mean, shot in rows:
        print(f"{shot}: mean |with AO - without| {mean:.2f}/255")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
