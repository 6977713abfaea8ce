#!/usr/bin/env bash
# make package (issue 46, items 1 and 4): CPack's five Debian packages from this build, their
# dependencies (dpkg-shlibdeps for the libraries they link, the library packages at the same
# version for the others, the -dev packages the .pc files' Requires.private name), their contents;
# examples/embed built and run against nothing but the core's two packages (libobscura,
# libobscura-dev) unpacked into a scratch root, through the CMake package and through pkg-config;
# examples/host built against all five in a second root (it writes images with libobscura-eval).
# usage: test_package.sh BUILD_DIR SOURCE_DIR CMAKE CC
set -uo pipefail
build=$1 src=$2 cmake=$3 cc=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }
ok() { :; }

ver() { sed -n "s/^#define OB_VERSION_$1 \([0-9]*\)$/\1/p" "$src/include/obscura/obscura.h"; }
version=$(ver MAJOR).$(ver MINOR).$(ver PATCH)
if [ "$(ver MAJOR)" -eq 0 ]; then suffix=0.$(ver MINOR); else suffix=$(ver MAJOR); fi
runtime=libobscura$suffix evalrt=libobscura-eval$suffix soname=libobscura.so.$suffix evalso=libobscura-eval.so.$suffix

cpack=$(dirname "$cmake")/cpack
if ! (cd "$build" && "$cpack" -G DEB -B "$tmp/pk" --config CPackConfig.cmake >"$tmp/cpack.log" 2>&1); then
    tail -20 "$tmp/cpack.log"; echo "package: cpack failed"; exit 1
fi
# The core's packages into core/, all five into root/.
for p in "$runtime" libobscura-dev "$evalrt" libobscura-eval-dev obscura; do
    deb=$tmp/pk/${p}_${version}_amd64.deb
    [ -f "$deb" ] || { bad "no $deb (made: $(ls "$tmp/pk"))"; continue; }
    dpkg-deb -x "$deb" "$tmp/root" || bad "dpkg-deb -x $deb"
    case $p in "$runtime" | libobscura-dev) dpkg-deb -x "$deb" "$tmp/core" || bad "dpkg-deb -x $deb" ;; esac
    deps=$(dpkg-deb -f "$deb" Depends)
    echo "  $p $version: Depends: $deps"
    case $p in
    "$runtime") # the core: OpenGL's loader and the C library, none of the lab
        [[ $deps == *"libc6 (>="* && $deps == *libepoxy0* ]] || bad "$p: no dpkg-shlibdeps dependencies ($deps)"
        for lab in assimp embree cjson stb zlib; do [[ $deps != *$lab* ]] || bad "$p depends on $lab: $deps"; done ;;
    libobscura-dev)
        [[ $deps == *"$runtime (= $version)"* && $deps == *libepoxy-dev* ]] || bad "$p: $deps"
        for lab in assimp embree cjson stb zlib; do [[ $deps != *$lab* ]] || bad "$p depends on $lab: $deps"; done ;;
    "$evalrt") [[ $deps == *"$runtime (= $version)"* && $deps == *libassimp* && $deps == *libembree* ]] ||
                   bad "$p: no dependency on $runtime (= $version) or the lab ($deps)" ;;
    libobscura-eval-dev) [[ $deps == *"$evalrt (= $version)"* && $deps == *"libobscura-dev (= $version)"* ]] ||
                             bad "$p: $deps" ;;
    obscura) [[ $deps == *"$runtime (= $version)"* && $deps == *"$evalrt (= $version)"* ]] || bad "$p: $deps" ;;
    esac
done
lib=$tmp/root/usr/lib corelib=$tmp/core/usr/lib
[ -f "$lib/$soname" ] || bad "no $soname in the runtime package"
[ -f "$lib/$evalso" ] || bad "no $evalso in the eval package"
[ -L "$lib/libobscura.so" ] || bad "no libobscura.so link in the -dev package"
[ -L "$lib/libobscura-eval.so" ] || bad "no libobscura-eval.so link in the eval -dev package"
for f in usr/include/obscura/obscura.h usr/include/obscura/scene.h usr/include/obscura/eval.h usr/lib/pkgconfig/obscura.pc \
         usr/lib/pkgconfig/obscura-eval.pc usr/lib/cmake/obscura/obscura-config.cmake \
         usr/lib/cmake/obscura/obscura-eval-targets.cmake usr/bin/obscura usr/share/obscura/scenes; do
    [ -e "$tmp/root/$f" ] || bad "no $f in the packages"
