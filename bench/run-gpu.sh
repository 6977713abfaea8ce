#!/usr/bin/env bash
# The benchmark on a lent GPU machine (bench/README.md "On a GPU"): run from the repository root
# there, with .gl carried (scripts/pack-runtime.sh --device fills it: the EGL/GL loader .debs the
# image lacks, runtime.tar.xz with the project's shared libraries, bin/ with obscura and
# libobscura, the FZK-Haus model and the commit). Everything it writes lands in $OUT (or
# bench/results/gpu) and is packed as results.tgz after every step, so a step that runs out of
# time loses only itself.
#   usage: bench/run-gpu.sh [maps|defaults|shaders|h1080|stereo|filters|host|tests|fzk|temporal|deinterleave|miptaps|slicemips|upsample|atrium|all]...
#   (default all; the smoke render always)
# Verified on an NVIDIA H100 through EGL on 2026-11-23 (bench/results/2026-11-23-h100-egl.md).
# shellcheck disable=SC2054 # the commas separate an option's values (--quality low,high), not array elements
set -u
steps=${*:-all}
gpu=${OB_GPU:-hw} # sw only to try the script itself on a machine without a GPU
out=${OUT:-bench/results/gpu}
raw=$out/r
mkdir -p "$raw"
want() { case " $steps " in *" all "* | *" $1 "*) return 0 ;; esac; return 1; }
pack() { tar -czf "$out/results.tgz.part" -C "$raw" . && mv "$out/results.tgz.part" "$out/results.tgz"; }

