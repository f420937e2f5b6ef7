#!/bin/sh
# cluster.sh — vivianloc-2007 Figures 13, 14 and the spread column of 17 on
# this machine, for the light octree tool (cluster):
#
#   1. Figure 14: cluster seconds on the dragon at depth 5 for KNN K = 50,
#      100, 250, 500 x 150k, 300k, 600k, 1.2M stored photons;
#   2. Figure 13: cluster seconds at depth 4, 5, 6 (K = 300) on 600k stored
#      photons on each scene, with the issue's target on the depth-6 column:
#      <= 8 s wall for 600k photons, delta 6, K 300 on 2 cores (the paper:
#      2m41s to 3m47s); the phases (FLANN build, KNN queries, gathering +
#      k-means) beside it;
#   3. Figure 17's spread column: the spread at fixed k = 1, 2, 4, 8 VDLs on
#      the Cornell box, 1M photons emitted, delta 6, K 300
#      (bench/cluster_spread.c, ../bench/cluster_spread beside the tools),
#      with a cosine-weighted hemisphere of the same photon counts as a
#      bound for diffuse interreflection; then k = 4 with k-means restarts,
#      with the photons of other surfaces left out, and k = 1, 4, 8 on a map
#      that keeps the direct-light photons too.
#
# Photon maps are traced first with photons (not timed): a 200k-photon pilot
# run gives each scene's stored/emitted ratio, then -n is chosen so that
# about the wanted count is stored. The bunny and the dragon stand in the
# open (no walls), so few of their photons are ever reflected: their maps
# keep every hit (--store all); the enclosed scenes keep the indirect
# photons only, as the pipeline does.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the
# repository; THREADS (default 2); FAST=1: a quick subset (K 50 and 250,
# 150k and 600k photons, depths 4 and 5, three scenes, spread on 300k
# emitted); CLUSTER_SCENES overrides the scene list of part 2.
# Seconds are wall seconds, and CPU seconds (user + system) of the whole
# command (reading the map, building the octree, writing the file).

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
THREADS=${THREADS:-2}
if [ "${FAST:-0}" = 1 ]; then
    KNNS="50 250"
    COUNTS="150000 600000"
    DEPTHS="4 5"
    SCENES=${CLUSTER_SCENES:-"cornell sponza dragon"}
    SPREAD_EMITTED=300000
else
    KNNS="50 100 250 500"
    COUNTS="150000 300000 600000 1200000"
    DEPTHS="4 5 6"
    SCENES=${CLUSTER_SCENES:-"cornell cornell-original sponza bunny dragon staircase"}
    SPREAD_EMITTED=1000000
fi
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-cluster.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

if [ ! -x "$GB_BIN/cluster" ] || [ ! -x "$GB_BIN/photons" ]; then
    echo "cluster.sh: cluster or photons not built in $GB_BIN"
    exit 1
fi

scene_file() {
    if [ "$1" = cornell ]; then
        echo "$GB_ROOT/scenes/cornell/cornell.scene"
    else
        echo "$GB_ROOT/scenes/shared/$1.scene"
    fi
}

store_of() {
    case $1 in
    bunny | dragon) echo all ;;
    *) echo indirect ;;
    esac
}

# field NAME FILE: the value after "NAME " in --stats output.
field() {
    sed -n "s/^$1 //p" "$2" | head -n 1
}

# photon_map SCENE_NAME STORED: traces a map of about STORED photons into
# $dir/SCENE_NAME-STORED.phot (once); prints nothing, fails on error.
photon_map() {
    out="$dir/$1-$2.phot"
    [ -f "$out" ] && return 0
    scene=$(scene_file "$1")
    store=$(store_of "$1")
    if [ ! -f "$dir/$1.pilot" ]; then
        "$GB_BIN/photons" -q --stats --store "$store" -n 200000 -j "$THREADS" "$scene" \
            -o "$dir/pilot.phot" >"$dir/$1.pilot" 2>"$dir/err" || return 1
        rm -f "$dir/pilot.phot"
    fi
    pilot=$(field stored "$dir/$1.pilot")
    [ "${pilot:-0}" -gt 0 ] || return 1
    emitted=$(awk -v s="$2" -v p="$pilot" 'BEGIN { printf "%d", s * 200000 / p + 1 }')
    "$GB_BIN/photons" -q --stats --store "$store" -n "$emitted" -j "$THREADS" "$scene" \
        -o "$out" >"$dir/photons.stats" 2>"$dir/err" &&
        field stored "$dir/photons.stats" >"$out.stored"
}

