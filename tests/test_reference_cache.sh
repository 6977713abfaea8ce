#!/usr/bin/env bash
# The reference cache is checked, not trusted (issue 44): an entry that is garbage of the right
# size, holds NaN or out-of-range values, is truncated, is a FIFO, a symbolic link or a directory,
# was traced for another view, by an older obscura or from an older copy of the model is named in
# one warning line, removed (a directory is left alone) and traced again, and the report's RMSE is
# the one a --no-cache run gives. Two compares tracing the same view at once leave one valid
# entry. A full, read-only or impossible cache location is a warning and exit 0, with Mesa's
# shader cache turned off (Mesa maps it and died of SIGBUS on a full disk).
set -u
OBSCURA=$1
dir=$(mktemp -d)
mounts=()
cleanup() {
    for m in "${mounts[@]}"; do umount "$m" 2>/dev/null; done
    rm -rf "$dir"
}
trap cleanup EXIT
export XDG_CACHE_HOME="$dir/cache"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# Small and fast: one method, 32x24 pixels, 8 rays (the reference is deterministic for a seed).
SMALL=(--size 32x24 --methods ssao --spp 8)
W=32
H=24

# The entry's format as a reader outside obscura sees it (reference_cache.c): the header, the
# payload's FNV-1a checksum, and the values. Also edits entries: the cases below need entries
# that are wrong in one way only.
cat >"$dir/entry.py" <<'PY'
import math, os, struct, sys

W, H = int(os.environ["W"]), int(os.environ["H"])

