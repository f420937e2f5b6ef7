#!/bin/sh
# window.t — gbview's window as a user drives it, on a virtual X display
# with a window manager (Xvfb, openbox) and xdotool's keys and mouse: the
# fly camera, the mouse, C, M without a bake, T, H, P twice without
# overwriting, and Esc, the close button and SIGINT ending it within one
# frame, also in the middle of topo's parts and of implicit's links (on
# ../shared's Sponza).
# The view is read back from B's bookmark line, the rest from --timings'
# log (a line a frame, 'quit asked' once). No check depends on time: the
# waits have limits against a hang only. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
. "$(dirname "$0")/x_session.sh"
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs gbview voxelize thin segment
for program in Xvfb openbox xdotool; do
    if ! command -v $program >/dev/null 2>&1; then
        missing "$program is not installed (make deps)"
        tap_done
        exit
    fi
done
x_start || { missing "Xvfb did not start"; tap_done; exit; }

# Mesa's GLX driver is unloaded at exit still holding a few hundred bytes;
# preloaded, it stays mapped and LeakSanitizer can name (and waive) it.
glx_driver=$(ls /usr/lib/*/dri/swrast_dri.so 2>/dev/null | head -1)

# Starts gbview ARGS in $dir with its log in $dir/log; sets $pid and $wid.
# timeout: a hang fails the test (status 124) rather than the whole suite.
start_gbview() {
    (cd "$dir" && exec env ${glx_driver:+LD_PRELOAD=$glx_driver} timeout 600 \
        "$GB_BIN/gbview" --timings "$@" >"$dir/log" 2>"$dir/err") &
    pid=$!
    wid=$(gbview_window)
    xdotool windowactivate --sync "$wid" 2>/dev/null
}

# The view as B prints it (the bookmark line B adds to the log).
bookmark() {
    before=$(count_lines '^gbview: camera position' "$dir/log")
    xdotool key b
    wait_for "^gbview: camera position" "$dir/log" 60 || return
    until [ "$(count_lines '^gbview: camera position' "$dir/log")" -gt "$before" ]; do
        sleep 0.1
    done
    grep '^gbview: camera position' "$dir/log" | sed -n "$((before + 1))p"
}

# Drags with button $1 from ($2, $3) to ($4, $5) in the window and prints
# the view after, dragging again (at most 5 times) while it is still $6:
# once, in a sanitized run beside hard_cases.t, a right drag left the view
# as it was, as if the drag never reached the window (not reproduced under
# load since). A drag gbview does not follow still fails the check after.
drag() {
    for try in 1 2 3 4 5; do
        xdotool mousemove --window "$wid" "$2" "$3" mousedown "$1" \
            mousemove --window "$wid" "$4" "$5" mouseup "$1"
        after=$(bookmark)
        [ "$after" != "$6" ] && break
    done
    echo "$after"
}

# At most one frame drew after the quit was asked.
frames_after_quit() {
    sed -n '/^gbview: quit asked/,$p' "$dir/log" | grep -c '^gbview: frame'
}

# --- the direct method: the camera, the keys, screenshots, Esc.
echo old >"$dir/gbview-000.png"
start_gbview --resolution 160x120 "$scene"
ok "$([ -n "$wid" ]; echo $?)" "the window opens"
wait_for ', final' "$dir/log" 120
ok $? "the image becomes final (a line ', final')"

first=$(bookmark)
ok "$(echo "$first" | grep -q 'camera position 278 273 -800 target 278 273 -799 up 0 1 0 fov 39.3077 resolution 160 120'; echo $?)" \
    "B prints the scene's camera as a .scene line"
# W is read as held at each frame (glfwGetKey): it stays down until a frame
# of the moving view is logged, so that a loaded machine, which may take
# the press and the release in one poll, cannot lose it.
moving=$(count_lines ', moving' "$dir/log")
xdotool keydown w
for i in $(seq 600); do   # 60 s: a limit against a hang, never a measure
    [ "$(count_lines ', moving' "$dir/log")" -gt "$moving" ] && break
    sleep 0.1
done
xdotool keyup w
second=$(bookmark)
ok "$([ -n "$second" ] && [ "$second" != "$first" ] &&
      [ "$(echo "$second" | cut -d' ' -f5)" != 278 ] || [ "$(echo "$second" | cut -d' ' -f7)" != -800 ]; echo $?)" \
    "W moves the eye"
ok "$(sed -n '/, final/,$p' "$dir/log" | grep -q '^gbview: frame .*, moving.*, presented'; echo $?)" \
    "... and a final image gives way to the moving view's"
eval "$(xdotool getwindowgeometry --shell "$wid")"
third=$(drag 1 80 60 120 70 "$second")
target2=$(echo "$second" | cut -d' ' -f7-9)
target3=$(echo "$third" | cut -d' ' -f7-9)
position2=$(echo "$second" | cut -d' ' -f3-5)
position3=$(echo "$third" | cut -d' ' -f3-5)
ok "$([ "$position3" = "$position2" ] && [ "$target3" != "$target2" ]; echo $?)" \
    "dragging with the left button turns the view, the eye stays"
fourth=$(drag 3 80 60 110 60 "$third")
position4=$(echo "$fourth" | cut -d' ' -f3-5)
ok "$([ -n "$fourth" ] && [ "$position4" != "$position3" ]; echo $?)" \
    "dragging with the right button orbits: the eye moves"
xdotool key c
fifth=$(bookmark)
ok "$([ "$fifth" = "$first" ]; echo $?)" "C goes back to the scene's camera"

xdotool key m
wait_for '^gbview: octree skipped' "$dir/log" 60
ok "$(grep -q '^gbview: topo skipped: .*--bake' "$dir/log" &&
      grep -q '^gbview: octree skipped: ' "$dir/log"; echo $?)" \
    "M without a bake: topo and octree are skipped, saying why"
wait_for_title "$wid" ' - flc - ' 60
ok $? "... and flc is shown"
xdotool key t
wait_for_title "$wid" ' - flc - direct$' 60
ok $? "T: the direct light alone"
xdotool key h
wait_for '^gbview: keys shown' "$dir/log" 60
ok $? "H shows the keys"
xdotool key p
wait_for '^gbview: screenshot: gbview-001.png' "$dir/log" 60
xdotool key p
wait_for '^gbview: screenshot: gbview-002.png' "$dir/log" 60
ok "$([ -s "$dir/gbview-001.png" ] && [ -s "$dir/gbview-002.png" ] &&
      [ "$(cat "$dir/gbview-000.png")" = old ]; echo $?)" \
    "P twice: two new screenshots, an older one kept"
xdotool key Escape
wait $pid
ok $? "Esc: exit status 0"
ok "$([ "$(frames_after_quit)" -le 1 ]; echo $?)" "Esc: at most one frame after it"

# --- the close button (openbox's Alt+F4 asks the window to close).
start_gbview --resolution 160x120 "$scene"
wait_for '^gbview: frame' "$dir/log" 120
xdotool key alt+F4
wait $pid
ok $? "the close button: exit status 0"

# --- Esc in the middle of topo's parts.
bake=$dir/bake
topo_bake "$bake" "$scene" 48
ok $? "bake for topo"
start_gbview --resolution 256x256 --method topo --bake "$bake" --budget 5 "$scene"
wait_for 'part [1-9][0-9]*/[0-9]+' "$dir/log" 120
ok $? "topo at a 5 ms budget draws its image in parts"
xdotool key Escape
wait $pid
ok $? "Esc during topo's parts: exit status 0"
ok "$([ "$(frames_after_quit)" -le 1 ]; echo $?)" "... after at most one more part"

# --- SIGINT (Ctrl-C in the terminal) during the same.
start_gbview --resolution 256x256 --method topo --bake "$bake" --budget 5 "$scene"
wait_for 'part [1-9][0-9]*/[0-9]+' "$dir/log" 120
kill -INT $pid
wait $pid
ok $? "SIGINT during topo's parts: exit status 0"
ok "$([ "$(frames_after_quit)" -le 1 ]; echo $?)" "... after at most one more part"

# --- --frames 1 -o with implicit: the saved image is implicit's, whole, not
# the direct light shown while its links are built.
"$GB_BIN/gbview" --headless --resolution 64x64 --method implicit "$scene" -o "$dir/implicit.exr"
(cd "$dir" && exec env ${glx_driver:+LD_PRELOAD=$glx_driver} timeout 600 "$GB_BIN/gbview" \
    --resolution 64x64 --method implicit --frames 1 -o "$dir/window.exr" "$scene" \
    >"$dir/log" 2>"$dir/err")
ok $? "implicit --frames 1 -o in a window: exit status 0"
cmp -s "$dir/implicit.exr" "$dir/window.exr"
ok $? "... and its image is the headless one, links and all"

# --- Esc while implicit's links are built beside the frames (Sponza: tens
# of seconds of links on two cores).
start_gbview --resolution 160x90 --method implicit "$GB_ROOT/scenes/shared/sponza.scene"
wait_for ', presented, setup [0-9]+ %' "$dir/log" 300
ok $? "implicit's links: the window shows direct light and the setup's progress meanwhile"
xdotool key Escape
wait $pid
ok $? "Esc during the links: exit status 0"
ok "$([ "$(frames_after_quit)" -le 1 ]; echo $?)" "... after at most one more frame"

tap_done