# run SCENE_NAME STORED DEPTH K: one timed cluster run; prints
# "wall cpu index query kmeans stored leaves vdls" or "failed: ...".
run() {
    if ! photon_map "$1" "$2"; then
        echo "failed: photons: $(head -n 1 "$dir/err")"
        return
    fi
    if ! /usr/bin/time -f '%e %U %S' -o "$dir/time" "$GB_BIN/cluster" -q --stats \
        -j "$THREADS" -d "$3" -k "$4" "$(scene_file "$1")" "$dir/$1-$2.phot" \
        -o "$dir/out.lot" >"$dir/stats" 2>"$dir/err"; then
        echo "failed: $(head -n 1 "$dir/err")"
        return
    fi
    awk -v i="$(field index_seconds "$dir/stats")" -v q="$(field query_seconds "$dir/stats")" \
        -v k="$(field kmeans_seconds "$dir/stats")" -v l="$(field leaves "$dir/stats")" \
        -v v="$(field vdls "$dir/stats")" -v n="$(cat "$dir/$1-$2.phot.stored")" \
        '{ printf "%6.2f %6.2f %6.2f %6.2f %6.2f %9d %7d %8d\n", $1, $2 + $3, i, q, k, n, l, v }' \
        "$dir/time"
}

echo "cluster, $THREADS threads; load average at start: $(cut -d ' ' -f 1-3 /proc/loadavg)"
echo
echo "Figure 14: dragon, depth 5, wall s / cpu s (paper, 1 core 2007: 4..47 s)"
printf '%-8s' "K"
for n in $COUNTS; do printf ' %15s' "$n"; done
printf '\n'
for k in $KNNS; do
    printf '%-8s' "$k"
    for n in $COUNTS; do
        set -- $(run dragon "$n" 5 "$k")
        if [ "$1" = failed: ]; then printf ' %15s' failed; else printf ' %7s/%-7s' "$1" "$2"; fi
    done
    printf '\n'
done

echo
echo "Figure 13: 600k stored photons, K 300; per depth: wall s, cpu s; then the phases of" \
    "the deepest (FLANN build, KNN queries, gathering + k-means: wall s; k-means / KNN, the" \
    "issue 48 goal <= 1.5)"
printf '%-17s' scene
for d in $DEPTHS; do printf ' %13s' "delta $d"; done
printf ' %6s %6s %6s %9s %7s %8s %6s\n' index knn kmeans photons leaves vdls ratio
for s in $SCENES; do
    printf '%-17s' "$s"
    for d in $DEPTHS; do
        set -- $(run "$s" 600000 "$d" 300)
        if [ "$1" = failed: ]; then
            printf ' %13s' failed
            shift
            last="$*"
        else
            printf ' %6s/%-6s' "$1" "$2"
            last=$(printf '%6s %6s %6s %9s %7s %8s %6.2f' "$3" "$4" "$5" "$6" "$7" "$8" \
                "$(echo "$5 $4" | awk '{ print ($2 > 0 ? $1 / $2 : 0) }')")
        fi
    done
    printf ' %s\n' "$last"
done

echo
spread=$GB_BIN/../bench/cluster_spread
if [ -x "$spread" ]; then
    cornell=$(scene_file cornell)
    if "$GB_BIN/photons" -q -n "$SPREAD_EMITTED" -j "$THREADS" "$cornell" \
        -o "$dir/spread.phot" 2>"$dir/err"; then
        echo "Figure 17 spread column: Cornell box, $SPREAD_EMITTED photons emitted, delta 6," \
            "K 300, fixed k (degrees; paper: k 1 2 4 8 -> 30 25 20 10)"
        "$spread" "$cornell" "$dir/spread.phot" 6 300 1 1 2 4 8
        if [ "${FAST:-0}" != 1 ]; then
            echo "the same at k = 4 with 4 k-means restarts (cluster --restarts 4):"
            "$spread" "$cornell" "$dir/spread.phot" 6 300 4 4 | tail -n 1
            echo "... keeping only photons whose surface normal is within 25 degrees of the leaf's:"
            SPREAD_NORMAL_COS=0.9 "$spread" "$cornell" "$dir/spread.phot" 6 300 1 4 | tail -n 1
            if "$GB_BIN/photons" -q --store all -n "$SPREAD_EMITTED" -j "$THREADS" "$cornell" \
                -o "$dir/spread.phot" 2>"$dir/err"; then
                echo "... every hit stored, direct light included (photons --store all):"
                "$spread" "$cornell" "$dir/spread.phot" 6 300 1 1 4 8 | tail -n 3
            fi
        fi
    else
        echo "spread: photons failed: $(head -n 1 "$dir/err")"
    fi
else
    echo "(no $spread: the spread table needs it built, make bench)"
fi
