#!/usr/bin/env bash
# A build without the viewer (-DOB_VIEWER=OFF): `obscura view` fails with one line and exit 2.
# usage: test_noviewer.sh OBSCURA
set -uo pipefail
err=$(mktemp)
trap 'rm -f "$err"' EXIT
"$1" view --scene cornell 2>"$err"
rc=$?
if [ $rc -ne 2 ] || [ "$(wc -l <"$err")" -ne 1 ] || ! grep -q "no viewer" "$err"; then
    echo "FAIL: obscura view without a viewer: exit $rc, stderr:"; cat "$err"; exit 1
fi
echo "noviewer: $(cat "$err")"
