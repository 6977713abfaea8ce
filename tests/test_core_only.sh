#!/usr/bin/env bash
# The core alone (issue 46, item 1): this source tree configured with -DOB_CORE_ONLY=ON where
# pkg-config knows nothing but OpenGL's loaders and cglm (a scratch PKG_CONFIG_LIBDIR holding only
# their .pc files: assimp, libcjson, zlib and stb are not there to be found), built, installed, and
# examples/embed built and run against that install alone. Checks: nothing of the lab was looked
# for (CMakeCache), read (the objects' dependency files name no header of Assimp, Embree, cJSON,
# stb or zlib) or linked (libobscura.so's NEEDED entries: the C library, libm, libepoxy); no
# libobscura-eval, CLI or viewer was built; the install holds obscura.h and scene.h, not eval.h.
# usage: test_core_only.sh SOURCE_DIR CMAKE CC
set -uo pipefail
src=$1 cmake=$2 cc=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }

# pkg-config's world: the .pc files of the loaders and cglm (and what they require), nothing else.
mkdir -p "$tmp/pc"
for m in epoxy egl cglm gl x11 opengl glx xproto kbproto xcb xau xdmcp pthread-stubs; do
    d=$(pkg-config --variable=pcfiledir "$m" 2>/dev/null) && [ -f "$d/$m.pc" ] && cp "$d/$m.pc" "$tmp/pc/"
done
export PKG_CONFIG_LIBDIR=$tmp/pc PKG_CONFIG_PATH=
for lab in assimp libcjson zlib stb; do
    ! pkg-config --exists "$lab" || { echo "core_only: the scratch pkg-config still finds $lab"; exit 1; }
done

b=$tmp/build
if ! "$cmake" -S "$src" -B "$b" -DOB_CORE_ONLY=ON -DCMAKE_BUILD_TYPE=Release "-DCMAKE_C_COMPILER=$cc" \
        "-DCMAKE_INSTALL_PREFIX=$tmp/prefix" >"$tmp/configure.log" 2>&1; then
    tail -20 "$tmp/configure.log"; echo "core_only: configure failed"; exit 1
fi
if ! "$cmake" --build "$b" -j "$(nproc)" >"$tmp/build.log" 2>&1; then
    grep -E "error|Error" "$tmp/build.log" | head -20; echo "core_only: build failed"; exit 1
fi
cached=$(grep -iE '^[^#/]*(assimp|embree|cjson|stb|zlib)' "$b/CMakeCache.txt" || true)
[ -z "$cached" ] || bad "the core-only configure looked for the lab: $cached"
lab_headers=$(find "$b" -name '*.o.d' -exec grep -lE '/(assimp|embree3|cjson|stb)/|/zlib\.h' {} + 2>/dev/null || true)
[ -z "$lab_headers" ] || bad "core objects read a header of the lab: $(echo "$lab_headers" | head -3)"
for t in libobscura-eval.so obscura; do [ ! -e "$b/$t" ] || bad "$t was built in the core-only build"; done

lib=$(readlink -f "$b/libobscura.so")
needed=$(readelf -d "$lib" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort | tr '\n' ' ')
echo "core_only: $(basename "$lib") NEEDED: $needed"
for n in $needed; do
    case $n in libc.so.* | libm.so.* | libepoxy.so.* | ld-linux*.so.* | libpthread.so.* | libdl.so.*) ;;
    *) bad "libobscura.so needs $n" ;;
    esac
done

if ! "$cmake" --install "$b" >"$tmp/install.log" 2>&1; then tail -10 "$tmp/install.log"; bad "install failed"; fi
p=$tmp/prefix
for f in include/obscura/obscura.h include/obscura/scene.h lib/pkgconfig/obscura.pc lib/cmake/obscura/obscura-config.cmake; do
    [ -e "$p/$f" ] || bad "not installed: $f"
done
[ ! -e "$p/include/obscura/eval.h" ] || bad "eval.h installed by the core-only build"
[ -z "$(find "$p" -name 'libobscura-eval*' -o -name obscura -type f)" ] || bad "more than the core installed"

# An engine's build against it: examples/embed through the CMake package (find_package(obscura)).
if "$cmake" -S "$src/examples/embed" -B "$tmp/embed" -DCMAKE_PREFIX_PATH="$p" -DCMAKE_BUILD_TYPE=Release \
        "-DCMAKE_C_COMPILER=$cc" "-DCMAKE_C_FLAGS=-Wall -Wextra -Werror" >"$tmp/embed.log" 2>&1 &&
   "$cmake" --build "$tmp/embed" >>"$tmp/embed.log" 2>&1; then
    if "$tmp/embed/embed" --size 96x72 --out "$tmp/ao.pfm" >"$tmp/run.log" 2>&1; then
        echo "core_only: $(tail -1 "$tmp/run.log")"
    else bad "embed against the core alone failed: $(tail -2 "$tmp/run.log")"; fi
    deps=$(ldd "$tmp/embed/embed")
    [[ $deps == *"$p/lib"*"libobscura.so"* ]] || bad "embed does not load the core-only install: $(echo "$deps" | grep obscura)"
else
    tail -15 "$tmp/embed.log"; bad "examples/embed does not build against the core alone"
fi
if [ $fails -gt 0 ]; then echo "core_only: $fails failure(s)"; exit 1; fi
echo "core_only: ok (configured, built and installed without the lab; examples/embed built and ran against it)"