def fnv(b):
    h = 1469598103934665603
    for x in b:
        h = ((h ^ x) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h

def layout(data):
    """(payload offset, floats per pixel, payload line's start or -1)"""
    if data.startswith(b"obscura reference cache "):
        at = data.index(b"\npayload ") + 1
        return data.index(b"\n", at) + 1, 2, at
    if data.startswith(b"PF\n"):  # format 1: a bare PFM, AO, standard error, 0
        end = 0
        for _ in range(3):
            end = data.index(b"\n", end) + 1
        return end, 3, -1
    raise SystemExit("unknown entry format")

def fix_checksum(data):
    off, _, at = layout(data)
    if at < 0:
        return data
    line = data[at:off - 1].split(b" ")
    line[-1] = b"%016x" % fnv(data[off:])
    return data[:at] + b" ".join(line) + b"\n" + data[off:]

cmd, path = sys.argv[1], sys.argv[2]
if cmd == "valid":
    data = open(path, "rb").read()
    assert data.startswith(b"obscura reference cache 2\n"), "not format 2: %r" % data[:30]
    off, stride, at = layout(data)
    fields = data[at:off - 1].decode().split()
    assert fields[:3] == ["payload", "float32le", "ao,stderr"] and fields[4] == "fnv1a64", fields
    payload = data[off:]
    assert len(payload) == int(fields[3]) == W * H * 8, (len(payload), fields)
    assert fnv(payload) == int(fields[5], 16), "checksum"
    values = struct.unpack("<%df" % (W * H * 2), payload)
    assert all(0 <= a <= 1 for a in values[0::2]), "AO outside [0, 1]"
    assert all(math.isfinite(e) and e >= 0 for e in values[1::2]), "standard error"
elif cmd == "garble":  # plausible values of the right size: only the checksum can tell
    data = bytearray(open(path, "rb").read())
    off, stride, _ = layout(bytes(data))
    for k in range(W * H):
        data[off + 4 * stride * k:off + 4 * stride * k + 8] = struct.pack("<ff", 0.97, 0.01)
    open(path, "wb").write(data)
elif cmd == "poke":  # poke PATH PIXEL CHANNEL VALUE, the checksum made to match
    k, ch, v = int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
    data = bytearray(open(path, "rb").read())
    off, stride, _ = layout(bytes(data))
    data[off + 4 * (stride * k + ch):off + 4 * (stride * k + ch) + 4] = struct.pack("<f", v)
    open(path, "wb").write(fix_checksum(bytes(data)))
elif cmd == "oldpfm":  # a format-1 entry: what obscura before issue 44 wrote
    body = struct.pack("<%df" % (W * H * 3), *([0.5, 0.01, 0.0] * (W * H)))
    open(path, "wb").write(b"PF\n%d %d\n-1.0\n" % (W, H) + body)
PY
entry() { W=$W H=$H python3 "$dir/entry.py" "$@"; }

# compare TAG ARGS...: a report in $dir/TAG, its exit code in $dir/TAG.rc; never hangs.
compare() {
    local tag=$1
    shift
    timeout 60 "$OBSCURA" compare "$@" "${SMALL[@]}" --report "$dir/$tag" >"$dir/$tag.out" 2>"$dir/$tag.err"
    echo $? >"$dir/$tag.rc"
}
rc() { cat "$dir/$1.rc"; }
json() { python3 -c 'import json, sys; v = json.load(open(sys.argv[1]))["views"][0]; print(repr(eval(sys.argv[2])))' \
    "$dir/$1/results.json" "$2" 2>/dev/null; }
rmse() { json "$1" 'v["methods"][0]["rmse"]'; }
cached() { json "$1" 'v["reference"]["cached"]'; }
entries() { find "$1" -maxdepth 1 -name 'reference-*' 2>/dev/null | sort; }

# The truth: --no-cache runs in a cache of their own.
XDG_CACHE_HOME="$dir/truth-cache" compare truth --scene corner --no-cache
XDG_CACHE_HOME="$dir/truth-cache" compare truth_diag --scene corner:diagonal --no-cache
truth=$(rmse truth)
truth_diag=$(rmse truth_diag)
if [ "$(rc truth)" = 0 ] && [ -n "$truth" ] && [ -n "$truth_diag" ] && [ "$truth" != "$truth_diag" ]; then ok
else bad "the --no-cache runs failed or agree ($truth, $truth_diag): $(tail -2 "$dir/truth.err")"; fi

# The entry of corner:default, traced once, then used.
compare warm --scene corner
entry_path=$(entries "$XDG_CACHE_HOME/obscura")
if [ "$(rc warm)" = 0 ] && [ "$(cached warm)" = False ] && [ "$(echo "$entry_path" | wc -l)" = 1 ] && [ -f "$entry_path" ]
then ok; else bad "the first run left no single entry (rc $(rc warm)): $entry_path"; fi
if entry valid "$entry_path" 2>"$dir/valid.err"; then ok; else bad "the entry is not valid: $(tail -1 "$dir/valid.err")"; fi
cp "$entry_path" "$dir/good_entry" 2>/dev/null
compare again --scene corner
if [ "$(rc again)" = 0 ] && [ "$(cached again)" = True ] && [ "$(rmse again)" = "$truth" ]; then ok
else bad "a valid entry was not used (cached $(cached again), RMSE $(rmse again), truth $truth)"; fi

# bad_entry NAME WHY: the entry prepared as NAME says is named once as WHY, traced again (not
# cached, the --no-cache RMSE) and replaced by a valid entry. Every way it falls short is said.
bad_entry() {
    local name=$1 why=$2 problems=""
    compare "$name" --scene corner
    local warnings
    warnings=$(grep -c "^obscura: warning: reference cache entry $entry_path: .*; recomputing$" "$dir/$name.err")
    [ "$(rc "$name")" = 0 ] || problems+=" exit $(rc "$name");"
    [ "$warnings" = 1 ] || problems+=" $warnings warnings naming the entry, expected 1;"
    grep -q "$why" "$dir/$name.err" || problems+=" no '$why' said;"
    [ "$(cached "$name")" = False ] || problems+=" reported cached: $(cached "$name");"
    [ "$(rmse "$name")" = "$truth" ] || problems+=" RMSE $(rmse "$name"), the --no-cache run's $truth;"
    if ! [ -f "$entry_path" ] || [ -L "$entry_path" ] || ! timeout 10 env W=$W H=$H python3 "$dir/entry.py" valid "$entry_path" 2>/dev/null
    then problems+=" the entry was not replaced by a valid one;"; fi
    if [ -z "$problems" ]; then ok
    else bad "$name:$problems $(grep -v '%' "$dir/$name.err" | tail -2 | tr '\n' ' ')"; fi
}
# Each case starts from the good entry, whatever the case before left (a FIFO would block cp).
reset_entry() {
    rm -rf "$entry_path"
    cp "$dir/good_entry" "$entry_path"
}

# (a) Garbage of the right size: plausible AO (0.97, where the truth is ~0.15) behind the header.
reset_entry
entry garble "$entry_path"
bad_entry garbage "checksum"

# (b) NaN, AO out of [0, 1], a negative standard error: with the checksum made to match, so the
# values themselves are what is checked. Pixels 308, 267 and 234 are on the corner's geometry
# (their AO is under 1 at this size), so a value used there would change the RMSE.
reset_entry
entry poke "$entry_path" 308 0 nan
bad_entry nan "AO nan"
reset_entry
entry poke "$entry_path" 267 0 1.5
bad_entry ao_range "AO 1.5"
reset_entry
entry poke "$entry_path" 234 1 -0.25
bad_entry stderr_negative "standard error -0.25"

# (c) Truncated.
reset_entry
truncate -s $(($(stat -c %s "$entry_path") / 2)) "$entry_path"
bad_entry truncated "truncated"

# (d) A FIFO in the entry's place: no hang (compare's timeout would say 124), the name replaced.
rm -rf "$entry_path"
mkfifo "$entry_path"
bad_entry fifo "a FIFO"

# (e) Foreign: corner:diagonal's entry copied over corner:default's.
before=$(entries "$XDG_CACHE_HOME/obscura")
compare diag --scene corner:diagonal
diag_entry=$(comm -13 <(echo "$before") <(entries "$XDG_CACHE_HOME/obscura"))
if [ "$(rc diag)" = 0 ] && [ -n "$diag_entry" ] && [ "$(rmse diag)" = "$truth_diag" ]; then ok
else bad "corner:diagonal made no entry of its own: $diag_entry"; fi
rm -rf "$entry_path"
cp "$diag_entry" "$entry_path"
bad_entry foreign "another view"

# An entry of format 1 (a bare PFM, as obscura wrote before): recomputed once, not alarming.
rm -rf "$entry_path"
entry oldpfm "$entry_path"
bad_entry old_format "written by an older obscura"

# A symbolic link in the entry's place is removed, not followed: its target stays as it was.
cp "$dir/good_entry" "$dir/link_target"
rm -rf "$entry_path"
ln -s "$dir/link_target" "$entry_path"
bad_entry symlink "a symbolic link"
if cmp -s "$dir/good_entry" "$dir/link_target"; then ok; else bad "the symbolic link's target was changed"; fi

# A directory in the entry's place: named, left alone with what it holds, the command still right.
rm -rf "$entry_path"
mkdir "$entry_path"
echo keep >"$entry_path/inside"
compare directory --scene corner
if [ "$(rc directory)" = 0 ] && grep -q "^obscura: warning: reference cache entry $entry_path: .*a directory.*; recomputing$" \
    "$dir/directory.err" && [ "$(rmse directory)" = "$truth" ] && [ "$(cat "$entry_path/inside" 2>/dev/null)" = keep ]
then ok; else bad "a directory entry: exit $(rc directory), RMSE $(rmse directory): $(grep -v '%' "$dir/directory.err" | tail -2)"; fi
rm -rf "$entry_path"

# A model edited in place (same name, same triangle count and bounds, the box thinner): its old
# entry is stale, named so, and traced again.
model="$dir/box.obj"
write_box() {
    local s=$1
    cat >"$model" <<OBJ
v -2 0 -2
v 2 0 -2
v 2 0 2
v -2 0 2
v -$s 0 -$s
v $s 0 -$s
v $s 1 -$s
v -$s 1 -$s
v -$s 0 $s
v $s 0 $s
v $s 1 $s
v -$s 1 $s
f 1 4 3 2
f 5 6 7 8
f 10 9 12 11
f 9 5 8 12
f 6 10 11 7
f 8 7 11 12
OBJ
}
write_box 0.5
compare model_warm --scene "$model"
write_box 0.3
XDG_CACHE_HOME="$dir/truth-cache" compare model_truth --scene "$model" --no-cache
compare model_edited --scene "$model"
if [ "$(rc model_edited)" = 0 ] && grep -q "^obscura: warning: reference cache entry .*: the scene's files changed.*; recomputing$" \
    "$dir/model_edited.err" && [ "$(cached model_edited)" = False ] && [ "$(rmse model_edited)" = "$(rmse model_truth)" ] &&
    [ "$(rmse model_warm)" != "$(rmse model_truth)" ]
then ok; else bad "an edited model's entry: cached $(cached model_edited), RMSE $(rmse model_edited), truth $(rmse model_truth): $(grep warning "$dir/model_edited.err")"; fi

# (f) Two compares of the same view at once on an empty cache: both succeed, one valid entry
# and no temporary file is left, and a third run uses it.
export XDG_CACHE_HOME="$dir/race-cache"
compare race1 --scene corner &
pid1=$!
compare race2 --scene corner &
pid2=$!
wait $pid1 $pid2
left=$(find "$XDG_CACHE_HOME/obscura" -mindepth 1 2>/dev/null)
if [ "$(rc race1)" = 0 ] && [ "$(rc race2)" = 0 ] && [ "$(rmse race1)" = "$truth" ] && [ "$(rmse race2)" = "$truth" ]; then ok
else bad "two compares at once: exit $(rc race1) and $(rc race2)"; fi
if [ "$(echo "$left" | wc -l)" = 1 ] && entry valid "$left" 2>"$dir/race.valid"; then ok
else bad "two compares at once left '$left', not one valid entry: $(tail -1 "$dir/race.valid")"; fi
compare race3 --scene corner
if [ "$(rc race3)" = 0 ] && [ "$(cached race3)" = True ] && [ "$(rmse race3)" = "$truth" ] && ! grep -q warning "$dir/race3.err"
then ok; else bad "the raced entry was not used: cached $(cached race3), RMSE $(rmse race3)"; fi

# A temporary entry a killed process left an hour ago goes at the next store; one a process may
# still be writing (a minute old) stays.
stale="$XDG_CACHE_HOME/obscura/reference-0000000000000000.pfm.tmp-AbCdEf"
fresh="$XDG_CACHE_HOME/obscura/reference-0000000000000001.pfm.tmp-AbCdEf"
printf 'half' >"$stale"
printf 'half' >"$fresh"
touch -d '2 hours ago' "$stale"
touch -d '1 minute ago' "$fresh"
compare stale --scene corner:diagonal
if [ "$(rc stale)" = 0 ] && [ ! -e "$stale" ] && [ -e "$fresh" ]; then ok
else bad "stale temporaries: exit $(rc stale), stale one $( [ -e "$stale" ] && echo kept || echo removed), fresh one $( [ -e "$fresh" ] && echo kept || echo removed)"; fi
rm -f "$fresh"

# (g) A cache location that cannot take the entry: one warning for our cache, one for Mesa's
# (turned off: no mesa_shader_cache made), exit 0 (not 135, SIGBUS), the right RMSE.
unwritable() {
    local name=$1 where=$2
    XDG_CACHE_HOME="$where" compare "$name" --scene corner
    if [ "$(rc "$name")" != 0 ]; then bad "$name: exit $(rc "$name") (135 is SIGBUS): $(grep -v '%' "$dir/$name.err" | tail -2)"
    elif [ "$(grep -c "^obscura: warning: cannot write the reference cache entry $where/obscura/reference-.*: .*" "$dir/$name.err")" != 1 ]; then
        bad "$name: no single warning about the reference cache: $(grep -v '%' "$dir/$name.err" | tail -2)"
    elif [ "$(grep -c "^obscura: warning: Mesa's shader cache $where/mesa_shader_cache: .*MESA_SHADER_CACHE_DISABLE=true$" "$dir/$name.err")" != 1 ]; then
        bad "$name: no single warning about Mesa's shader cache: $(grep -v '%' "$dir/$name.err" | tail -2)"
    elif [ -e "$where/mesa_shader_cache" ]; then bad "$name: Mesa's shader cache was used"
    elif [ "$(rmse "$name")" != "$truth" ]; then bad "$name: RMSE $(rmse "$name"), truth $truth"
    else ok; fi
}
# No root needed: a cache "directory" under a regular file.
touch "$dir/a_file"
unwritable not_a_directory "$dir/a_file/cache"
# A full and a read-only file system: small tmpfs mounts (root only; else said and skipped).
mkdir -p "$dir/mnt_full" "$dir/mnt_readonly"
if mount -t tmpfs -o size=64k tmpfs "$dir/mnt_full" 2>/dev/null; then
    mounts+=("$dir/mnt_full")
    dd if=/dev/zero of="$dir/mnt_full/filler" bs=4k 2>/dev/null
    unwritable full "$dir/mnt_full"
    if mount -t tmpfs -o size=1m,ro tmpfs "$dir/mnt_readonly" 2>/dev/null; then
        mounts+=("$dir/mnt_readonly")
        unwritable read_only "$dir/mnt_readonly"
    else bad "a read-only tmpfs could not be mounted where a writable one could"; fi
else
    echo "note: cannot mount a tmpfs here (not root?): the full and read-only cache cases are skipped" >&2
fi

echo "reference_cache: $passed passed, $failed failed"
[ "$failed" = 0 ]
