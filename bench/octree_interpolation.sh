#!/bin/sh
# octree_interpolation.sh — the light octree display's two interpolations
# (cluster --interpolation trilinear | surface; light_octree_shading.h)
# against each other over photon seeds (issue 49: "no worse anywhere in
# make report, better on the boxes"). make report renders one photon map
# per point, seed 0; its ratio of the two errors moves with the seed by
# more than the two interpolations differ on some scenes, so this runs
# several.
#
# Per scene and per point (photons -n N, cluster --depth D --vdls K at
# cluster's default tolerance), for each seed s of 0 .. SEEDS - 1:
# photons --seed s, cluster twice (the interpolation is a flag of the
# file's header: the leaves are the same), the indirect term (gbview
# --method octree --terms indirect) against `reference --mode full
# --min-bounces 2` (the photon map carries every bounce: make report's own
# reference for the octree), imgdiff's relative MSE. The ratio of a seed
# is surface over trilinear; the table gives the mean ratio over the
# seeds, its standard error (sample standard deviation / sqrt SEEDS), the
# least and largest, and how many seeds surface lost.
#
# OCTREE_INTERPOLATION_SCENES: entries PATH:SIZE:SPP (PATH under scenes/;
# the frame size and reference spp; default make report's five octree
# scenes at its sizes); OCTREE_INTERPOLATION_POINTS: photons:depth:vdls
# entries (default make report's three: 200000:5:1 200000:5:4
# 600000:6:4); OCTREE_INTERPOLATION_SEEDS (default 8). About 13 minutes on
# 2 cores with the defaults. Run by `make bench`; prints a Markdown table.

. "$(dirname "$0")/common.sh"
needs photons cluster gbview reference imgdiff
scenes=${OCTREE_INTERPOLATION_SCENES:-"cornell/cornell.scene:96x96:256 \
shared/cornell-original.scene:96x96:256 shared/sponza.scene:128x72:256 \
shared/living-room.scene:128x72:256 shared/staircase.scene:72x128:256"}
points=${OCTREE_INTERPOLATION_POINTS:-"200000:5:1 200000:5:4 600000:6:4"}
seeds=${OCTREE_INTERPOLATION_SEEDS:-8}

# The relative MSE of the octree's indirect term at $size against
# $dir/reference.exr, from the photon map $dir/map.phot clustered with
# interpolation $1 at depth $2 with $3 VDLs.
octree_error() { # interpolation depth vdls
    mkdir -p "$dir/$1"
    "$GB_BIN/cluster" -q --depth "$2" --vdls "$3" --interpolation "$1" "$scene" \
        "$dir/map.phot" -o "$dir/$1/$name.lot" || return 1
    "$GB_BIN/gbview" --headless --quiet --method octree --terms indirect --bake "$dir/$1" \
        --resolution "$size" "$scene" -o "$dir/$1.exr" 2>/dev/null || return 1
    relative_mse "$dir/$1.exr" "$dir/reference.exr"
}

echo "light octree display: surface against trilinear interpolation over $seeds photon seeds;"
echo "$(nproc) cores; $(date -u '+%Y-%m-%d %H:%M UTC'); indirect term against reference"
echo "--mode full --min-bounces 2 (seed 0), relative MSE; ratio: surface / trilinear per seed"
echo
echo "| scene | photons | depth | VDLs | trilinear mean | surface mean | mean ratio | standard error | least | largest | seeds surface lost |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for entry in $scenes; do
    path=${entry%%:*}
    rest=${entry#*:}
    size=${rest%%:*}
    spp=${rest#*:}
    scene=$root/scenes/$path
    name=$(basename "$scene" .scene)
    "$GB_BIN/reference" -q --mode full --min-bounces 2 --spp "$spp" --resolution "$size" \
        "$scene" -o "$dir/reference.exr" || exit 1
    for point in $points; do
        photons=${point%%:*}
        rest=${point#*:}
        depth=${rest%%:*}
        vdls=${rest#*:}
        : >"$dir/errors"
        seed=0
        while [ "$seed" -lt "$seeds" ]; do
            "$GB_BIN/photons" -q -n "$photons" --seed "$seed" "$scene" -o "$dir/map.phot" || exit 1
            trilinear=$(octree_error trilinear "$depth" "$vdls") || exit 1
            surface=$(octree_error surface "$depth" "$vdls") || exit 1
            echo "$trilinear $surface" >>"$dir/errors"
            seed=$((seed + 1))
        done
        awk -v scene="$name" -v photons="$photons" -v depth="$depth" -v vdls="$vdls" '
            { t += $1; s += $2; r[NR] = $2 / $1; mean += r[NR]; lost += $2 > $1
              least = NR == 1 || r[NR] < least ? r[NR] : least
              largest = NR == 1 || r[NR] > largest ? r[NR] : largest }
            END {
                mean /= NR
                for (i = 1; i <= NR; ++i) spread += (r[i] - mean) ^ 2
                error = NR > 1 ? sqrt(spread / (NR - 1) / NR) : 0
                printf "| %s | %d | %d | %d | %.5f | %.5f | %.3f | %.3f | %.3f | %.3f | %d of %d |\n",
                       scene, photons, depth, vdls, t / NR, s / NR, mean, error, least, largest,
                       lost, NR }' "$dir/errors"
    done
done
