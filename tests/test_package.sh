#!/usr/bin/env bash
# make package (issue 46, item 4): CPack's three Debian packages from this build, their
# dependencies (dpkg-shlibdeps for the libraries they link, the runtime package at the same
# version for the other two), their contents, and examples/embed built and run against nothing but
# the packages unpacked into a scratch root, through the CMake package and through pkg-config.
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
if [ "$(ver MAJOR)" -eq 0 ]; then runtime=libobscura0.$(ver MINOR) soname=libobscura.so.0.$(ver MINOR)
else runtime=libobscura$(ver MAJOR) soname=libobscura.so.$(ver MAJOR); fi

cpack=$(dirname "$cmake")/cpack
if ! (cd "$build" && "$cpack" -G DEB -B "$tmp/pk" --config CPackConfig.cmake >"$tmp/cpack.log" 2>&1); then
    tail -20 "$tmp/cpack.log"; echo "package: cpack failed"; exit 1
fi
for p in "$runtime" libobscura-dev obscura; do
    deb=$tmp/pk/${p}_${version}_amd64.deb
    [ -f "$deb" ] || { bad "no $deb (made: $(ls "$tmp/pk"))"; continue; }
    dpkg-deb -x "$deb" "$tmp/root" || bad "dpkg-deb -x $deb"
    deps=$(dpkg-deb -f "$deb" Depends)
    echo "  $p $version: Depends: $deps"
    case $p in
    "$runtime") [[ $deps == *"libc6 (>="* && $deps == *libassimp* && $deps == *libepoxy0* ]] ||
                    bad "$p: no dpkg-shlibdeps dependencies ($deps)" ;;
    *) [[ $deps == *"$runtime (= $version)"* ]] || bad "$p does not depend on $runtime (= $version): $deps" ;;
    esac
done
lib=$tmp/root/usr/lib
[ -f "$lib/$soname" ] || bad "no $soname in the runtime package"
[ -L "$lib/libobscura.so" ] || bad "no libobscura.so link in the -dev package"
for f in usr/include/obscura/obscura.h usr/lib/pkgconfig/obscura.pc usr/lib/cmake/obscura/obscura-config.cmake \
         usr/bin/obscura usr/share/obscura/scenes; do
    [ -e "$tmp/root/$f" ] || bad "no $f in the packages"
done
[ "$(dpkg-deb -c "$tmp/pk/${runtime}_${version}_amd64.deb" | grep -c 'usr/include\|usr/bin')" -eq 0 ] ||
    bad "the runtime package holds headers or programs"

# ldd's whole output first: under pipefail, `ldd | grep -q` fails when grep
# exits at the first match and ldd dies of SIGPIPE (CI saw exactly that).
loads_root() { local deps; deps=$(ldd "$1") && [[ $deps == *"$lib/$soname"* ]]; }
# examples/embed through the CMake package of the unpacked root, and run.
if "$cmake" -S "$src/examples/embed" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$tmp/root/usr" -DCMAKE_BUILD_TYPE=Release \
        "-DCMAKE_C_COMPILER=$cc" >"$tmp/cm.log" 2>&1 && "$cmake" --build "$tmp/cm" >>"$tmp/cm.log" 2>&1; then
    if "$tmp/cm/embed" --size 96x72 --out "$tmp/cm_ao.pfm" >"$tmp/run.log" 2>&1; then ok; else bad "embed (CMake) failed: $(tail -2 "$tmp/run.log")"; fi
    loads_root "$tmp/cm/embed" || bad "embed (CMake) does not load the packaged library: $(ldd "$tmp/cm/embed" | grep obscura)"
else
    tail -15 "$tmp/cm.log"; bad "examples/embed does not build against the packages (CMake)"
fi
# ... and through pkg-config.
mkdir -p "$tmp/pc"
if PKG_CONFIG_PATH="$lib/pkgconfig" make -C "$src/examples/embed" CC="$cc" OUT="$tmp/pc" >"$tmp/pc.log" 2>&1; then
    if LD_LIBRARY_PATH="$lib" "$tmp/pc/embed" --size 96x72 --out "$tmp/pc_ao.pfm" >"$tmp/run.log" 2>&1; then ok
    else bad "embed (pkg-config) failed: $(tail -2 "$tmp/run.log")"; fi
else
    tail -15 "$tmp/pc.log"; bad "examples/embed does not build against the packages (pkg-config)"
fi
if [ $fails -gt 0 ]; then echo "package: $fails failure(s)"; exit 1; fi
echo "package: ok ($runtime, libobscura-dev, obscura $version; examples/embed built against them both ways and ran)"
