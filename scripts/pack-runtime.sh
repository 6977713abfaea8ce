#!/usr/bin/env bash
# Pack what build/obscura needs at run time for a machine that lacks the project's Debian
# packages (the lent GPU machine, see bench/README.md): every shared library `ldd` resolves,
# except glibc's own (libc, libm, libdl, libpthread, librt, ld-linux: the target has them and they
# must match its loader), as .gl/runtime.tar.xz. Compressed because the working tree that travels
# to the device is capped at 64 MiB and libembree3 alone is ~42 MiB.
# On the device: tar -xJf .gl/runtime.tar.xz -C .gl && export LD_LIBRARY_PATH=$PWD/.gl/lib
# (bench/run-gpu.sh does both).
#   usage: scripts/pack-runtime.sh [--device] [BINARY]
# --device also puts there what the lent machine lacks beside the libraries: the EGL/GL loader
# .debs (libglvnd, downloaded with apt-get), bin/ (obscura and libobscura, found there through
# LD_LIBRARY_PATH as the build's RUNPATH is this machine's path), FZK-Haus's model and the commit.
set -euo pipefail
device=false
if [ "${1:-}" = --device ]; then device=true; shift; fi
BIN=${1:-build/obscura}
cd "$(dirname "$0")/.."
[ -x "$BIN" ] || { echo "pack-runtime: $BIN not built (run make)" >&2; exit 1; }
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/lib" .gl
ldd "$BIN" | awk '/=> \// {print $3}' | while read -r lib; do
    case "$(basename "$lib")" in
    libc.so.* | libm.so.* | libdl.so.* | libpthread.so.* | librt.so.* | ld-linux*) continue ;;
    esac
    cp -L "$lib" "$stage/lib/"
done
# .gl/ is machine-specific and large: it must never be committed.
git check-ignore -q .gl/ 2>/dev/null || echo "pack-runtime: .gl/ is not ignored: echo /.gl/ >>.git/info/exclude" >&2
tar -cJf .gl/runtime.tar.xz -C "$stage" lib
echo "pack-runtime: $(ls "$stage/lib" | wc -l) libraries -> .gl/runtime.tar.xz ($(du -h .gl/runtime.tar.xz | cut -f1))"
if $device; then
    rm -rf .gl/lib # an unpacked copy from an earlier try here would travel too (64 MiB cap)
    o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
    mkdir -p /tmp/amd64/partial .gl/bin
    apt-get $o update -qq
    (cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
    cp -L "$BIN" "$(dirname "$BIN")"/libobscura.so.0.* "$(dirname "$BIN")"/libobscura-eval.so.0.* .gl/bin/
    ifc=/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
    [ -f "$ifc" ] && cp "$ifc" .gl/
    # The test suite as built here (bench/run-gpu.sh tests): the build tree without its objects,
    # data/ and the Debian models the scenes name (absent there).
    models=(/usr/share/glmark2/models/bunny.obj /usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj
        /usr/share/doc/python3-tinyobjloader/examples/cornell_box.mtl
        /usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb)
    present=()
    for m in "${models[@]}"; do [ -f "$m" ] && present+=("$m"); done
    tar -cJf .gl/ctest.tar.xz --exclude=CMakeFiles --exclude='*.a' --exclude=Testing --exclude=build/tests/screenshots \
        --exclude=build/packages \
        "$(dirname "$BIN")" data "${present[@]}" 2>/dev/null
    git rev-parse HEAD >.gl/commit
    git diff --quiet HEAD || echo "(working tree differs from HEAD)" >>.gl/commit
    echo "pack-runtime: .gl ready for bench/run-gpu.sh ($(du -sh .gl | cut -f1); carry .gl)"
fi
