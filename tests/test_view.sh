#!/usr/bin/env bash
# obscura view under Xvfb (Debian's xvfb; Mesa's llvmpipe through GLX): the viewer starts and
# renders, its screenshot is not blank and shows the panel in a column of its own beside the
# picture (which keeps the window's shape, letterboxed) at 640x360, 1024x768, 1280x720 and
# 1600x900, a scripted run moves the camera and switches methods (the frames differ accordingly),
# the mouse works the camera on the picture only, test mode writes one CSV row and one screenshot
# per camera x method with a GPU and a CPU time above 0 for every pass that ran, the reference
# view shows its panes in the picture's place (and comes from the cache the second time),
# `screenshot` is the picture alone where `screenshot_ui` is the window, a scripted click reaches
# the panel, no screenshots/ appears unless a screenshot goes there, and bad input or a closed
# window exits cleanly.
set -u
OBSCURA=$1
IMGCHECK=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

if ! command -v xvfb-run >/dev/null; then
    echo "view: xvfb-run is missing (scripts/install-deps.sh installs xvfb)" >&2
    exit 1
fi
# One X server per call, on a free display number; 24-bit so screenshots keep their colours.
# timeout: a viewer that never exits fails the test instead of hanging it.
xrun() { local limit=$1; shift; timeout "$limit" xvfb-run -a -s "-screen 0 800x600x24" "$@"; }

# Numbers from imgcheck, compared in awk (floats).
gt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a > b) }'; }
lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

# ---- a scripted run: panel, camera movement, method switch, debug view ------------------------
# 640x360: the panel takes the right half (x 320..640, its widest share), the picture the left,
# 320x180 at y 90 with bars above and below; F1 hides the panel and the picture takes the window.
# The clock advances 1/30 s per frame, so W held for 0.5 s is 15 frames of movement on any machine.
cat >"$dir/walk.txt" <<EOF
# time  event
0.0   screenshot_ui $dir/gui.png
0.1   key F1 press
0.2   screenshot $dir/start.png
0.25  key W down
0.75  key W up
0.8   screenshot $dir/moved.png
0.85  view ao
0.9   screenshot $dir/ao_ssao.png
0.95  method none
1.0   screenshot $dir/ao_none.png
1.05  key ESCAPE press
EOF
if xrun 300 "$OBSCURA" view --scene cornell --size 640x360 --script "$dir/walk.txt" \
    >"$dir/walk.out" 2>"$dir/walk.err"; then ok; else bad "scripted run failed: $(tail -3 "$dir/walk.err")"; fi
for f in gui start moved ao_ssao ao_none; do
    if [ -f "$dir/$f.png" ]; then ok; else bad "no screenshot $f.png"; fi
done

if [ -f "$dir/start.png" ]; then
    # Not blank: the whole image varies (the Cornell box's walls, blocks and shadows).
    read -r lo hi mean sd < <("$IMGCHECK" region 0 0 640 360 "$dir/start.png")
    if gt "$sd" 20 && gt "$hi" "$lo"; then ok; else bad "start.png looks blank (stddev $sd, $lo..$hi)"; fi
    # The image's size is the window's.
    read -r w h _ < <("$IMGCHECK" "$dir/start.png")
    if [ "$w" = 640 ] && [ "$h" = 360 ]; then ok; else bad "screenshot is ${w}x$h, want 640x360"; fi
fi
if [ -f "$dir/gui.png" ] && [ -f "$dir/start.png" ]; then
    # The panel's column (x 320..640): with it the region is ImGui's dark window and differs from
    # the same region without it (the picture is there then).
    read -r _ _ panel_mean _ < <("$IMGCHECK" region 370 60 250 250 "$dir/gui.png")
    read -r _ _ bare_mean _ < <("$IMGCHECK" region 370 60 250 250 "$dir/start.png")
    if lt "$panel_mean" 90 && gt "$(awk -v a="$bare_mean" -v b="$panel_mean" 'BEGIN { print a - b }')" 30; then ok
    else bad "no panel: the right side's mean is $panel_mean with the GUI and $bare_mean without"; fi
    # Beside it the picture, 320x180 at y 90 (the window's shape), between flat bars.
    read -r _ _ _ pic_sd < <("$IMGCHECK" region 0 100 320 160 "$dir/gui.png")
    read -r bar_lo bar_hi _ bar_sd < <("$IMGCHECK" region 0 280 320 80 "$dir/gui.png")
    if gt "$pic_sd" 20 && lt "$bar_sd" 2 && lt "$bar_hi" 40; then ok
    else bad "no letterboxed picture beside the panel: picture stddev $pic_sd, bar $bar_lo..$bar_hi (stddev $bar_sd)"; fi
