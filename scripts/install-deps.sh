#!/usr/bin/env bash
# Installs the Debian packages Obscura needs, and only the missing ones. Idempotent: a second run
# installs nothing and says so. Uses sudo when not root.
set -euo pipefail

packages=(
    # build
    build-essential cmake pkg-config
    # make test-fuzz and make fuzz: clang with libFuzzer (tests/fuzz). The fuzzer's runtime,
    # libclang_rt.fuzzer, is in libclang-rt-14-dev, which clang only recommends (and this script
    # installs without recommends)
    clang libclang-rt-14-dev
    # make test: the ABI check of libobscura against abi/libobscura.abi (abidw, abidiff)
    abigail-tools
    # GL/EGL: libepoxy loads both; Mesa's EGL gives the device platform and llvmpipe
    libepoxy-dev libegl-dev libegl1 libegl-mesa0 libgl1-mesa-dri libgl-dev
    # libraries
    libassimp-dev libcglm-dev libstb-dev libcjson-dev
    libembree-dev         # Embree 3: the ray-traced AO / bounce reference (src/eval/reference.c)
    # the viewer (obscura view): a GLFW window with a GLX context, Dear ImGui 1.86 (its GLFW and
    # OpenGL 3 backends dlopen libGL.so.1), and Xvfb so its tests run with no display
    libglfw3-dev libimgui-dev libgl1 libglx-mesa0 xvfb xauth
    # the comparison report: charts, and the headless browser its test opens it in
    gnuplot-nox
    chromium
    # make test's Slurm test (tests/test_slurm.sh): a single-node cluster on localhost, started and
    # stopped by the test itself in a scratch folder (no service is enabled or started here)
    munge slurmctld slurmd slurm-client
    # scenes the demo and the tests use
    glmark2-data          # /usr/share/glmark2/models/bunny.obj (Stanford bunny)
    assimp-testmodels     # IFC/AC14-FZK-Haus.ifc, glTF2/2CylinderEngine-glTF-Binary (engine)
    python3-tinyobjloader # /usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj
    openarena-081-maps    # oa_dm1 and oa_shine inside pak1-maps.pk3, each repacked alone into data/
    # (CGAL's armadillo comes from libcgal-demo's .deb, downloaded but not installed: see below)
)

# Data made from the packages' files, in the repository's data/ (git-ignored; a link works),
# written as the caller, not with sudo. Each step runs only when its file is missing, on both
# exits below, so a second run costs a few file tests.
data_dir="$(cd "$(dirname "$0")/.." && pwd)/data"

