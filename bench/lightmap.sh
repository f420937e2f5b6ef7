#!/bin/sh
# lightmap.sh — the lightmap's error against its bake's CPU time (issue 49),
# on LIGHTMAP_SCENES (default McGuire's Cornell box) at LIGHTMAP_SIZE
# (default 512: atlas --size) from LIGHTMAP_PHOTONS photons (default 1 M;
# cluster's defaults, or LIGHTMAP_CLUSTER_FLAGS, e.g. "--interpolation
# surface").
#
# Rows: lightmap --quality Q for Q in LIGHTMAP_QUALITIES (default 0 16 64
# 256; 0 reads the octree at the texel, Q > 0 is the final gather reading
# the octree where its rays meet the scene, at lightmap's default
# --accuracy: gathers on a lattice, texels between interpolated), the same
# with --accuracy 0 (a gather at every texel) for Q in LIGHTMAP_EVERY
# (default 64, empty for none), and --paths --quality Q for Q in
# LIGHTMAP_PATHS (default 16 64 256, empty for none; the unbiased gather, no
# octree). The
# truth: --paths --quality LIGHTMAP_TRUTH --accuracy 0 (default 1024: a
# gather at every texel) with --seed 1;
# its noise floor, half the relative MSE between it and the same with
# --seed 2 (the two are independent, each holds half of it), is subtracted
# from nothing: compare rows with it.
# Columns: the CPU seconds (user + sys) of the whole bake (photons, cluster,
# atlas and lightmap; the --paths rows need no octree but are charged the
# same atlas, not the photons and cluster) and of lightmap alone; then
# bench/lightmap_error's relative MSE per texel, (a - b)^2 / (b^2 + 0.01
# mean(b)^2), on the texels the scene's camera sees, those 5 texels or more
# from a chart's edge and every covered one; the ratio of means one texel
# in from the charts' edges, the worst chart's, and the dark texels'
# (truth under a tenth of the mean: the floor under the boxes, the ceiling
# above McGuire's light).
# Prints a Markdown table; LIGHTMAP_CSV=FILE also writes its rows as CSV
# (make report's lightmap.csv). Run by `make bench`, and by `make report`
# on McGuire's box.

. "$(dirname "$0")/common.sh"
needs photons cluster atlas lightmap
error_program=$(bench_program lightmap_error) || exit 1
LIGHTMAP_SCENES=${LIGHTMAP_SCENES:-$root/scenes/shared/cornell-original.scene}
LIGHTMAP_SIZE=${LIGHTMAP_SIZE:-512}
LIGHTMAP_PHOTONS=${LIGHTMAP_PHOTONS:-1000000}
LIGHTMAP_QUALITIES=${LIGHTMAP_QUALITIES:-"0 16 64 256"}
LIGHTMAP_EVERY=${LIGHTMAP_EVERY-64}
LIGHTMAP_PATHS=${LIGHTMAP_PATHS-"16 64 256"}
LIGHTMAP_TRUTH=${LIGHTMAP_TRUTH:-1024}

# cpu_seconds FILE: user + sys of a GNU time -f "%U %S" file.
cpu_seconds() { awk '{ printf "%.2f", $1 + $2 }' "$1"; }
timed() { # OUT.time TOOL ARGS...
    out=$1
    shift
    /usr/bin/time -f "%U %S" -o "$out" "$@" || exit 1
}

echo "lightmap at ${LIGHTMAP_SIZE}^2, $LIGHTMAP_PHOTONS photons, truth --paths --quality" \
    "$LIGHTMAP_TRUTH --accuracy 0; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
echo "| scene | lightmap | bake CPU (s) | lightmap CPU (s) | seen | interior | covered | edge ratio | worst chart ratio | dark ratio |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
[ -z "$LIGHTMAP_CSV" ] ||
    echo "scene,mode,quality,bake_cpu_s,lightmap_cpu_s,seen_relative_mse,interior_relative_mse,covered_relative_mse,edge_ratio_of_means,chart_worst_ratio,dark_ratio_of_means,truth_quality,truth_floor_seen,accuracy" \
        >"$LIGHTMAP_CSV"
