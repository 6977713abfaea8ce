#!/usr/bin/env bash
# Pack what build/obscura needs at run time for a machine that lacks the project's Debian
# packages (the lent GPU machine, see bench/README.md): every shared library `ldd` resolves,
# except glibc's own (libc, libm, libdl, libpthread, librt, ld-linux: the target has them and they
# must match its loader), as .gl/runtime.tar.xz. Compressed because the working tree that travels
# to the device is capped at 64 MiB and libembree3 alone is ~42 MiB.
# On the device: tar -xJf .gl/runtime.tar.xz -C .gl && export LD_LIBRARY_PATH=$PWD/.gl/lib
# (bench/run-gpu.sh does both).
set -euo pipefail
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
