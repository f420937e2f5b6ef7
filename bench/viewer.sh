#!/bin/sh
# viewer.sh — gbview's window as a user meets it, on this machine's OpenGL
# (llvmpipe here), in a real window on a virtual display (Xvfb, openbox,
# xdotool; tests/cli/x_session.sh): for every scene, window size and
# method, with the default frame budget and with --budget 0 (whole frames,
# as before the budget) in the same run:
#   first frame   seconds from the start to the method's first image in the
#                 window (the log's own clock: the window's creation; scene
#                 loading before it is in "start"); implicit and flc-iv:
#                 after their links (direct light is shown meanwhile)
#   start         wall seconds from the command to that first image
#   latency       ms from a mouse event to the frame that shows it on
#                 screen, median and 95th percentile over a drag of
#                 VIEWER_DRAG_SECONDS (events every 50 ms)
#   fps moving    frames shown a second during the drag
#   converge      seconds from the last moving frame to the final image
#                 (flc: its 256 samples; ">N": not within VIEWER_LIMIT;
#                 --budget 0: 0, every frame is whole)
#   peak memory   MiB (GNU time's maximum resident set)
# The timings are the window's own (gbview --timings: a log line a frame).
#
# VIEWER_SCENES: scene files (default the Cornell box of the tree and
#   scenes/shared/{sponza,staircase}.scene); VIEWER_LARGE=1 adds Sponza
#   subdivided to 4.25 M triangles (bench/subdivide_obj.py; direct, octree
#   and flc only, as the issue asks);
# VIEWER_SIZES (default "512x512 1280x720"); VIEWER_METHODS (default
#   "direct octree flc implicit topo flc-iv"); VIEWER_BUDGETS (default
#   "default 0"); VIEWER_FIRST_LIMIT seconds a run may wait for its first
#   image (600), VIEWER_LIMIT for the final one (600);
# VIEWER_BAKE: a folder of bakes NAME/ (default: made here with make bake).
# Prints a Markdown table on stdout.

. "$(dirname "$0")/common.sh"
. "$root/tests/cli/x_session.sh"
needs gbview
VIEWER_SCENES=${VIEWER_SCENES:-"$root/scenes/cornell/cornell.scene $root/scenes/shared/sponza.scene $root/scenes/shared/staircase.scene"}
VIEWER_SIZES=${VIEWER_SIZES:-"512x512 1280x720"}
VIEWER_METHODS=${VIEWER_METHODS:-"direct octree flc implicit topo flc-iv"}
VIEWER_BUDGETS=${VIEWER_BUDGETS:-"default 0"}
VIEWER_LIMIT=${VIEWER_LIMIT:-600}
VIEWER_FIRST_LIMIT=${VIEWER_FIRST_LIMIT:-600}
VIEWER_DRAG_SECONDS=${VIEWER_DRAG_SECONDS:-3}
VIEWER_BAKE=${VIEWER_BAKE:-$dir/bakes}
trap 'x_stop; rm -rf "$dir"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
x_start || { echo "viewer.sh: Xvfb did not start" >&2; exit 1; }

# The bake of scene $1 in $VIEWER_BAKE/NAME (make bake, once; the large
# scene only its light octree, NAME.lot: octree draws it by the walk).
bake_of() {
    name=$(basename "$1" .scene)
    target=bake
    case $name in *-large) target=$VIEWER_BAKE/$name/$name.lot ;; esac
    if [ ! -f "$VIEWER_BAKE/$name/$name.lot" ]; then
        mkdir -p "$VIEWER_BAKE/$name"
        make -s -C "$root" "$target" SCENE="$1" BAKE="$VIEWER_BAKE/$name" BIN="$GB_BIN" \
            >"$dir/bake.log" 2>&1 || { tail -5 "$dir/bake.log" >&2; return 1; }
    fi
    echo "$VIEWER_BAKE/$name"
}

# The log's lines from the last moving frame on, into $dir/after.
after_moving() {
    from=$(grep -n ', moving' "$dir/log" | tail -1 | cut -d: -f1)
    tail -n +"${from:-1}" "$dir/log" >"$dir/after"
}

# The log's clock (t S s) of the log line on stdin.
clock() {
    sed -n 's/.*, t \([0-9.]*\) s,.*/\1/p'
}

