#!/bin/sh
# thin.sh — wall time, CPU time and peak memory of thin (skeleton and
# nearest-node grid, files written) on voxelized scenes at several
# resolutions, with the node and edge counts and the cost per empty voxel
# (which stays about flat when the cost is linear in the empty voxels).
# voxelize makes the input first; its time is not counted. Reference on
# these machines (../shared/ANCHORS.md): scikit-image skeletonize_3d takes
# 3.5 s on Sponza's empty space at 256, the DGCI 2013 authors' thinning
# 6.1 s; the targets are 1.7 s at 256 and 15 s at 512, under 2 GiB.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the
# repository; THIN_SCENES: scene files (default the Cornell box and Sponza);
# THIN_RESOLUTIONS (default 64 128 256 512); THIN_OPTIONS: extra options.
# cpu s is user + system time; wall s includes reading the .vdb and
# writing both files.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
THIN_SCENES=${THIN_SCENES:-"$GB_ROOT/scenes/shared/cornell-original.scene $GB_ROOT/scenes/shared/sponza.scene"}
THIN_RESOLUTIONS=${THIN_RESOLUTIONS:-"64 128 256 512"}
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

# field NAME FILE: the value after "NAME" in thin --stats or time -v output.
field() {
    sed -n "s/^[[:space:]]*$1[[:space:]:]*//p" "$2" | head -n 1
}

echo "thin, default options, --stats and /usr/bin/time;" \
    "load average at start: $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null)"
printf '%-18s %5s %15s %10s %8s %8s %8s %9s %8s %8s %9s\n' scene res voxels empty \
    "wall s" "cpu s" "MiB" "ns/empty" nodes edges cavities
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
        printf '%-18s %5s %15s %10s %8s %8s %8s %9s %8s %8s %9s\n' "$name" "$res" \
            "$(field voxels "$dir/stats" | tr -d ' ')" "$empty" "$wall" "$cpu" "$mib" "$per" \
            "$(field nodes "$dir/stats")" "$(field edges "$dir/stats")" \
            "$(field "cavities opened" "$dir/stats")"
    done
done
