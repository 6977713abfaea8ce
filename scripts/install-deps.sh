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
    # scenes the demo and the tests use
    glmark2-data          # /usr/share/glmark2/models/bunny.obj (Stanford bunny)
    assimp-testmodels     # /usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
    python3-tinyobjloader # /usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj
)

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
echo "install-deps: done"
