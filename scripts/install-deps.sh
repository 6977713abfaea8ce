#!/usr/bin/env bash
# Installs the Debian packages Obscura needs, and only the missing ones. Idempotent: a second run
# installs nothing and says so. Uses sudo when not root.
set -euo pipefail

packages=(
    # build
    build-essential cmake pkg-config
    # GL/EGL: libepoxy loads both; Mesa's EGL gives the device platform and llvmpipe
    libepoxy-dev libegl-dev libegl1 libegl-mesa0 libgl1-mesa-dri libgl-dev
    # libraries
    libassimp-dev libcglm-dev libstb-dev libcjson-dev
    libembree-dev         # Embree 3: the ray-traced AO / bounce reference (src/reference)
    # the viewer (obscura view): a GLFW window with a GLX context, Dear ImGui 1.86 (its GLFW and
    # OpenGL 3 backends dlopen libGL.so.1), and Xvfb so its tests run with no display
    libglfw3-dev libimgui-dev libgl1 libglx-mesa0 xvfb xauth
    # the comparison report: charts, and the headless browser its test opens it in
    gnuplot-nox
    chromium
    # scenes the demo and the tests use
    glmark2-data          # /usr/share/glmark2/models/bunny.obj (Stanford bunny)
    assimp-testmodels     # /usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
    python3-tinyobjloader # /usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj
    openarena-081-maps    # oa_dm1 inside pak1-maps.pk3, repacked alone into data/oa_dm1.pk3
)

# Assimp's Q3BSP importer reads only the first map of a .pk3, and pak1-maps.pk3 holds 50 maps:
# copy oa_dm1's BSP alone into data/oa_dm1.pk3 (git-ignored) for scenes/oa_dm1.obscura.json.
# Only the BSP: the package has no textures, and the map's lightmaps are inside the BSP. Run on
# both exits below, and only when the file is missing; written as the caller, not with sudo.
oa_pk3_src=/usr/share/games/openarena/baseoa/pak1-maps.pk3
oa_pk3="$(cd "$(dirname "$0")/.." && pwd)/data/oa_dm1.pk3"
repack_oa_dm1() {
    if [ -f "$oa_pk3" ] || [ ! -f "$oa_pk3_src" ]; then return 0; fi
    echo "install-deps: repacking oa_dm1 into $oa_pk3"
    mkdir -p "$(dirname "$oa_pk3")"
    python3 - "$oa_pk3_src" "$oa_pk3" <<'PY'
import os, sys, zipfile
src, dst = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(src) as z, zipfile.ZipFile(dst + ".part", "w", zipfile.ZIP_DEFLATED) as o:
    o.writestr("maps/oa_dm1.bsp", z.read("maps/oa_dm1.bsp"))
os.replace(dst + ".part", dst)  # never leave a half-written pk3 that the next run would keep
PY
}

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done

# Debian images often exclude /usr/share/doc from installs (dpkg path-exclude); the Cornell OBJ
# lives there, so check the file itself, not just the package.
cornell=/usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj
reinstall_cornell=0
if [ ${#missing[@]} -eq 0 ] && [ ! -f "$cornell" ]; then reinstall_cornell=1; fi

if [ ${#missing[@]} -eq 0 ] && [ $reinstall_cornell -eq 0 ]; then
    echo "install-deps: all ${#packages[@]} packages present, nothing to install"
    repack_oa_dm1
    exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
        echo "install-deps: need root or sudo to install: ${missing[*]}" >&2
        exit 1
    fi
fi

export DEBIAN_FRONTEND=noninteractive
echo "install-deps: updating the package lists"
$sudo apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
    echo "install-deps: installing ${missing[*]}"
    $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [ ! -f "$cornell" ]; then
    # The package is installed but dpkg skipped its docs: fetch the .deb and unpack the two files.
    echo "install-deps: unpacking the Cornell box OBJ that dpkg's path-exclude skipped"
    tmp=$(mktemp -d)
    (cd "$tmp" && apt-get download -qq python3-tinyobjloader >/dev/null && dpkg-deb -x ./*.deb x)
    $sudo mkdir -p "$(dirname "$cornell")"
    $sudo cp "$tmp"/x/usr/share/doc/python3-tinyobjloader/examples/cornell_box.* "$(dirname "$cornell")"/
    rm -rf "$tmp"
fi
repack_oa_dm1
echo "install-deps: done"