# The GL/EGL loaders (libglvnd) the device image lacks, unpacked over / as the device notes say.
for f in .gl/*.deb; do [ -e "$f" ] && dpkg -x "$f" /; done
ldconfig
# The project's own shared libraries (assimp, cjson, embree, epoxy, ...) under .gl/lib, the
# binary and libobscura under .gl/bin. LD_LIBRARY_PATH wins over the build's RUNPATH.
if [ -f .gl/runtime.tar.xz ]; then
    tar -xJf .gl/runtime.tar.xz -C .gl
    # The image's own C++ runtime is newer than Debian 12's and the driver may load it too:
    # one copy in the process, the newer one.
    for l in libstdc++.so.6 libgcc_s.so.1; do ldconfig -p | grep -q "$l " && rm -f ".gl/lib/$l"; done
fi
export LD_LIBRARY_PATH=$PWD/.gl/bin:$PWD/.gl/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
B=./build/obscura
[ -x .gl/bin/obscura ] && B=./.gl/bin/obscura
# glvnd finds no NVIDIA EGL vendor on some images: point it at the driver's file.
nv=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -f "$nv" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$nv
# The vendor file names libEGL_nvidia.so.0 bare: the driver's folder must be on the search path.
for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do [ -d "$d" ] && LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$d; done
# The scenes/ sidecars are looked up in the source tree compiled in; here the tree is the cwd.
export OBSCURA_DATA_DIR=$PWD
# FZK-Haus's sidecar names the model where Debian's assimp-testmodels puts it.
ifc=/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
if [ -f .gl/AC14-FZK-Haus.ifc ] && [ ! -f "$ifc" ]; then mkdir -p "${ifc%/*}" && cp .gl/AC14-FZK-Haus.ifc "$ifc"; fi

{
    echo "commit: $(cat .gl/commit 2>/dev/null || git rev-parse HEAD 2>/dev/null || echo unknown)"
    echo "date: $(date -u +%FT%TZ)"
    nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,clocks.mem,power.limit --format=csv 2>&1
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-) x $(nproc)"
    uname -a
} >"$raw/machine.txt"
if ldd "$B" | grep "not found" >>"$raw/machine.txt"; then
    echo "run-gpu: missing libraries (scripts/pack-runtime.sh --device here first)" >&2
    pack; exit 1
fi

# A first render with -v names the EGL device and GL_RENDERER; without a hardware device stop.
if ! timeout 60 "$B" render --scene corner --size 64x48 --gpu "$gpu" -v --out "$raw/smoke.png" >"$raw/smoke.txt" 2>&1; then
    cat "$raw/smoke.txt" >&2
    { cat "$nv"; echo "LD_LIBRARY_PATH=$LD_LIBRARY_PATH"; ldconfig -p | grep -i -E "egl|glvnd"
      LD_DEBUG=libs timeout 60 "$B" render --scene corner --size 64x48 --gpu "$gpu" --out /tmp/x.png 2>&1 | grep -i -E "egl|nvidia|error" | head -60; } >>"$raw/smoke.txt" 2>&1
    pack; exit 1
fi
cat "$raw/smoke.txt"

methods=ssao,hbao,crytek,alchemy,ssdo,ssdo_merged,gtao,vbao,vbgi
# The AO map of every method on the GPU, to hold against the same maps from llvmpipe (the noise
# is a function of the pixel and frame index alone, so the two should agree to float rounding).
if want maps; then
    mkdir -p "$raw/maps"
    for m in ${methods//,/ }; do
        timeout 60 "$B" render --gpu "$gpu" --scene cornell --camera front --size 320x240 --method "$m" --shadow none \
            --out "$raw/maps/$m.png" --ao-out "$raw/maps/$m.pfm" >>"$raw/maps.txt" 2>&1 || echo "maps $m: exit $?" >>"$raw/maps.txt"
    done
    pack
fi

run() {
    local name=$1 limit=$2; shift 2
    timeout "$limit" "$B" bench --gpu "$gpu" "$@" --json "$raw/$name.json" --csv "$raw/$name.csv" >"$raw/$name.txt" 2>"$raw/$name.err"
    echo "$name: exit $? ($SECONDS s)" | tee -a "$raw/steps.txt"
    pack
}
# Every method x preset, 200 measured frames after 20, shadow maps every frame (--full), the
# floor kernel beside each configuration, the default filter: the whole frame as shipped.
sweep=(--full --cameras front --radius 4 --quality low,medium,high,ultra --frames 200 --warmup 20 --floor)
# Issue 47's new defaults for vbao and vbgi, each against the value it replaced, in runs side by
# side on one machine: two depth layers (layers=2: the second_layer pass, one more raster of the
# scene, and the AO pass reading it) against one, and steps joined along a curve (connect=curve:
# one more normal fetch per step) against the chord and against none, and the facet wedge
# (facets=on, off by default: one fetch a pixel, a few operations a slice; the G-buffer writes its
# facet target either way) against none. cornell:front and FZK-Haus's
# stair at 1080p, every preset, shadows off (no pass here reads them); the default run again last,
# so that a drift of the machine during the step shows.
d47=(--size 1920x1080 --radius 4 --quality low,medium,high,ultra --frames 100 --warmup 20 --shadow none --methods vbao,vbgi)
both() { printf -- '--set vbao.%s --set vbgi.%s ' "$1" "$1"; }
for sc in cornell:front fzk-haus:stair; do
    dv=(--scene "${sc%%:*}" --cameras "${sc#*:}" "${d47[@]}")
    want defaults && run "defaults_${sc%%:*}" 60 "${dv[@]}"
    # shellcheck disable=SC2046 # both's words are separate arguments on purpose
    want defaults && run "layers1_${sc%%:*}" 60 "${dv[@]}" $(both layers=1)
    # shellcheck disable=SC2046
    want defaults && run "chord_${sc%%:*}" 60 "${dv[@]}" $(both connect=chord)
    # shellcheck disable=SC2046
    want defaults && run "connect_off_${sc%%:*}" 60 "${dv[@]}" $(both connect=off)
    # shellcheck disable=SC2046
    want defaults && run "facets_on_${sc%%:*}" 60 "${dv[@]}" $(both facets=on)
    # shellcheck disable=SC2046
    want defaults && run "before_${sc%%:*}" 60 "${dv[@]}" $(both layers=1) $(both connect=off)
    want defaults && run "defaults_again_${sc%%:*}" 60 "${dv[@]}"
done
# Shader edits side by side (bench --shader-dir): every copy of shaders/ under .gl/sh/NAME, each
# with its own edit (whoever packs .gl makes them), at the defaults step's settings at high alone,
# beside the built-in shaders, before and after them.
if want shaders && [ -d .gl/sh ]; then
    for sc in cornell:front fzk-haus:stair; do
        hv=(--scene "${sc%%:*}" --cameras "${sc#*:}" "${d47[@]}" --quality high)
        run "builtin_${sc%%:*}" 60 "${hv[@]}"
        for d in .gl/sh/*/; do
            n=$(basename "$d")
            run "sh_${n}_${sc%%:*}" 60 "${hv[@]}" --shader-dir "$d"
        done
        run "builtin_again_${sc%%:*}" 60 "${hv[@]}"
    done
