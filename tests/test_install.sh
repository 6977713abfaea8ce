#!/usr/bin/env bash
# The library as another project takes it home: `cmake --install` into a temporary prefix, which
# is then moved (nothing may point back at the build or the source tree), examples/embed built
# against it through find_package(obscura) and through pkg-config, and both binaries run.
# usage: test_install.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset OBSCURA_DATA_DIR
cmake=${CMAKE:-cmake} cc=${CC:-cc} # the build's own, when CTest runs this
fails=0
ok() { :; }
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }
# (ldd's output is kept whole: grep -q would stop reading, and pipefail see ldd's SIGPIPE.)
loads_installed() { local deps; deps=$(ldd "$1") && grep -q "libobscura.*=> $prefix/" <<<"$deps"; }
step() { # step NAME COMMAND...: run quietly, show the log on failure
    if "${@:2}" >"$tmp/log" 2>&1; then ok; else bad "$1"; tail -20 "$tmp/log"; return 1; fi
}

step "cmake --install" "$cmake" --install "$build" --prefix "$tmp/stage" || exit 1
mv "$tmp/stage" "$tmp/prefix"
prefix=$tmp/prefix
pc=$(find "$prefix" -name obscura.pc)
libdir=$(dirname "$(dirname "$pc")")

# ---- the tree ----
for f in include/obscura/obscura.h include/obscura/scene.h include/obscura/eval.h bin/obscura share/obscura/scenes/bunny.obscura.json \
         share/obscura/shaders/ssao.glsl; do
    [ -f "$prefix/$f" ] || bad "not installed: $f"
done
for f in libobscura.so libobscura-eval.so cmake/obscura/obscura-config.cmake cmake/obscura/obscura-config-version.cmake \
         cmake/obscura/obscura-targets.cmake cmake/obscura/obscura-eval-targets.cmake pkgconfig/obscura.pc \
         pkgconfig/obscura-eval.pc; do
    [ -e "$libdir/$f" ] || bad "not installed: ${libdir#"$prefix"/}/$f"
done
[ -z "$(find "$prefix" -name '*.a')" ] || bad "a static library was installed"

# ---- no path of this machine's trees in the installed binaries (debug info aside) ----
for bin in "$libdir/libobscura.so" "$libdir/libobscura-eval.so" "$prefix/bin/obscura"; do
    objcopy --strip-debug "$bin" "$tmp/stripped"
    if grep -qaF -e "$src" -e "$build" "$tmp/stripped"; then
        bad "$(basename "$bin") names the source or build tree: $(strings "$tmp/stripped" | grep -F -e "$src" -e "$build" | head -3)"
    fi
done

# ---- the installed CLI finds its data directory from its own place, run from anywhere ----
if (cd / && "$prefix/bin/obscura" list) >"$tmp/list" 2>&1 && grep -q "^  bunny" "$tmp/list"; then ok
else bad "installed obscura list names no bunny: $(tail -3 "$tmp/list")"; fi

# ---- a host program elsewhere finds the data directory beside the installed library ----
printf '#include <obscura/scene.h>\n#include <stdio.h>\nint main(void) { puts(ob_data_dir()); return 0; }\n' >"$tmp/host.c"
if step "a host program against the installed library" "$cc" -std=c11 -Wall -Werror -I"$prefix/include" "$tmp/host.c" \
        -o "$tmp/host" -L"$libdir" -lobscura -Wl,-rpath,"$libdir"; then
    found=$(cd / && "$tmp/host")
    [ "$found" = "$(cd "$prefix/share/obscura" && pwd -P)" ] || bad "ob_data_dir() from a host: '$found', want $prefix/share/obscura"
    found=$(cd / && OBSCURA_DATA_DIR=/somewhere "$tmp/host")
    [ "$found" = /somewhere ] || bad "OBSCURA_DATA_DIR=/somewhere: ob_data_dir() gives '$found'"
fi

# ---- examples/embed through the CMake package ----
flags="-Wall -Wextra -Werror"
if step "cmake configure of examples/embed" "$cmake" -S "$src/examples/embed" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$prefix" \
        -DCMAKE_BUILD_TYPE=Release "-DCMAKE_C_COMPILER=$cc" "-DCMAKE_C_FLAGS=$flags" &&
   step "cmake build of examples/embed" "$cmake" --build "$tmp/cm"; then
    if "$tmp/cm/embed" --method ssao --filter gaussian --out "$tmp/cm_ao.pfm"; then ok; else bad "embed (CMake) failed"; fi
    [ -s "$tmp/cm_ao.pfm" ] || bad "embed (CMake) wrote no AO"
    loads_installed "$tmp/cm/embed" || bad "embed (CMake) does not load the installed library"
fi

# ---- examples/embed through pkg-config ----
mkdir -p "$tmp/pc"
if PKG_CONFIG_PATH="$libdir/pkgconfig" step "make (pkg-config) of examples/embed" \
        make -C "$src/examples/embed" CC="$cc" OUT="$tmp/pc" CFLAGS="-O2 $flags"; then
    if "$tmp/pc/embed" --method hbao --filter bilateral --size 256x192 --out "$tmp/pc_ao.pfm"; then ok
    else bad "embed (pkg-config) failed"; fi
    [ -s "$tmp/pc_ao.pfm" ] || bad "embed (pkg-config) wrote no AO"
    loads_installed "$tmp/pc/embed" || bad "embed (pkg-config) does not load the installed library"
fi

# ---- examples/host (its own renderer around ob_host_ao) through the CMake package ----
if step "cmake configure of examples/host" "$cmake" -S "$src/examples/host" -B "$tmp/hm" -DCMAKE_PREFIX_PATH="$prefix" \
        -DCMAKE_BUILD_TYPE=Release "-DCMAKE_C_COMPILER=$cc" "-DCMAKE_C_FLAGS=$flags" &&
   step "cmake build of examples/host" "$cmake" --build "$tmp/hm"; then
    if [ -f "$src/data/armadillo.off" ]; then
        if "$tmp/hm/host" --model "$src/data/armadillo.off" --size 96x72 --frames 2 --out-ao "$tmp/hm_ao.pfm" >/dev/null; then ok
        else bad "host example (CMake) failed"; fi
        [ -s "$tmp/hm_ao.pfm" ] || bad "host example (CMake) wrote no AO"
    fi
    loads_installed "$tmp/hm/host" || bad "host example (CMake) does not load the installed library"
fi

# ---- the example's own check must be able to fail: no AO, no darker contact ----
if [ -x "$tmp/pc/embed" ]; then
    "$tmp/pc/embed" --method none --size 64x48 >/dev/null
    rc=$?
    [ $rc -eq 3 ] || bad "embed --method none: exit $rc, want 3 (the contact is not darker)"
fi

if [ $fails -gt 0 ]; then echo "install: $fails failure(s)"; exit 1; fi
echo "install: ok ($(find "$prefix" -type f | wc -l) files installed, both builds of examples/embed and examples/host ran)"