# Assimp's Q3BSP importer reads only the first map of a .pk3, and pak1-maps.pk3 holds 50 maps:
# copy each map's BSP alone into data/MAP.pk3 for scenes/MAP.obscura.json (oa_dm1, an indoor
# gothic level; oa_shine, an angular tech level of stairs and floating platforms; czest1dm, a castle
# courtyard with an arcade of arches, the project's stand-in for the Sponza atrium). Only the BSP:
# the package has no textures, and the maps' lightmaps are inside the BSP.
oa_pk3_src=/usr/share/games/openarena/baseoa/pak1-maps.pk3
oa_maps=(oa_dm1 oa_shine czest1dm)
repack_oa_maps() {
    local want=()
    for m in "${oa_maps[@]}"; do [ -f "$data_dir/$m.pk3" ] || want+=("$m"); done
    if [ ${#want[@]} -eq 0 ] || [ ! -f "$oa_pk3_src" ]; then return 0; fi
    echo "install-deps: repacking ${want[*]} into $data_dir"
    mkdir -p "$data_dir"
    python3 - "$oa_pk3_src" "$data_dir" "${want[@]}" <<'PY'
import os, sys, zipfile
src, out = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(src) as z:
    for name in sys.argv[3:]:
        dst = os.path.join(out, name + ".pk3")
        with zipfile.ZipFile(dst + ".part", "w", zipfile.ZIP_DEFLATED) as o:
            o.writestr(f"maps/{name}.bsp", z.read(f"maps/{name}.bsp"))
        os.replace(dst + ".part", dst)  # never leave a half-written pk3 that the next run would keep
PY
}

# CGAL's sample meshes ship only inside libcgal-demo, as /usr/share/doc/libcgal-dev/data.tar.gz,
# and installing it would pull libcgal-dev and Boost's headers (21 packages) for one 1.6 MB
# file, into a path that dpkg's path-exclude may skip. So its .deb is downloaded (24 MB, not
# installed) and the mesh unpacked into data/: the Stanford armadillo scan
# (scenes/armadillo.obscura.json). An installed libcgal-demo's tarball is used as it is.
cgal_meshes=(armadillo)
cgal_tarball=/usr/share/doc/libcgal-dev/data.tar.gz
unpack_cgal_meshes() {
    local want=()
    for m in "${cgal_meshes[@]}"; do [ -f "$data_dir/$m.off" ] || want+=("$m"); done
    if [ ${#want[@]} -eq 0 ]; then return 0; fi
    echo "install-deps: unpacking ${want[*]} from CGAL's data (libcgal-demo) into $data_dir"
    mkdir -p "$data_dir"
    local tmp tarball=$cgal_tarball
    tmp=$(mktemp -d)
    if [ ! -f "$tarball" ]; then
        if ! (cd "$tmp" && apt-get download -qq libcgal-demo >"$tmp/log" 2>&1); then
            $sudo apt-get update -qq >/dev/null 2>&1 || true # lists missing or stale
            if ! (cd "$tmp" && apt-get download -qq libcgal-demo >"$tmp/log" 2>&1); then
                echo "install-deps: cannot download the Debian package libcgal-demo:" \
                     "$(grep -m1 '^E:' "$tmp/log" || tail -n1 "$tmp/log")" >&2
                rm -rf "$tmp"
                exit 1
            fi
        fi
        dpkg-deb --fsys-tarfile "$tmp"/libcgal-demo_*.deb | tar -xf - -C "$tmp" ."$cgal_tarball"
        tarball=$tmp$cgal_tarball
    fi
    for m in "${want[@]}"; do
        tar -xzOf "$tarball" "data/meshes/$m.off" >"$data_dir/$m.off.part"
        mv "$data_dir/$m.off.part" "$data_dir/$m.off"
    done
    rm -rf "$tmp"
}

# The check set's models (scenes/views.json, "check"): files inside Debian packages that are
# downloaded, not installed (openfoam-examples is 36 MB of case files around three models;
# ippsample-data a printer test suite around one), each unpacked into data/ under its own name
# (a .gz gunzipped; a map NAME.pk3 from a .pk3 holding many: its maps/NAME.bsp repacked alone, as
# repack_oa_maps does): PACKAGE PATH-IN-PACKAGE NAME. openarena-088-data's pak6-patch088.pk3 (72 MB)
# holds 38 maps; oa_shouse is the inside of a house (roof trusses, beams, stairs under a ceiling).
of_geom=/usr/share/doc/openfoam-examples/examples
deb_models=(
    "openarena-088-data /usr/share/games/openarena/baseoa/pak6-patch088.pk3 oa_shouse.pk3"
    "openfoam-examples $of_geom/resources/geometry/motorBike.obj.gz motorbike.obj"
    "openfoam-examples $of_geom/incompressible/simpleFoam/windAroundBuildings/constant/triSurface/buildings.obj.gz buildings.obj"
    "openfoam-examples $of_geom/resources/geometry/flange.stl.gz flange.stl"
    "ippsample-data /usr/share/ipptool/dodeca_chain_loop.3mf dodeca_chain_loop.3mf"
)
unpack_deb_models() {
    local entry pkg path name debs=""
    for entry in "${deb_models[@]}"; do
        read -r pkg path name <<<"$entry"
        [ -f "$data_dir/$name" ] && continue
        mkdir -p "$data_dir"
        [ -n "$debs" ] || debs=$(mktemp -d) # each package downloaded once, whatever it holds
        if ! ls "$debs/${pkg}"_*.deb >/dev/null 2>&1; then
            echo "install-deps: unpacking models from Debian's $pkg into $data_dir"
            if ! (cd "$debs" && apt-get download -qq "$pkg" >"$debs/log" 2>&1); then
                $sudo apt-get update -qq >/dev/null 2>&1 || true # lists missing or stale
                if ! (cd "$debs" && apt-get download -qq "$pkg" >"$debs/log" 2>&1); then
                    echo "install-deps: cannot download the Debian package $pkg:" \
                         "$(grep -m1 '^E:' "$debs/log" || tail -n1 "$debs/log")" >&2
                    rm -rf "$debs"
                    exit 1
                fi
            fi
        fi
        dpkg-deb --fsys-tarfile "$debs"/"${pkg}"_*.deb | tar -xf - -C "$debs" ."$path"
        if [ ! -f "$debs$path" ]; then echo "install-deps: $pkg holds no $path" >&2; rm -rf "$debs"; exit 1; fi
        case $path in
        *.gz) gzip -dc "$debs$path" >"$data_dir/$name.part" ;;
        *.pk3)
            python3 - "$debs$path" "$data_dir/$name.part" "maps/${name%.pk3}.bsp" <<'PY'
import sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as z, zipfile.ZipFile(sys.argv[2], "w", zipfile.ZIP_DEFLATED) as o:
    o.writestr(sys.argv[3], z.read(sys.argv[3]))
PY
            ;;
        *) cp "$debs$path" "$data_dir/$name.part" ;;
        esac
        mv "$data_dir/$name.part" "$data_dir/$name"
    done
    [ -z "$debs" ] || rm -rf "$debs"
}

make_data() {
    repack_oa_maps
    unpack_cgal_meshes
    unpack_deb_models
}

sudo=""
if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then sudo="sudo"; fi

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
    make_data
    exit 0
fi

if [ "$(id -u)" -ne 0 ] && [ -z "$sudo" ]; then
    echo "install-deps: need root or sudo to install: ${missing[*]}" >&2
    exit 1
fi

export DEBIAN_FRONTEND=noninteractive
echo "install-deps: updating the package lists"
$sudo apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
    # One line naming every package the apt sources lack, not apt's screenful.
    unknown=()
    for p in "${missing[@]}"; do
        apt-cache show "$p" >/dev/null 2>&1 || unknown+=("$p")
    done
    if [ ${#unknown[@]} -gt 0 ]; then
        echo "install-deps: not in the apt sources (Debian 12 'bookworm' main expected):" \
             "${unknown[*]}" >&2
        exit 1
    fi
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
make_data
echo "install-deps: done"
