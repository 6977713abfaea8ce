#!/usr/bin/env bash
# Remakes abi/libobscura.abi and abi/libobscura-eval.abi, the ABI baselines that tests/test_abi.sh
# compares the two libraries with, from a build's libraries: scripts/abi-baseline.sh [BUILD]
# (default build). Run it when the public
# ABI changed on purpose, in the same commit as the change and the docs/changelog.md entry. An
# incompatible change (abidiff's ABIDIFF_ABI_INCOMPATIBLE_CHANGE: a function removed or its
# signature changed, a public struct's layout changed) is refused unless the soname moved with it,
# that is unless OB_VERSION_MAJOR (or before 1.0 OB_VERSION_MINOR) in include/obscura/obscura.h
# was raised: a host built against the old header must not load the new library.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-build}
for tool in abidw abidiff; do
    command -v $tool >/dev/null || { echo "abi-baseline: $tool not found (scripts/install-deps.sh installs abigail-tools)" >&2; exit 1; }
done
baseline() { # NAME
    local lib=$build/$1.so base=$src/abi/$1.abi tmp report rc
    [ -f "$lib" ] || { echo "abi-baseline: $lib not found (make build first)" >&2; exit 1; }
    tmp=$(mktemp)
    abidw --no-show-locs --no-corpus-path --headers-dir "$src/include/obscura" --drop-private-types "$lib" >"$tmp"
    soname() { grep -o "soname='[^']*'" "$1" | head -1; }
    # An incompatible change: abidiff's ABIDIFF_ABI_INCOMPATIBLE_CHANGE bit, or any function or
    # variable removed or changed (a public struct's layout reaches a host through every function that
    # takes it: abidiff lists those as changed and leaves the decision to us). Only additions pass.
    incompatible() { # incompatible RC REPORT
        [ $(($1 & 8)) -ne 0 ] && return 0
        echo "$2" | grep -Eq "(Functions|Variables) changes summary: [1-9][0-9]* Removed|(Functions|Variables) changes summary: [0-9]+ Removed(\\([^)]*\\))?, [1-9][0-9]* Changed"
    }

    if [ -f "$base" ]; then
        set +e
        report=$(abidiff "$base" "$tmp" 2>&1)
        rc=$?
        set -e
        if incompatible $rc "$report" && [ "$(soname "$base")" = "$(soname "$tmp")" ]; then
            echo "$report" | head -40 >&2
            echo "abi-baseline: an incompatible ABI change with the same $(soname "$tmp"): raise OB_VERSION_MINOR" \
                 "(OB_VERSION_MAJOR from 1.0 on) in include/obscura/obscura.h, rebuild, and run this again" >&2
            rm -f "$tmp"
            exit 1
        fi
    fi
    mkdir -p "$(dirname "$base")"
    chmod 644 "$tmp"
    mv "$tmp" "$base"
    echo "abi-baseline: $base from $lib ($(soname "$base"), $(grep -c '<elf-symbol ' "$base") symbols)"
}
baseline libobscura
baseline libobscura-eval
