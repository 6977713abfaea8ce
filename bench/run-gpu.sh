#!/usr/bin/env bash
# The benchmark on a lent GPU machine (see bench/README.md and the device notes): run from the
# repository root there, with .gl (the EGL/GL loader .debs and runtime.tar.xz from
# scripts/pack-runtime.sh) and build/obscura carried. Results go to $OUT (or bench/results/gpu).
#   usage: bench/run-gpu.sh [quick|sweep|stereo|scaling|all]   (default all)
# NOT YET VERIFIED on a GPU: no machine was lent to the task that wrote it.
set -u
what=${1:-all}
out=${OUT:-bench/results/gpu}
mkdir -p "$out"
# The GL/EGL loaders (libglvnd) the device image lacks: unpacked over / as the device notes say.
for f in .gl/*.deb; do [ -e "$f" ] && dpkg -x "$f" /; done
ldconfig
# The project's own runtime libraries (assimp, cjson, stb, embree, epoxy, ...) stay under .gl/lib.
if [ -f .gl/runtime.tar.xz ]; then
    tar -xJf .gl/runtime.tar.xz -C .gl
    export LD_LIBRARY_PATH=$PWD/.gl/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
fi
# glvnd finds no NVIDIA EGL vendor on some images: point it at the driver's file.
nv=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -f "$nv" ] && ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
    export __EGL_VENDOR_LIBRARY_FILENAMES=$nv
fi
# The scenes/ sidecars are looked up in the source tree compiled in; here the tree is the cwd.
export OBSCURA_DATA_DIR=$PWD
B=./build/obscura
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv >"$out/nvidia-smi.csv" 2>&1 || true
ldd "$B" | grep "not found" && { echo "run-gpu: missing libraries (run scripts/pack-runtime.sh here first)" >&2; exit 1; }
"$B" render --scene corner --size 64x48 --gpu hw -v --out "$out/smoke.png" || exit 1
run() { local name=$1; shift; "$B" bench --gpu hw -v "$@" --json "$out/$name.json" --csv "$out/$name.csv" >"$out/$name.txt" 2>"$out/$name.err"; echo "$name: exit $?"; }
case $what in quick | all) run quick --scene cornell --cameras front --frames 10 --warmup 2 ;; esac
case $what in sweep | all) run sweep --full --scene cornell --size 800x600 --frames 50 --warmup 5 ;; esac
case $what in stereo | all) run stereo --full --scene cornell --stereo --frames 50 --warmup 5 ;; esac
case $what in scaling | all) run scaling --scene cornell --cameras front --scaling --frames 50 --warmup 5 ;; esac
exit 0