fi
if [ -f "$dir/start.png" ] && [ -f "$dir/moved.png" ]; then
    d=$("$IMGCHECK" diff "$dir/start.png" "$dir/moved.png")
    if gt "$d" 2; then ok; else bad "W did not move the camera (mean difference $d)"; fi
fi
if [ -f "$dir/ao_ssao.png" ] && [ -f "$dir/ao_none.png" ]; then
    # The AO view: SSAO darkens the creases; none is white wherever there is geometry.
    read -r _ _ m_ssao _ < <("$IMGCHECK" region 0 0 640 360 "$dir/ao_ssao.png")
    read -r lo_none _ m_none _ < <("$IMGCHECK" region 0 0 640 360 "$dir/ao_none.png")
    if gt "$m_none" "$m_ssao" && gt "$("$IMGCHECK" diff "$dir/ao_ssao.png" "$dir/ao_none.png")" 1; then ok
    else bad "method switch: AO view mean $m_ssao (ssao) vs $m_none (none)"; fi
    if [ "$lo_none" -ge 250 ]; then ok; else bad "the AO view of none is not white (min $lo_none)"; fi
fi

# Camera presets: the number keys and Tab (sphere-on-plane has three distinct ones), and the
# mouse look (right button held while the cursor moves).
cat >"$dir/presets.txt" <<EOF
0.0   screenshot $dir/preset1.png
0.05  key 3 press
0.1   screenshot $dir/preset3.png
0.15  key TAB press
0.2   screenshot $dir/tab.png
0.25  move 100 100
0.3   mouse right down
0.35  move 300 100
0.4   mouse right up
0.45  screenshot $dir/look.png
0.5   resize 240 200
0.6   screenshot $dir/resized.png
0.65  quit
EOF
if xrun 300 "$OBSCURA" view --scene sphere-on-plane --gui off --size 320x180 --script "$dir/presets.txt" \
    >/dev/null 2>"$dir/presets.err"; then ok; else bad "preset run failed: $(tail -3 "$dir/presets.err")"; fi
for pair in "preset1 preset3" "preset3 tab" "tab look"; do
    set -- $pair
    if [ -f "$dir/$1.png" ] && [ -f "$dir/$2.png" ] && gt "$("$IMGCHECK" diff "$dir/$1.png" "$dir/$2.png")" 1; then ok
    else bad "$1 -> $2: the camera did not change"; fi
done
# A resized window renders at its new size (the renderer's targets follow the framebuffer).
read -r w h _ < <("$IMGCHECK" "$dir/resized.png" 2>/dev/null)
read -r _ _ _ sd < <("$IMGCHECK" region 0 0 240 200 "$dir/resized.png" 2>/dev/null)
if [ "${w:-0}" = 240 ] && [ "${h:-0}" = 200 ] && gt "${sd:-0}" 5; then ok; else bad "resize: screenshot ${w:-?}x${h:-?}, stddev ${sd:-?}"; fi