fi
want h1080 && run h1080 150 --scene cornell --size 1920x1080 "${sweep[@]}"
want stereo && run stereo 150 --scene cornell --stereo "${sweep[@]}"
# The filters after gtao high (crease's tiled auto picks the plain program on a GPU; on names
# the tiled one, block the 4x4-pixels-per-invocation one that llvmpipe runs), and the
# half-resolution AO chain.
want filters && run filters 60 --scene cornell --size 1920x1080 "${sweep[@]}" --methods gtao,vbao --quality high \
    --filters none,box4,gaussian,bilateral_sep,crease --ao-scales 1,0.5
want filters && run filters_tiled 40 --scene cornell --size 1920x1080 "${sweep[@]}" --methods gtao --quality high \
    --filters crease --set crease.tiled=on
want filters && run filters_block 40 --scene cornell --size 1920x1080 "${sweep[@]}" --methods gtao --quality high \
    --filters crease --set crease.tiled=block
# Issue 45's host path on a driver that runs the GPU apart from the CPU (bench --host; on llvmpipe
# every call's CPU time is its GPU time): ob_host_ao's input pass, chain and output pass beside the
# frame's chain (the 1.05x target), and its CPU time per call (checks, GL-state save and restore,
# submission): every method at 1080p, then AO scale 1 and 1/2 with temporal accumulation.
want host && run host 170 --host --scene cornell --size 1920x1080 --radius 4 --frames 60 --warmup 10
want host && run host_temporal 90 --host --scene cornell --size 1920x1080 --radius 4 --frames 60 --warmup 10 \
    --methods vbao,gtao --ao-scales 1,0.5 --temporal on
# FZK-Haus's stair (issue 18's view): 36k triangles and its lights' shadow maps every frame.
want fzk && run fzk 200 --scene fzk-haus --size 1920x1080 "${sweep[@]}" --cameras stair --quality high
# Issue 17's cost target: the temporal accumulation pass against the AO pass it follows, in the
# same run, along FZK-Haus's walk (the path its flicker table is measured on), as on 2026-11-23
# (radius 4, shadows off: neither pass reads them). gtao high at AO scale 1, 1/2 and 1/4; then
# the default method and the two whose bounce rides in the same dispatch (vbgi, ssdo).
walk=(--scene fzk-haus --size 1920x1080 --path walk --path-frames 16 --radius 4 --temporal on --frames 200 --warmup 20
    --shadow none)
want temporal && run temporal 120 "${walk[@]}" --methods gtao --quality high --ao-scales 1,0.5,0.25
want temporal && run temporal_methods 120 "${walk[@]}" --methods vbao,vbgi,ssao,ssdo --quality high
# Issue 18's deinterleaved sampling (methods/deinterleave.c): the random-kernel methods' plain
# and deinterleaved programs in two runs of the same sweep, at the suggested radius and twice it
# (where the plain program's taps scatter the most), FZK-Haus's stair at 1080p. llvmpipe gains
# nothing from it (docs/methods.md, "Deinterleaved sampling"): this is where it is measured.
split=(--scene fzk-haus --size 1920x1080 --cameras stair --radius 4,8 --quality low,medium,high,ultra --frames 200
    --warmup 20 --floor --filters none --methods ssao,hbao,crytek,alchemy,ssdo,ssdo_merged)
