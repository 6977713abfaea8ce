#!/usr/bin/env bash
# The frame without AO at the exposure of the frame with AO, so that the pair differs by the AO
# alone (issue 20). The automatic key adapts to each frame: on its own, the darker with-AO frame is
# exposed brighter, which lifts the open areas by up to 4 levels and undoes part of the darkening
# in the creases (docs/lighting.md, "What the demo measures").
#
# usage: scripts/noao_frame.sh OBSCURA WITH_AO.log NO_AO.png RENDER_OPTIONS...
#
#   WITH_AO.log     stderr of `obscura render -v ...` for the with-AO frame: its line
#                   "obscura: hdr: log-average L, key K, exposure E (...)"
#   NO_AO.png       where the frame without AO goes
#   RENDER_OPTIONS  the with-AO frame's scene, camera and size (no --method, --out, --key or
#                   --exposure)
#
# The tone map scales by exposure x key / L_avg, with L_avg of the radiance before exposure
# (src/passes/hdr.c). The no-AO frame is rendered once for its own L_avg (L'), then again with
# --key K --exposure E L' / L: its scale is then K E / L, the with-AO frame's.
# Exit 2 with one line on stderr when the log has no exposure line (HDR off, or not -v).
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: scripts/noao_frame.sh OBSCURA WITH_AO.log NO_AO.png RENDER_OPTIONS..." >&2
    exit 2
fi
bin=$1
with_log=$2
out=$3
shift 3
# "L K E" from a render -v log.
exposure_of() {
    sed -n 's/^obscura: hdr: log-average \([^,]*\), key \([^,]*\), exposure \([^ ]*\) .*/\1 \2 \3/p' "$1" | tail -n 1
}
read -r l k e < <(exposure_of "$with_log") || true
if [ -z "${e:-}" ]; then
    echo "noao_frame: $with_log: no 'obscura: hdr: log-average' line (render it with -v and HDR on)" >&2
    exit 2
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! "$bin" render "$@" --method none --out "$out" -v 2>"$log"; then
    cat "$log" >&2
    exit 1
fi
read -r l_none _ _ < <(exposure_of "$log") || true
if [ -z "${l_none:-}" ]; then
    echo "noao_frame: obscura render -v printed no exposure line for the no-AO frame" >&2
    exit 2
fi
scale=$(awk -v e="$e" -v a="$l_none" -v b="$l" 'BEGIN { printf "%.9g", e * a / b }')
"$bin" render "$@" --method none --key "$k" --exposure "$scale" --out "$out"
