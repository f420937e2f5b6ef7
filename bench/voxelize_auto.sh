#!/bin/sh
# voxelize_auto.sh — voxelize -r auto (tools/voxelize/auto_resolution.h) on
# AUTO_SCENES (default the two rooms, the two Cornell boxes, the classroom,
# the bunny, Sponza, the staircase and the living room):
#   the resolution chosen, and whether three resolutions agreed (settled);
#   the seconds of voxelize -r auto against voxelize -r CHOSEN, same run;
#   where it settled, the topo bake (voxelize, thin --grid, segment with the
#   gates fitted) at CHOSEN and at twice it: its seconds, the skeleton's
#   nodes, and the relative MSE (imgdiff) of gbview --method topo at
#   AUTO_SIZE (default 64x64) from the CHOSEN bake against the 2x one.
# Prints a Markdown table on stdout. Run by `make bench`.

. "$(dirname "$0")/common.sh"
AUTO_SIZE=${AUTO_SIZE:-64x64}
s=$root/scenes
AUTO_SCENES=${AUTO_SCENES:-"$s/two-rooms/two-rooms.scene $s/cornell/cornell.scene $s/shared/cornell-original.scene $s/shared/classroom.scene $s/shared/bunny.scene $s/shared/sponza.scene $s/shared/staircase.scene $s/shared/living-room.scene"}

seconds() { awk '{ print $1 }' "$1"; }

# bake SCENE NAME R: the topo bake at -r R in $dir/R, its seconds in $dir/R.time
bake() {
    b=$dir/$3
    mkdir -p "$b"
    /usr/bin/time -f "%e" -o "$b.time" sh -c '
        "$1/voxelize" -q -r "$4" "$2" -o "$5/$3.vdb" &&
        "$1/thin" -q -s "$5/$3.vdb" -o "$5/$3.skel" --grid "$5/$3.grid.vdb" >"$5/thin.stats" &&
        "$1/segment" -q "$5/$3.skel" --voxels "$5/$3.vdb" --grid "$5/$3.grid.vdb" -o "$5/$3.seg"' \
        sh "$GB_BIN" "$1" "$2" "$3" "$b" || exit 1
}

echo "voxelize -r auto; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
echo "| scene | chosen | settled | auto s | -r chosen s | bake s at chosen / 2x | skeleton nodes at chosen / 2x | topo image against the 2x bake: relative MSE |"
echo "|---|---:|---|---:|---:|---|---|---:|"
for scene in $AUTO_SCENES; do
    name=$(basename "$scene" .scene)
    /usr/bin/time -f "%e" -o "$dir/auto.time" "$GB_BIN/voxelize" -r auto "$scene" \
        -o "$dir/auto.vdb" 2>"$dir/auto.err" || { cat "$dir/auto.err" >&2; exit 1; }
    chosen=$(sed -n 's/^voxelize: -r auto: \([0-9]*\) .*/\1/p' "$dir/auto.err")
    settled=no
    grep -q "the same at three resolutions" "$dir/auto.err" && settled=yes
    /usr/bin/time -f "%e" -o "$dir/plain.time" "$GB_BIN/voxelize" -q -r "$chosen" "$scene" \
        -o "$dir/plain.vdb" || exit 1
    bakes="-" nodes="-" error="-"
    if [ $settled = yes ]; then
        double=$((2 * chosen))
        bake "$scene" "$name" "$chosen"
        nodes_chosen=$(awk '$1 == "nodes" { print $2 }' "$dir/$chosen/thin.stats")
        bake "$scene" "$name" "$double"
        nodes_double=$(awk '$1 == "nodes" { print $2 }' "$dir/$double/thin.stats")
        for r in "$chosen" "$double"; do
            "$GB_BIN/gbview" --headless --quiet --method topo --bake "$dir/$r" -r "$AUTO_SIZE" \
                -o "$dir/$r.exr" "$scene" || exit 1
        done
        bakes="$(seconds "$dir/$chosen.time") / $(seconds "$dir/$double.time")"
        nodes="$nodes_chosen / $nodes_double"
        error=$(relative_mse "$dir/$chosen.exr" "$dir/$double.exr")
    fi
    echo "| $name | $chosen | $settled | $(seconds "$dir/auto.time") | $(seconds "$dir/plain.time") | $bakes | $nodes | $error |"
done
