#!/bin/sh
# thin_threads.sh — thin on 1 thread against 2, in the same run: the same
# .vdb thinned with -j 1 and -j 2 in turn, THIN_ROUNDS times each (runs
# alternated, so that a change in the machine's speed falls on both),
# printing per run the wall and CPU time of the whole command and thin's
# own --stats: the seconds of its maps, collapse, graph and nearest-node
# grid, the CPU seconds of the skeleton (maps to graph), and the collapse's
# iterations shared by the threads. The output bytes are the same for
# both (test_thin checks it); only the time differs.
#
# GB_BIN: the folder of the tools (default build/bin); THIN_THREADS_CASES:
# "scene:resolution" pairs (default the Cornell box and Sponza at 256);
# THIN_ROUNDS (default 3).

. "$(dirname "$0")/common.sh"
needs thin voxelize
THIN_THREADS_CASES=${THIN_THREADS_CASES:-"$root/scenes/shared/cornell-original.scene:256 $root/scenes/shared/sponza.scene:256"}
THIN_ROUNDS=${THIN_ROUNDS:-3}
if ! /usr/bin/time -v true >/dev/null 2>&1; then
    echo "thin_threads.sh: needs GNU time (/usr/bin/time -v)"
    exit 1
fi

echo "thin -j 1 against -j 2, alternated; load average at start:" \
    "$(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null)"
printf '%-18s %5s %3s %8s %8s %8s %9s %8s %8s %13s %8s\n' scene res j "wall s" "cpu s" \
    "maps s" "collapse s" "graph s" "nearest s" "skeleton cpu s" shared
for case in $THIN_THREADS_CASES; do
    scene=${case%:*} res=${case##*:}
    name=$(basename "$scene" .scene)
    if ! "$GB_BIN/voxelize" -q -r "$res" "$scene" -o "$dir/in.vdb" 2>"$dir/err"; then
        printf '%-18s %5s voxelize failed: %s\n' "$name" "$res" "$(head -n 1 "$dir/err")"
        continue
    fi
    round=0
    while [ "$round" -lt "$THIN_ROUNDS" ]; do
        for j in 1 2; do
            start=$(date +%s.%N)
            if ! /usr/bin/time -v -o "$dir/time" "$GB_BIN/thin" -q --stats -j "$j" \
                "$dir/in.vdb" -o "$dir/out.skel" --grid "$dir/out.grid.vdb" \
                >"$dir/stats" 2>"$dir/err"; then
                printf '%-18s %5s %3s thin failed: %s\n' "$name" "$res" "$j" \
                    "$(head -n 1 "$dir/err")"
                continue
            fi
            end=$(date +%s.%N)
            wall=$(echo "$start $end" | awk '{ printf "%.2f", $2 - $1 }')
            cpu=$(awk '/User time|System time/ { s += $NF } END { printf "%.2f", s }' "$dir/time")
            # "maps A, collapse B, graph C, nearest D" and "skeleton E, nearest F"
            phases=$(value seconds "$dir/stats" | tr -d ',' | awk '{ print $2, $4, $6, $8 }')
            skeleton=$(value "cpu seconds" "$dir/stats" |
                sed -n 's/^ *skeleton \([0-9.]*\),.*/\1/p')
            shared=$(value iterations "$dir/stats" | sed -n 's/.*(\([0-9]*\) on all threads).*/\1/p')
            # shellcheck disable=SC2086
            printf '%-18s %5s %3s %8s %8s %8s %9s %8s %8s %13s %8s\n' "$name" "$res" "$j" \
                "$wall" "$cpu" $phases "$skeleton" "$shared"
        done
        round=$((round + 1))
    done
done
echo "load average at end: $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null)"
