#!/bin/sh
# thin.sh — wall time, CPU time and peak memory of thin (skeleton and
# nearest-node grid, files written) on voxelized scenes at several
# resolutions, with the node and edge counts and the cost per empty voxel
# (which stays about flat when the cost is linear in the empty voxels).
# voxelize makes the input first; its time is not counted.
#
# The peer, in the same run: right after thin, on the same .vdb,
# bench/skeletonize_3d.py runs scikit-image's skeletonize_3d (Lee 1994) on
# the same empty voxels (a dense boolean array of grid_size). Column
# "skimage cpu s" is the process CPU time of the skeletonize_3d call alone
# (time.process_time; reading the file and building the array not counted).
# The peer runs on one thread, so the ratios compare it with thin on one
# thread, run again with -j 1 for them: "thin / skimage" is the CPU time
# (user + system) of that whole thin command (reading the .vdb, cavities,
# collapse, graph, nearest-node grid, writing both files) over "skimage cpu
# s"; "skeleton / skimage" compares the thinning alone: the "cpu seconds
# skeleton" of its --stats (from the maps to the graph: no file read or
# written, no nearest-node grid) over the same. Below 1, thin is the faster.
# The other columns are thin's default run (2 threads). The peer's empty
# voxel count must equal thin's, else the ratio is "-". Rows above THIN_PEER_MAX have "-" there; a missing peer (no
# python3-skimage or python3-openvdb) gives "-" and one line on stderr.
# Context only, not a ratio (../shared/ANCHORS.md, measured on another
# day): the DGCI 2013 authors' thinning took 6.1 s on Sponza at 256; the
# targets are 1.7 s at 256 and 15 s at 512, under 2 GiB.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the
# repository; THIN_SCENES: scene files (default the Cornell box and Sponza);
# THIN_RESOLUTIONS (default 64 128 256 512); THIN_OPTIONS: extra options;
# THIN_PEER_MAX: the largest resolution the peer runs at (default 256; 0:
# no peer); THIN_PYTHON: the python with the Debian modules (default
# /usr/bin/python3). cpu s is user + system time; wall s includes reading
# the .vdb and writing both files.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
THIN_SCENES=${THIN_SCENES:-"$GB_ROOT/scenes/shared/cornell-original.scene $GB_ROOT/scenes/shared/sponza.scene"}
THIN_RESOLUTIONS=${THIN_RESOLUTIONS:-"64 128 256 512"}
THIN_PEER_MAX=${THIN_PEER_MAX:-256}
THIN_PYTHON=${THIN_PYTHON:-/usr/bin/python3}
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-thin.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

if [ ! -x "$GB_BIN/thin" ] || [ ! -x "$GB_BIN/voxelize" ]; then
    echo "thin.sh: thin or voxelize not built in $GB_BIN"
    exit 1
fi
timer=
if /usr/bin/time -v true >/dev/null 2>&1; then
    timer="/usr/bin/time -v -o $dir/time"
fi

# The peer: off when THIN_PEER_MAX is 0, or (one line on stderr) when it
# cannot run here.
peer="$GB_ROOT/bench/skeletonize_3d.py"
peer_on=yes
case $THIN_PEER_MAX in
    ''|*[!0-9]*) echo "thin.sh: THIN_PEER_MAX '$THIN_PEER_MAX' is not a number" >&2; exit 1 ;;
esac
if [ "$THIN_PEER_MAX" -eq 0 ]; then
    peer_on=
elif [ ! -f "$peer" ]; then
    echo "thin.sh: no $peer: skimage columns are -" >&2
    peer_on=
elif ! command -v "$THIN_PYTHON" >/dev/null 2>&1; then
    echo "thin.sh: no $THIN_PYTHON (THIN_PYTHON): skimage columns are -" >&2
    peer_on=
elif ! "$THIN_PYTHON" -c 'import numpy, pyopenvdb, skimage.morphology' >/dev/null 2>&1; then
    echo "thin.sh: $THIN_PYTHON has no pyopenvdb or skimage (install python3-skimage" \
        "python3-openvdb): skimage columns are -" >&2
    peer_on=
fi

# field NAME FILE: the value after "NAME" in thin --stats or time -v output.
field() {
    sed -n "s/^[[:space:]]*$1[[:space:]:]*//p" "$2" | head -n 1
}

echo "thin, default options, --stats and /usr/bin/time;" \
    "load average at start: $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null)"