# ---- the mouse works the camera on the picture only ---------------------------------------------
# 640x360 with the panel: the right button dragged and the wheel on the bar above the picture
# (y < 90, under the overlay, which takes no input) leave the camera alone; dragged on the
# picture, it looks. Then the panel's left edge (x 320) dragged to x 400 narrows the panel, and
# the picture widens to 400x225.
cat >"$dir/mouse.txt" <<EOF
0.0   screenshot $dir/mouse0.png
0.05  move 100 40
0.1   mouse right down
0.15  move 300 40
0.2   mouse right up
0.25  scroll 5
0.3   screenshot $dir/mouse1.png
0.35  move 100 180
0.4   mouse right down
0.45  move 250 180
0.5   mouse right up
0.55  screenshot $dir/mouse2.png
0.6   move 320 200
0.65  mouse left down
0.7   move 360 200
0.75  move 400 200
0.8   mouse left up
0.9   screenshot $dir/dragged.png
0.95  quit
EOF
if xrun 300 "$OBSCURA" view --scene corner --size 640x360 --script "$dir/mouse.txt" >/dev/null 2>"$dir/mouse.err"; then ok
else bad "mouse run failed: $(tail -3 "$dir/mouse.err")"; fi
if [ -f "$dir/mouse1.png" ] && ! gt "$("$IMGCHECK" diff "$dir/mouse0.png" "$dir/mouse1.png")" 1; then ok
else bad "a drag or the wheel beside the picture moved the camera"; fi
if [ -f "$dir/mouse2.png" ] && gt "$("$IMGCHECK" diff "$dir/mouse1.png" "$dir/mouse2.png")" 1; then ok
else bad "a drag on the picture did not turn the camera"; fi
read -r w h _ < <("$IMGCHECK" "$dir/dragged.png" 2>/dev/null)
if [ "${w:-0}x${h:-0}" = 400x225 ]; then ok; else bad "dragging the panel's edge: the picture is ${w:-?}x${h:-?}, want 400x225"; fi

