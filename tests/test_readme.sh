#!/usr/bin/env bash
# README.md against the registries (issue 20): its lists of methods (--method), filters
# (--filter), views (--view and the viewer's debug views) and its table of scenes and cameras say
# exactly what `obscura list --json` says; the --samples and --key ranges it gives are the ones
# the CLI's help prints and its parser enforces. CPU only (list loads the scenes, renders nothing).
# usage: test_readme.sh OBSCURA README.md
set -uo pipefail
OBSCURA=$1
README=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

if "$OBSCURA" list --json >"$dir/list.json" 2>"$dir/list.err"; then ok; else bad "list --json: $(cat "$dir/list.err")"; fi

if python3 - "$dir/list.json" "$README" <<'PY'
import json, re, sys
d = json.load(open(sys.argv[1]))
readme = open(sys.argv[2]).read()
errors = []

def same(what, documented, registry):
    if list(documented) != list(registry) and sorted(documented) != sorted(registry):
        missing = [x for x in registry if x not in documented]
        extra = [x for x in documented if x not in registry]
        errors.append(f"{what}: README lacks {missing}, names unknown {extra}")

def option_list(option):
    # `--option a|b|c` as the README writes it (two names at least: `--method none` alone is a
    # use, not the list); exactly one such list per option.
    found = re.findall(r"`%s ([a-z0-9_]+(?:\|[a-z0-9_]+)+)`" % re.escape(option), readme)
    if len(found) != 1:
        errors.append(f"{option}: {len(found)} lists in README, want 1")
        return []
    return found[0].split("|")

same("--method", option_list("--method"), [m["name"] for m in d["methods"]])
same("--filter", option_list("--filter"), [f["name"] for f in d["filters"]])
same("--view", option_list("--view"), d["views"])
m = re.search(r"switch to a debug view:(.*?);", readme, re.S)
same("viewer debug views", re.findall(r"`([a-z_]+)`", m.group(1)) if m else [], d["views"])

# The scenes table between its markers: name, kind, description, cameras.
m = re.search(r"<!-- scenes: begin -->(.*?)<!-- scenes: end -->", readme, re.S)
rows = {}
if not m:
    errors.append("no scenes table (<!-- scenes: begin --> ... <!-- scenes: end -->)")
else:
    for line in m.group(1).splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 4 or not cells[0].startswith("`"):
            continue
        rows[cells[0].strip("`")] = (cells[1], re.findall(r"`([^`]+)`", cells[3]))
scenes = d["scenes"]
same("scenes", list(rows), [s["name"] for s in scenes])
assert [s["name"] for s in d["builtin_scenes"]] == [s["name"] for s in scenes if s["kind"] == "builtin"]
assert d["named_scenes"] == [s["name"] for s in scenes if s["kind"] == "named"]
for s in scenes:
    if s["name"] not in rows:
        continue
    kind, cams = rows[s["name"]]
    want_kind = "built-in" if s["kind"] == "builtin" else "named"
    if kind != want_kind:
        errors.append(f"{s['name']}: README says {kind}, list says {want_kind}")
    if "cameras" not in s:
        # A named scene whose model is not installed here: its cameras cannot be checked.
        print(f"note: {s['name']} not loaded ({s.get('error')}), cameras unchecked")
        continue
    if cams != s["cameras"]:
        errors.append(f"{s['name']} cameras: README {cams}, list {s['cameras']}")
for e in errors:
    print(e)
sys.exit(1 if errors else 0)
PY
then ok; else bad "README.md lags obscura list --json (above)"; fi

# The ranges README gives are the help's and the parser's.
"$OBSCURA" render --help >"$dir/help" 2>&1
for range in "--samples:1..2048" "--key:0.001..10"; do
    opt=${range%%:*} r=${range#*:}
    if grep -qE -- "^  $opt .*$r" "$dir/help" && grep -qF -- "\`$opt" "$README" && grep -qF -- "$r" "$README"; then ok
    else bad "$opt: help or README does not give $r"; fi
done
# Just past each end of those ranges is refused with exit 2 and a line naming the range; the ends
# themselves get past the parser (the run then stops at the unknown scene, exit 2 as well, with a
# message that does not mention the option).
expect_refused() { # OPTION VALUE RANGE
    "$OBSCURA" render --scene no-such-scene --out "$dir/x.png" "$1" "$2" >/dev/null 2>"$dir/err"
    local rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l <"$dir/err")" -eq 1 ] && grep -qF -- "$1" "$dir/err" && grep -qF -- "$3" "$dir/err"; then ok
    else bad "$1 $2: exit $rc, $(cat "$dir/err")"; fi
}
expect_parsed() { # OPTION VALUE
    "$OBSCURA" render --scene no-such-scene --out "$dir/x.png" "$1" "$2" >/dev/null 2>"$dir/err"
    if ! grep -qF -- "$1" "$dir/err" && grep -q "no-such-scene" "$dir/err"; then ok
    else bad "$1 $2 was refused: $(cat "$dir/err")"; fi
}
expect_refused --samples 2049 "1..2048"
expect_refused --samples 0 "1..2048"
expect_parsed --samples 2048
expect_refused --key 10.5 "10"
expect_refused --key 0.0005 "0.001"
expect_parsed --key 10
[ ! -e "$dir/x.png" ] && ok || bad "a refused run left x.png"

echo "test_readme: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