for scene in $LIGHTMAP_SCENES; do
    name=$(basename "$scene" .scene)
    b=$dir/$name
    timed "$b.photons.time" "$GB_BIN/photons" -q -n "$LIGHTMAP_PHOTONS" "$scene" -o "$b.phot"
    timed "$b.cluster.time" "$GB_BIN/cluster" -q $LIGHTMAP_CLUSTER_FLAGS "$scene" "$b.phot" -o "$b.lot"
    timed "$b.atlas.time" "$GB_BIN/atlas" -q --size "$LIGHTMAP_SIZE" "$scene" -o "$b.atlas"
    octree_cpu=$(cat "$b.photons.time" "$b.cluster.time" "$b.atlas.time" |
        awk '{ s += $1 + $2 } END { printf "%.2f", s }')
    atlas_cpu=$(cpu_seconds "$b.atlas.time")
    for seed in 1 2; do
        timed "$b.truth$seed.time" "$GB_BIN/lightmap" -q --paths --quality "$LIGHTMAP_TRUTH" \
            --accuracy 0 --seed "$seed" "$scene" "$b.atlas" -o "$b.truth$seed.exr"
    done
    "$error_program" "$scene" "$b.atlas" "$b.truth2.exr" "$b.truth1.exr" >"$b.floor" || exit 1
    floor=$(awk '$1 == "seen_relative_mse" { printf "%.3g", $2 / 2 }' "$b.floor")
    printf "| %s | truth's noise floor (half of two seeds') | | %s | %s | | | | | |\n" "$name" \
        "$(cpu_seconds "$b.truth1.time")" "$floor"
    row() { # MODE QUALITY FLAGS... (MODE: octree, every or paths)
        mode=$1 quality=$2
        shift 2
        accuracy=default
        [ "$mode" = every ] && accuracy=0
        lot=$b.lot
        [ "$mode" = paths ] && lot=
        timed "$b.$mode$quality.time" "$GB_BIN/lightmap" -q --quality "$quality" "$@" "$scene" \
            "$b.atlas" $lot -o "$b.$mode$quality.exr"
        "$error_program" "$scene" "$b.atlas" "$b.$mode$quality.exr" "$b.truth1.exr" \
            >"$b.$mode$quality.error" || exit 1
        v() { value "$1" "$b.$mode$quality.error"; }
        cpu=$(cpu_seconds "$b.$mode$quality.time")
        base=$octree_cpu
        [ "$mode" = paths ] && base=$atlas_cpu
        bake=$(awk -v a="$base" -v b="$cpu" 'BEGIN { printf "%.2f", a + b }')
        label="--quality $quality"
        [ "$mode" = every ] && label="--quality $quality --accuracy 0"
        [ "$mode" = paths ] && label="--paths --quality $quality"
        printf "| %s | %s | %s | %s | %.4g | %.4g | %.4g | %.3f | %.3f | %.3g |\n" "$name" \
            "$label" "$bake" "$cpu" "$(v seen_relative_mse)" "$(v interior_relative_mse)" \
            "$(v covered_relative_mse)" "$(v edge_ratio_of_means)" "$(v chart_worst_ratio)" \
            "$(v dark_ratio_of_means)"
        [ -z "$LIGHTMAP_CSV" ] ||
            echo "$name,$mode,$quality,$bake,$cpu,$(v seen_relative_mse),$(v interior_relative_mse),$(v covered_relative_mse),$(v edge_ratio_of_means),$(v chart_worst_ratio),$(v dark_ratio_of_means),$LIGHTMAP_TRUTH,$floor,$accuracy" \
                >>"$LIGHTMAP_CSV"
    }
    for quality in $LIGHTMAP_QUALITIES; do
        row octree "$quality"
    done
    for quality in $LIGHTMAP_EVERY; do
        row every "$quality" --accuracy 0
    done
    for quality in $LIGHTMAP_PATHS; do
        row paths "$quality" --paths
    done
done