# ---- the panel beside the picture at the usual window sizes -------------------------------------
# The panel takes a column (at least 340 px at scale 1, 30 % of the width beyond, at most half),
# the picture the rest with the window's shape: `screenshot` (the picture alone) is as wide as the
# window less the panel, and the window shows that very picture (below the overlay's corner)
# beside the panel's dark column.
for size in 1024x768 1280x720 1600x900; do
    W=${size%x*} H=${size#*x}
    printf '0.1 screenshot %s\n0.1 screenshot_ui %s\n0.15 quit\n' "$dir/pic_$size.png" "$dir/win_$size.png" >"$dir/dock.txt"
    if ! timeout 300 xvfb-run -a -s "-screen 0 1700x1000x24" "$OBSCURA" view --scene cornell --method ssao --size "$size" \
        --script "$dir/dock.txt" >/dev/null 2>"$dir/dock.err"; then
        bad "$size: the viewer failed: $(tail -3 "$dir/dock.err")"
        continue
    fi
    read -r pw ph _ < <("$IMGCHECK" "$dir/pic_$size.png")
    if [ $((W - pw)) -ge 340 ] && [ $((2 * pw)) -ge "$W" ] &&
        [ "$(awk -v w="$W" -v h="$H" -v pw="$pw" -v ph="$ph" 'BEGIN { d = pw * h / w - ph; print (d < 1 && d > -1) }')" = 1 ]
    then ok; else bad "$size: the picture is ${pw}x$ph"; fi
    y0=$(((H - ph) / 2))
    "$IMGCHECK" region 0 40 "$pw" $((ph - 40)) "$dir/pic_$size.png" >"$dir/p1"
    "$IMGCHECK" region 0 $((y0 + 40)) "$pw" $((ph - 40)) "$dir/win_$size.png" >"$dir/p2"
    if cmp -s "$dir/p1" "$dir/p2"; then ok
    else bad "$size: the window's picture differs from the picture: $(cat "$dir/p2") vs $(cat "$dir/p1")"; fi
    read -r _ _ col_mean _ < <("$IMGCHECK" region $((pw + 10)) 40 $((W - pw - 20)) $((H - 80)) "$dir/win_$size.png")
    if lt "$col_mean" 90; then ok; else bad "$size: no panel beside the picture (the column's mean is $col_mean)"; fi
done

# ---- the reference view, screenshots with and without the panel, a scripted click --------------
# The reference is cached under XDG_CACHE_HOME: here, so the run neither reads nor fills the user's.
# The click: the panel's first control, "reference view (G)", sits at 640x360 at x 320 (640 - 320,
# the panel's column) + 8 padding + 9 (half the 19 px box), y 19 title + 8 padding + 9 = (337, 36).
# The script's clock stands still while the reference is traced, so ref.png shows it finished.
mkdir -p "$dir/cwd1" "$dir/cache"
cat >"$dir/ref.txt" <<EOF
0.0   screenshot $dir/plain.png
0.0   screenshot_ui $dir/plain_ui.png
0.1   move 337 36
0.2   mouse left down
0.3   mouse left up
0.5   screenshot $dir/ref.png
0.55  key W down
0.7   key W up
0.8   screenshot_ui $dir/stale_ui.png
0.85  quit
EOF
if (cd "$dir/cwd1" && XDG_CACHE_HOME="$dir/cache" xrun 300 "$OBSCURA" view --scene corner --method ssao --size 640x360 \
    --script "$dir/ref.txt" >/dev/null 2>"$dir/ref.err"); then ok; else bad "reference run failed: $(tail -3 "$dir/ref.err")"; fi
# The click reached the panel's checkbox (nothing else turns the view on in this script) ...
if grep -q "reference view on" "$dir/ref.err" && grep -q "reference: traced in" "$dir/ref.err"; then ok
else bad "the scripted click did not turn the reference view on: $(cat "$dir/ref.err")"; fi
# ... and moving the camera makes the reference stale.
if grep -q "reference: stale" "$dir/ref.err"; then ok; else bad "moving the camera did not mark the reference stale"; fi
# The panes, each 160x90, in the picture's 320x180 beside the panel: the method's AO (top left),
# the reference (top right) and the signed error (bottom left) each show the corner's walls (not
# one flat colour), the two AO panes agree roughly (ssao against AO_R) while the error pane (white
# where they agree, grey sky) is another image; the picture-sized screenshot holds all four.
if [ -f "$dir/ref.png" ]; then
    read -r w h _ < <("$IMGCHECK" "$dir/ref.png")
    if [ "$w" = 320 ] && [ "$h" = 180 ]; then ok; else bad "reference screenshot is ${w}x$h, want the picture's 320x180"; fi
    for pane in "method 0 0" "reference 160 0" "error 0 90" "view 160 90"; do
        set -- $pane
        read -r lo hi _ sd < <("$IMGCHECK" region "$2" "$3" 160 90 "$dir/ref.png")
        if gt "$sd" 5 && gt "$hi" "$lo"; then ok; else bad "reference view: the $1 pane is flat (stddev $sd, $lo..$hi)"; fi
    done
    read -r _ _ m_method _ < <("$IMGCHECK" region 0 0 160 90 "$dir/ref.png")
    read -r _ _ m_ref _ < <("$IMGCHECK" region 160 0 160 90 "$dir/ref.png")
    read -r _ _ m_err _ < <("$IMGCHECK" region 0 90 160 90 "$dir/ref.png")
    if lt "$(awk -v a="$m_method" -v b="$m_ref" 'BEGIN { d = a - b; print d < 0 ? -d : d }')" 10 &&
        gt "$(awk -v a="$m_err" -v b="$m_ref" 'BEGIN { d = a - b; print d < 0 ? -d : d }')" 20; then ok
    else bad "reference view panes: means method $m_method, reference $m_ref, error $m_err"; fi
else
    bad "no reference screenshot"
fi
# `screenshot` is the picture alone (320x180), `screenshot_ui` the window (640x360): the same
# frame, so the window holds that very picture at y 90 (the overlay is on the bar above it), and
# the panel beside it.
if [ -f "$dir/plain.png" ] && [ -f "$dir/plain_ui.png" ]; then
    read -r w h _ < <("$IMGCHECK" "$dir/plain.png")
    read -r uw uh _ < <("$IMGCHECK" "$dir/plain_ui.png")
    if [ "$w x $h, $uw x $uh" = "320 x 180, 640 x 360" ]; then ok
    else bad "screenshot ${w}x$h and screenshot_ui ${uw}x$uh, want the picture's 320x180 and the window's 640x360"; fi
    "$IMGCHECK" region 0 20 320 160 "$dir/plain.png" >"$dir/r1"
    "$IMGCHECK" region 0 110 320 160 "$dir/plain_ui.png" >"$dir/r2"
    if cmp -s "$dir/r1" "$dir/r2"; then ok
    else bad "the window's picture differs from the picture: $(cat "$dir/r2") vs $(cat "$dir/r1")"; fi
    read -r _ _ with_mean _ < <("$IMGCHECK" region 370 60 250 250 "$dir/plain_ui.png")
    if lt "$with_mean" 90; then ok; else bad "screenshot_ui has no panel: the column's mean is $with_mean"; fi
else
    bad "no plain.png / plain_ui.png"
fi
# No screenshots/ where the viewer ran: every screenshot above went to a named path.
if [ ! -e "$dir/cwd1/screenshots" ]; then ok; else bad "an empty screenshots/ appeared in the working directory"; fi

# The same camera again, by the key this time: from the cache, at once. P takes a screenshot with
# the default name, which makes screenshots/ (only then).
mkdir -p "$dir/cwd2"
printf '0.1 key G press\n0.2 screenshot %s\n0.25 key P press\n0.35 quit\n' "$dir/ref2.png" >"$dir/ref2.txt"
if (cd "$dir/cwd2" && XDG_CACHE_HOME="$dir/cache" xrun 300 "$OBSCURA" view --scene corner --method ssao --size 640x360 \
    --script "$dir/ref2.txt" >/dev/null 2>"$dir/ref2.err") && grep -q "reference: from the cache" "$dir/ref2.err"; then ok
else bad "the second reference did not come from the cache: $(cat "$dir/ref2.err")"; fi
if [ -f "$dir/ref.png" ] && [ -f "$dir/ref2.png" ] && ! gt "$("$IMGCHECK" diff "$dir/ref.png" "$dir/ref2.png")" 0.5; then ok
else bad "the cached reference view differs from the traced one"; fi
if [ "$(ls "$dir/cwd2/screenshots"/*.png 2>/dev/null | wc -l)" -eq 1 ]; then ok
else bad "P did not write one screenshot to screenshots/: $(ls -la "$dir/cwd2" 2>&1)"; fi

# ---- test mode: every camera x the given methods, tiny times ----------------------------------
mkdir -p "$dir/t"
if xrun 300 "$OBSCURA" view --scene cornell --size 160x120 --test-mode --seconds 0.05 --cycles 2 --methods none,ssao,hbao,ssdo --log "$dir/t/test.csv" \
    >"$dir/test.out" 2>"$dir/test.err"; then ok; else bad "test mode failed: $(tail -3 "$dir/test.err")"; fi
if [ -f "$dir/t/test.csv" ]; then
    rows=$(($(wc -l <"$dir/t/test.csv") - 1))
    ncam=$(tail -n +2 "$dir/t/test.csv" | cut -d, -f2 | sort -u | wc -l)
    if [ "$rows" -eq $((ncam * 4)) ] && [ "$ncam" -ge 1 ]; then ok; else bad "CSV has $rows rows for $ncam cameras x 4 methods"; fi
    # Every row: positive frames and FPS, and an ao time for every method but none.
    if awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
                { if ($col["frames"] < 2 || $col["fps"] <= 0 || $col["gbuffer_ms"] <= 0) exit 1
                  if ($3 != "none" && $col["ao_ms"] <= 0) exit 1 }' "$dir/t/test.csv"; then ok
    else bad "CSV rows without frames, FPS or pass times: $(cat "$dir/t/test.csv")"; fi
    # Every pass that ran reads more than 0 ms in every row, GPU and CPU (an empty cell is a pass
    # that did not run): on llvmpipe, with the window's framebuffer bound, timestamps were taken
    # late and the frame's last pass, tonemap, read 0.0000 while render measured it
    # (src/gpu/timer.c). gbuffer, compose and tonemap run in every frame.
    if awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) { col[$i] = i; if ($i ~ /_ms$/) ms[i] = $i }; next }
                { for (i in ms) if ($i != "" && $i + 0 <= 0) { print $3 " " $2 ": " ms[i] " = " $i; bad = 1 }
                  split("gbuffer_ms compose_ms tonemap_ms", always, " ")
                  for (k in always) if ($col[always[k]] == "") { print $3 " " $2 ": no " always[k]; bad = 1 }
                  # A pass with a GPU time has its CPU time, and the other way round.
                  for (i in ms) { c = ms[i]; sub(/_ms$/, "_cpu_ms", c)
                      if (c in col && ($i == "") != ($col[c] == "")) { print $3 " " $2 ": " ms[i] " and " c; bad = 1 } } }
                END { exit bad }' "$dir/t/test.csv" >"$dir/t/zero"; then ok
    else bad "CSV pass times of 0 ms or missing: $(cat "$dir/t/zero")"; fi
    shots=$(ls "$dir/t"/*.png 2>/dev/null | wc -l)
    if [ "$shots" -eq "$rows" ]; then ok; else bad "$shots screenshots for $rows rows"; fi
    if grep -q "^FPS" "$dir/test.out"; then ok; else bad "no summary table: $(cat "$dir/test.out")"; fi
else
    bad "no test-mode CSV"
fi
for f in "$dir"/t/*.png; do
    [ -f "$f" ] || continue
    read -r _ _ _ sd < <("$IMGCHECK" region 0 0 160 120 "$f")
    if gt "$sd" 5; then ok; else bad "test-mode screenshot $f is blank"; fi
    break
done

# ---- shader reload (R, development builds): from OBSCURA_DATA_DIR/shaders ------------------------
# A broken copy: the error names the file and line and the viewer keeps running on the old
# shaders; a good copy reloads.
mkdir -p "$dir/data"
cp -r "$(dirname "$0")/../shaders" "$dir/data/shaders"
cp "$dir/data/shaders/ssao.glsl" "$dir/ssao.good"
sed -i '25i this is not GLSL;' "$dir/data/shaders/ssao.glsl"
printf '0.1 key R press\n0.2 screenshot %s\n0.3 quit\n' "$dir/after_bad_reload.png" >"$dir/reload.txt"
if OBSCURA_DATA_DIR="$dir/data" xrun 120 "$OBSCURA" view --scene cornell --method ssao --gui off --size 160x120 --script "$dir/reload.txt" \
    >/dev/null 2>"$dir/reload_bad.err"; then ok; else bad "bad reload ended the viewer: $(tail -2 "$dir/reload_bad.err")"; fi
if grep -q "development builds" "$dir/reload_bad.err"; then
    echo "view: a release build, shader reload not tested"
else
    if grep -q "reload failed.*shaders/ssao.glsl:25" "$dir/reload_bad.err" && [ -f "$dir/after_bad_reload.png" ]; then ok
    else bad "bad reload: $(cat "$dir/reload_bad.err")"; fi
    cp "$dir/ssao.good" "$dir/data/shaders/ssao.glsl"
    printf '0.1 key R press\n0.3 quit\n' >"$dir/reload2.txt"
    if OBSCURA_DATA_DIR="$dir/data" xrun 120 "$OBSCURA" view --scene cornell --gui off --size 160x120 --script "$dir/reload2.txt" \
        >/dev/null 2>"$dir/reload_good.err" && grep -q "shaders reloaded" "$dir/reload_good.err"; then ok
    else bad "good reload: $(cat "$dir/reload_good.err")"; fi
fi

# ---- clean exits --------------------------------------------------------------------------------
# The window's close button (the same flag GLFW sets), after one frame.
printf '0.1 close\n' >"$dir/close.txt"
if xrun 120 "$OBSCURA" view --scene corner --size 200x150 --script "$dir/close.txt" \
    >/dev/null 2>"$dir/close.err"; then ok; else bad "closing the window: exit $? ($(tail -2 "$dir/close.err"))"; fi

# A bad scene: one line, exit 3, before any window opens.
xrun 60 "$OBSCURA" view --scene "$dir/missing.obj" >/dev/null 2>"$dir/bad.err"
code=$?
if [ $code -eq 3 ] && [ "$(wc -l <"$dir/bad.err")" -eq 1 ] && grep -q "missing.obj" "$dir/bad.err"; then ok
else bad "bad scene: exit $code, stderr: $(cat "$dir/bad.err")"; fi

# Test mode aborted (a method that does not exist): usage error, no log left behind.
xrun 60 "$OBSCURA" view --scene corner --test-mode --methods ssao,nope --log "$dir/t2.csv" \
    >/dev/null 2>"$dir/bad2.err"
code=$?
if [ $code -eq 2 ] && [ ! -e "$dir/t2.csv" ] && grep -q "nope" "$dir/bad2.err"; then ok
else bad "unknown test-mode method: exit $code, $(cat "$dir/bad2.err")"; fi

# A malformed script line: exit 3 naming the line.
printf '0.0 key W sideways\n' >"$dir/bad.txt"
env -u DISPLAY "$OBSCURA" view --scene corner --script "$dir/bad.txt" >/dev/null 2>"$dir/bad3.err"
code=$?
if [ $code -eq 3 ] && grep -q "bad.txt:1" "$dir/bad3.err"; then ok; else bad "bad script: exit $code, $(cat "$dir/bad3.err")"; fi

# --orbit plays from the start (the camera moves between frames); Space pauses it (it stays).
cat >"$dir/orbit.txt" <<EOF
0.1   screenshot $dir/orbit1.png
0.2   screenshot $dir/orbit2.png
0.25  key SPACE press
0.3   screenshot $dir/paused1.png
0.4   screenshot $dir/paused2.png
0.45  quit
EOF
if xrun 300 "$OBSCURA" view --scene corner --gui off --size 160x120 --orbit 90 --path-frames 8 --script "$dir/orbit.txt" \
    >/dev/null 2>"$dir/orbit.err"; then ok; else bad "orbit run failed: $(tail -3 "$dir/orbit.err")"; fi
if [ -f "$dir/orbit1.png" ] && gt "$("$IMGCHECK" diff "$dir/orbit1.png" "$dir/orbit2.png")" 1; then ok
else bad "--orbit: the camera did not move while playing"; fi
if [ -f "$dir/paused1.png" ] && ! gt "$("$IMGCHECK" diff "$dir/paused1.png" "$dir/paused2.png")" 1; then ok
else bad "Space: the camera still moved while paused"; fi

# An unknown option: usage error, before anything else.
"$OBSCURA" view --bogus >/dev/null 2>"$dir/bad4.err"
code=$?
if [ $code -eq 2 ] && grep -q "unknown option '--bogus'" "$dir/bad4.err"; then ok; else bad "unknown option: exit $code, $(cat "$dir/bad4.err")"; fi

# --set for a method other than the starting one switches methods while the settings are built,
# before the window exists: the viewer starts (no GLFW call on a NULL window) ...
printf '0.1 quit\n' >"$dir/quit.txt"
if xrun 120 "$OBSCURA" view --scene corner --gui off --size 160x120 --set hbao.radius=1 --script "$dir/quit.txt" \
    >/dev/null 2>"$dir/set_other.err"; then ok; else bad "--set for another method: exit $? ($(tail -2 "$dir/set_other.err"))"; fi
# The viewer takes the options every rendering command takes (one parser): with the same camera,
# lights, shadows and method its first frame is byte for byte what `render` writes.
common=(--scene corner --size 160x120 --eye 1.5,1.2,1.5 --target 0,0,0 --method hbao --shadow hard
        --light 'spot pos=1,2,1 dir=-1,-2,-1 cone=20,30 intensity=8')
printf '0.1 screenshot %s\n0.2 quit\n' "$dir/common_view.png" >"$dir/common.txt"
if xrun 120 "$OBSCURA" view "${common[@]}" --gui off --script "$dir/common.txt" >/dev/null 2>"$dir/common.err" &&
    "$OBSCURA" render "${common[@]}" --out "$dir/common_render.png" 2>>"$dir/common.err" &&
    cmp -s "$dir/common_view.png" "$dir/common_render.png"; then ok
else bad "view with render's options differs from render: $(tail -2 "$dir/common.err")"; fi
# --gpu belongs to the headless commands: the viewer's context is its window's.
"$OBSCURA" view --gpu sw >/dev/null 2>"$dir/gpu.err"
code=$?
if [ $code -eq 2 ] && grep -q "unknown option '--gpu'" "$dir/gpu.err"; then ok; else bad "view --gpu: exit $code, $(cat "$dir/gpu.err")"; fi
# ... and a bad one is reported as such even with a quality preset (whose method switch back
# must not clear the library's error first).
env -u DISPLAY "$OBSCURA" view --scene corner --quality high --set hbao.nope=1 >/dev/null 2>"$dir/bad5.err"
code=$?
if [ $code -eq 2 ] && grep -q "nope" "$dir/bad5.err"; then ok; else bad "bad --set with --quality: exit $code, $(cat "$dir/bad5.err")"; fi

# No display at all: exit 5 with a hint, not a crash.
env -u DISPLAY -u WAYLAND_DISPLAY "$OBSCURA" view --scene corner >/dev/null 2>"$dir/nodisp.err"
code=$?
if [ $code -eq 5 ] && grep -q "xvfb-run" "$dir/nodisp.err"; then ok; else bad "no display: exit $code, $(cat "$dir/nodisp.err")"; fi

echo "view: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