done
[ ! -e "$tmp/core/usr/include/obscura/eval.h" ] || bad "eval.h is in the core's packages"
for p in "$runtime" "$evalrt"; do
    [ "$(dpkg-deb -c "$tmp/pk/${p}_${version}_amd64.deb" | grep -c 'usr/include\|usr/bin')" -eq 0 ] ||
        bad "the library package $p holds headers or programs"
done
# pkg-config obscura names nothing of the lab: no cJSON or stb include folder, no library of theirs.
pc=$(PKG_CONFIG_PATH="$corelib/pkgconfig" pkg-config --cflags --libs --static obscura 2>&1) || bad "pkg-config obscura: $pc"
for lab in cjson stb assimp embree; do [[ $pc != *$lab* ]] || bad "pkg-config obscura names $lab: $pc"; done

# ldd's whole output first: under pipefail, `ldd | grep -q` fails when grep
# exits at the first match and ldd dies of SIGPIPE (CI saw exactly that).
loads_root() { local deps; deps=$(ldd "$1") && [[ $deps == *"$corelib/$soname"* ]]; }
# examples/embed through the CMake package of the core's root, and run.
if "$cmake" -S "$src/examples/embed" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$tmp/core/usr" -DCMAKE_BUILD_TYPE=Release \
        "-DCMAKE_C_COMPILER=$cc" >"$tmp/cm.log" 2>&1 && "$cmake" --build "$tmp/cm" >>"$tmp/cm.log" 2>&1; then
    if "$tmp/cm/embed" --size 96x72 --out "$tmp/cm_ao.pfm" >"$tmp/run.log" 2>&1; then ok; else bad "embed (CMake) failed: $(tail -2 "$tmp/run.log")"; fi
    loads_root "$tmp/cm/embed" || bad "embed (CMake) does not load the packaged library: $(ldd "$tmp/cm/embed" | grep obscura)"
else
    tail -15 "$tmp/cm.log"; bad "examples/embed does not build against the packages (CMake)"
fi
# ... and through pkg-config.
mkdir -p "$tmp/pc"
if PKG_CONFIG_PATH="$corelib/pkgconfig" make -C "$src/examples/embed" CC="$cc" OUT="$tmp/pc" >"$tmp/pc.log" 2>&1; then
    if LD_LIBRARY_PATH="$corelib" "$tmp/pc/embed" --size 96x72 --out "$tmp/pc_ao.pfm" >"$tmp/run.log" 2>&1; then ok
    else bad "embed (pkg-config) failed: $(tail -2 "$tmp/run.log")"; fi
else
    tail -15 "$tmp/pc.log"; bad "examples/embed does not build against the packages (pkg-config)"
fi
# examples/host against all five (find_package(obscura COMPONENTS eval)): built, and linked to both
# packaged libraries.
if "$cmake" -S "$src/examples/host" -B "$tmp/host" -DCMAKE_PREFIX_PATH="$tmp/root/usr" -DCMAKE_BUILD_TYPE=Release \
        "-DCMAKE_C_COMPILER=$cc" >"$tmp/host.log" 2>&1 && "$cmake" --build "$tmp/host" >>"$tmp/host.log" 2>&1; then
    deps=$(ldd "$tmp/host/host")
    [[ $deps == *"$lib/$soname"* && $deps == *"$lib/$evalso"* ]] ||
        bad "examples/host does not load the packaged libraries: $(echo "$deps" | grep obscura)"
else
    tail -15 "$tmp/host.log"; bad "examples/host does not build against the packages (CMake, COMPONENTS eval)"
fi
if [ $fails -gt 0 ]; then echo "package: $fails failure(s)"; exit 1; fi
echo "package: ok ($runtime, libobscura-dev, $evalrt, libobscura-eval-dev, obscura $version; examples/embed built against the core's alone both ways and ran, examples/host against all)"