# The large scene: Sponza split to 4.25 M triangles, its materials linked.
large_scene() {
    large=$dir/large
    mkdir -p "$large"
    sponza=$root/../shared/scenes/sponza-dabrovic
    for f in "$sponza"/*; do ln -sf "$f" "$large/"; done
    rm -f "$large/sponza.obj"
    python3 "$root/bench/subdivide_obj.py" "$sponza/sponza.obj" 3 "$large/sponza-large.obj" >&2 &&
        sed 's|^mesh .*|mesh sponza-large.obj|' "$root/scenes/shared/sponza.scene" \
            >"$large/sponza-large.scene" &&
        echo "$large/sponza-large.scene"
}

# The median and the 95th percentile of the numbers on stdin.
percentiles() {
    sort -n | awk '{ v[NR] = $1 } END {
        if (NR == 0) { print "- / -"; exit }
        m = v[int((NR + 1) / 2)]; p = v[int(0.95 * NR + 0.999)]
        printf "%.0f / %.0f", m, p }'
}

# One run: gbview $@ in a window; prints the table's measured columns.
measure() {
    rm -f "$dir/log"
    start=$(date +%s.%N)
    /usr/bin/time -f "%M" -o "$dir/time" "$GB_BIN/gbview" --timings --quiet "$@" \
        >"$dir/log" 2>"$dir/err" &
    pid=$!
    if ! wait_for ', presented$|, presented, latency' "$dir/log" "$VIEWER_FIRST_LIMIT"; then
        kill $pid 2>/dev/null
        wait $pid 2>/dev/null
        if [ -z "$retried" ]; then  # once: a run that shows no image is tried once more
            retried=1
            measure "$@"
        else
            echo "| no image within ${VIEWER_FIRST_LIMIT} s: $(tail -1 "$dir/err") | | | | | |"
        fi
        retried=
        return
    fi
    shown=$(date +%s.%N)
    wid=$(gbview_window)
    xdotool windowactivate --sync "$wid" 2>/dev/null
    wait_for ', (final|presented)' "$dir/log" "$VIEWER_LIMIT"
    xdotool mousemove --window "$wid" 100 100 mousedown 1
    steps=$((VIEWER_DRAG_SECONDS * 20))
    i=0
    while [ $i -lt $steps ]; do
        xdotool mousemove_relative -- 2 1
        sleep 0.05
        i=$((i + 1))
    done
    xdotool mouseup 1
    moved=$(grep -c ', moving' "$dir/log")
    after_moving
    waited=0
    until grep -q ', final' "$dir/after" || [ $waited -ge $((VIEWER_LIMIT * 10)) ]; do
        sleep 0.1
        waited=$((waited + 1))
        after_moving
    done
    xdotool key --window "$wid" Escape
    wait $pid
    first=$(grep -E ', presented$|, presented, latency' "$dir/log" | head -1 | clock)
    after_moving
    last_moving=$(head -1 "$dir/after" | clock)
    final=$(grep ', final' "$dir/after" | head -1 | clock)
    latency=$(grep ', moving.*latency' "$dir/log" | sed 's/.*latency \([0-9.]*\) ms.*/\1/' |
        percentiles)
    fps=$(grep ', moving.*, presented' "$dir/log" | sed 's/.*, t \([0-9.]*\) s,.*/\1/' |
        awk 'NR == 1 { a = $1 } { b = $1; n = NR } END { if (n > 1 && b > a) printf "%.1f", (n - 1) / (b - a); else print "-" }')
    converge=$(awk -v a="$last_moving" -v b="$final" -v l="$VIEWER_LIMIT" \
        'BEGIN { if (b == "") printf ">%d", l; else printf "%.1f", b - a }')
    memory=$(awk '{ printf "%.0f", $1 / 1024 }' "$dir/time")
    startup=$(awk -v a="$start" -v b="$shown" 'BEGIN { printf "%.1f", b - a }')
    echo "| $first | $startup | $latency | $fps | $converge | $memory |"
    [ "$moved" -gt 0 ] || echo "viewer.sh: no moving frame logged for $*" >&2
}

echo "gbview in a window on $(glxinfo -B 2>/dev/null | sed -n 's/.*OpenGL renderer string: //p' | head -1)" \
    "${DISPLAY:+(Xvfb)}, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
echo "| scene | window | method | budget ms | first frame (s) | start (s) | latency median / p95 (ms) | fps moving | converge (s) | peak memory (MiB) |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"
scenes=$VIEWER_SCENES
[ "$VIEWER_LARGE" = 1 ] && scenes="$scenes $(large_scene)"
for scene in $scenes; do
    name=$(basename "$scene" .scene)
    methods=$VIEWER_METHODS
    case $name in *-large) methods="direct octree flc" ;; esac
    bake=
    case " $methods " in *" octree "* | *" topo "*) bake=$(bake_of "$scene") || continue ;; esac
    for size in $VIEWER_SIZES; do
        for method in $methods; do
            for budget in $VIEWER_BUDGETS; do
                options="--resolution $size --method $method ${bake:+--bake $bake}"
                case $name in *-large) options="$options --atlas none" ;; esac
                [ "$budget" = default ] || options="$options --budget $budget"
                shown_budget=$budget
                [ "$budget" = default ] && shown_budget=50
                printf "| %s | %s | %s | %s " "$name" "$size" "$method" "$shown_budget"
                measure $options "$scene"
            done
        done
    done
done