printf '%-18s %5s %15s %10s %8s %8s %8s %9s %8s %8s %9s %13s %14s %18s\n' scene res \
    voxels empty "wall s" "cpu s" "MiB" "ns/empty" nodes edges cavities "skimage cpu s" \
    "thin / skimage" "skeleton / skimage"
for scene in $THIN_SCENES; do
    name=$(basename "$scene" .scene)
    for res in $THIN_RESOLUTIONS; do
        if ! "$GB_BIN/voxelize" -q -r "$res" "$scene" -o "$dir/in.vdb" 2>"$dir/err"; then
            printf '%-18s %5s voxelize failed: %s\n' "$name" "$res" "$(head -n 1 "$dir/err")"
            continue
        fi
        start=$(date +%s.%N)
        # shellcheck disable=SC2086
        if ! $timer "$GB_BIN/thin" -q --stats $THIN_OPTIONS "$dir/in.vdb" -o "$dir/out.skel" \
            --grid "$dir/out.grid.vdb" >"$dir/stats" 2>"$dir/err"; then
            printf '%-18s %5s thin failed: %s\n' "$name" "$res" "$(head -n 1 "$dir/err")"
            continue
        fi
        end=$(date +%s.%N)
        wall=$(echo "$start $end" | awk '{ printf "%.2f", $2 - $1 }')
        cpu=- mib=-
        if [ -n "$timer" ]; then
            cpu=$(awk '/User time|System time/ { s += $NF } END { printf "%.2f", s }' "$dir/time")
            mib=$(awk '/Maximum resident/ { printf "%.0f", $NF / 1024 }' "$dir/time")
        fi
        empty=$(field "empty voxels" "$dir/stats")
        per=$(echo "$wall $empty" | awk '{ printf "%.0f", ($2 > 0) ? 1e9 * $1 / $2 : 0 }')
        # The peer on the same .vdb, right after thin.
        peer_cpu=- ratio=- skeleton_ratio=-
        if [ -n "$peer_on" ] && [ "$res" -le "$THIN_PEER_MAX" ] && [ -n "$timer" ] &&
            # shellcheck disable=SC2086
            $timer "$GB_BIN/thin" -q --stats -j 1 $THIN_OPTIONS "$dir/in.vdb" \
                -o "$dir/out.skel" --grid "$dir/out.grid.vdb" >"$dir/stats1" 2>"$dir/err"; then
            cpu1=$(awk '/User time|System time/ { s += $NF } END { printf "%.2f", s }' "$dir/time")
            skeleton_cpu=$(field "cpu seconds" "$dir/stats1" |
                sed -n 's/^skeleton \([0-9.]*\),.*/\1/p')
            if "$THIN_PYTHON" "$peer" "$dir/in.vdb" >"$dir/peer" 2>"$dir/err"; then
                peer_empty=$(awk '{ print $2 }' "$dir/peer")
                peer_cpu=$(awk '{ printf "%.2f", $8 }' "$dir/peer")
                if [ "$peer_empty" != "$empty" ]; then
                    echo "thin.sh: $name $res: skeletonize_3d saw $peer_empty empty voxels," \
                        "thin $empty: no ratio" >&2
                else
                    ratio=$(awk -v t="$cpu1" '{ if ($8 > 0) printf "%.2f", t / $8; else print "-" }' \
                        "$dir/peer")
                fi
                if [ "$peer_empty" = "$empty" ] && [ -n "$skeleton_cpu" ]; then
                    skeleton_ratio=$(awk -v t="$skeleton_cpu" \
                        '{ if ($8 > 0) printf "%.2f", t / $8; else print "-" }' "$dir/peer")
                fi
            else
                echo "thin.sh: $name $res: skeletonize_3d.py failed: $(head -n 1 "$dir/err")" >&2
            fi
        fi
        printf '%-18s %5s %15s %10s %8s %8s %8s %9s %8s %8s %9s %13s %14s %18s\n' "$name" \
            "$res" "$(field voxels "$dir/stats" | tr -d ' ')" "$empty" "$wall" "$cpu" "$mib" \
            "$per" "$(field nodes "$dir/stats")" "$(field edges "$dir/stats")" \
            "$(field "cavities opened" "$dir/stats")" "$peer_cpu" "$ratio" "$skeleton_ratio"
    done
done
echo "load average at end: $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null)"