each() { local p=$1 v=$2 m; for m in ssao hbao crytek alchemy ssdo ssdo_merged; do printf -- '--set %s.%s=%s ' "$m" "$p" "$v"; done; }
di() { each deinterleave "$1"; }
# shellcheck disable=SC2046 # di's words are separate arguments on purpose
want deinterleave && run deinterleave_off 150 "${split[@]}" $(di off)
# shellcheck disable=SC2046
want deinterleave && run deinterleave_on 150 "${split[@]}" $(di on)
# Issue 18's depth MIP taps for the same six (shaders/taps.glsl, `depth_mips`): the same sweep
# again with them on; deinterleave_off is its baseline (ssdo's `packed` is off on a GPU either
# way). On llvmpipe they cost 1.4-1.6x, ssdo's about 1.1x (bench/results/2026-11-23-llvmpipe-mip-taps.md,
# 2026-11-23-llvmpipe-ssdo-mips-temporal-upsample.md): a GPU's cache is what they are for.
dm() { each depth_mips "$1"; }
# shellcheck disable=SC2046
want miptaps && run miptaps_on 150 "${split[@]}" $(dm on)
# Issue 18's gtao-high target (whole effect <= 0.25 ms at 1080p, the AO pass at the floor there):
# the slice methods' depth MIP chain (`depth_mips`, passes/depth_mips.c), which the first run
# found slower for gtao and vbao (0.253 -> 0.322 ms at 36 taps) with the source pixel found by a
# loop of selects per tap; it is now a closed form (shaders/depth_mips_read.glsl). Off and on in
# one run, every preset, the floor beside each, no filter.
sm=(--scene cornell --size 1920x1080 --cameras front --radius 4 --quality low,medium,high,ultra --frames 200 --warmup 20
    --floor --filters none --shadow none --methods gtao,vbao,vbgi)
want slicemips && run slicemips_off 120 "${sm[@]}"
want slicemips && run slicemips_on 120 "${sm[@]}" --set gtao.depth_mips=on --set vbao.depth_mips=on --set vbgi.depth_mips=on
# Issue 18's upsampler programs (docs/filters.md, "Subsampling"): auto takes the plain one on a
# GPU; the block one (one invocation per k x k pixels) was 1.3-2.7x faster on llvmpipe. Both at
# AO scale 1/2 and 1/4 after vbao, vbgi and ssdo (a second value in the same dispatch).
ups=(--scene fzk-haus --size 1920x1080 --cameras stair --methods vbao,vbgi,ssdo --ao-scales 0.5,0.25 --frames 200
    --warmup 20 --shadow none)
want upsample && run upsample_plain 120 "${ups[@]}" --upsample plain
want upsample && run upsample_block 120 "${ups[@]}" --upsample block
# Last: the longest step and no benchmark (a run out of time loses only it).
# The test suite on the GPU (the build tree that scripts/pack-runtime.sh --device packed; the
# repository root must be the same path as here, /work/main on these machines: CTest and the
# tests name absolute paths). The library and GPU suites only: the cli-labelled ones need llvmpipe
# (--gpu sw), gnuplot, chromium or a display and would fail there for that alone.
# Puri 2024's Table 1 on its Sponza stand-in (docs/atrium.md): the four cameras x ssao, hbao,
# alchemy (16 samples each) and none at the thesis's 1920x1080, headless (the viewer's test mode
# needs a display). The map comes from data/ in the ctest tarball.
if want atrium && [ -f .gl/ctest.tar.xz ]; then
    [ -f data/czest1dm.pk3 ] || tar -xJf .gl/ctest.tar.xz data
    run atrium 120 --scene czest1dm --size 1920x1080 --cameras detail,across,closeup,upper \
        --methods ssao,hbao,alchemy,none --samples 16 --set hbao.directions=4 --radius 4 --frames 100 --warmup 10
fi
if want tests && [ -f .gl/ctest.tar.xz ]; then
    tar -xJf .gl/ctest.tar.xz -C / usr 2>/dev/null
    tar -xJf .gl/ctest.tar.xz build data
    timeout 240 ctest --test-dir build -j8 -LE cli --output-on-failure >"$raw/ctest.log" 2>&1
    echo "tests: $(grep 'tests passed' "$raw/ctest.log") ($SECONDS s)" | tee -a "$raw/steps.txt"
    pack
fi
exit 0
