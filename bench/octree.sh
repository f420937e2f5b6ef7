#!/bin/sh
# octree.sh — the light octree (vivianloc-2007) on llvmpipe: the paper's
# Figure 17 ("Number of light clusters & quality": k, CPU preprocess,
# spread error, GPU fps) for k_max = 1, 2, 4, 6, 8 VDLs per leaf, on the
# Cornell box and Sponza, plus the image error of the indirect term.
#
# Per scene: one photon map (photons -n N; stored photons: light reflected at
# least once), then per k:
#   bake     cluster --vdls k --tolerance 0 (always k VDLs where a leaf has
#            that many distinct directions: the paper's fixed k) at depth
#            OCTREE_DEPTH (default 6, the paper's δ) with K = OCTREE_KNN
#            (default 300, the paper's KNN): wall and CPU seconds;
#   spread   cluster --stats' mean_spread_degrees: the power-weighted RMS
#            chord from the photons' directions to their VDL's, as an angle,
#            averaged over the leaves (the paper's §5.3.2 error);
#   frame    gbview --method octree at OCTREE_SIZE (default 1024x512), wall
#            ms of a whole frame (--timings "frame (wall)", up to glFinish),
#            mean of frames 2..OCTREE_FRAMES, and its fps;
#   octree   the octree pass alone: the frame with --terms indirect (g-buffer
#            and the octree, no direct light) less the same with --method
#            direct (g-buffer only), in wall ms and in CPU ms a frame (CPU
#            time of a run less a one-frame run's, over the frames after the
#            first: llvmpipe's threads wait without spinning, so CPU time
#            holds better than wall time on a loaded machine). On llvmpipe
#            the per-pass GPU timestamps miss most of the octree pass
#            (2.7 ms "indirect light" in a 280 ms frame: the fragments run at
#            the frame's glFinish), and "frame (gpu)", their sum, with them:
#            only whole wall frames are timed here;
#   error    the indirect term (--terms indirect) at the scene's error size
#            against `reference --mode full --min-bounces 2` (every path
#            reflected at least twice = full minus direct) at the scene's
#            spp: relative MSE and 8-bit sRGB MSE from imgdiff; a second
#            reference of another seed gives the references' own noise.
# A last row per scene: k_max 8 with cluster's default tolerance (0.2: the
# fewest VDLs whose irradiance error at the leaf's normals is under it).
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).
# OCTREE_SCENES: entries path:emitted-photons:error-size:spp, paths under
# scenes/. Takes 4 to 6 minutes on 2 cores.

. "$(dirname "$0")/common.sh"
OCTREE_DEPTH=${OCTREE_DEPTH:-6}
OCTREE_KNN=${OCTREE_KNN:-300}
OCTREE_KS=${OCTREE_KS:-"1 2 4 6 8"}
OCTREE_SIZE=${OCTREE_SIZE:-1024x512}
OCTREE_FRAMES=${OCTREE_FRAMES:-10}
# About 600k stored photons each (the paper's map): the Cornell box keeps
# two per emitted photon, Sponza (open roof) one in four. The Cornell box's
# reference takes 1024 spp: at 256 its noise (relative MSE 0.0025 between
# two seeds) is as large as the octree's error.
scenes=${OCTREE_SCENES:-"cornell/cornell.scene:300000:128x128:1024 shared/sponza.scene:2500000:192x108:256"}
needs photons cluster gbview reference imgdiff
if [ ! -x /usr/bin/time ]; then
    echo "octree.sh: /usr/bin/time missing (Debian package time)"
    exit 1
fi

# Renders OCTREE_FRAMES frames at OCTREE_SIZE; prints the wall ms of a frame
# (mean of frames 2..) and its CPU ms (see the top).
time_frames() { # gbview-arguments...
    /usr/bin/time -f '%U %S' -o "$dir/cpu1" "$GB_BIN/gbview" --headless --quiet \
        --resolution "$OCTREE_SIZE" --frames 1 --timings "$@" >/dev/null 2>&1 || return 1
    /usr/bin/time -f '%U %S' -o "$dir/cpu" "$GB_BIN/gbview" --headless --quiet \
        --resolution "$OCTREE_SIZE" --frames "$OCTREE_FRAMES" --timings "$@" \
        >"$dir/timings" 2>/dev/null || return 1
    awk -v frames="$OCTREE_FRAMES" '
        FILENAME ~ /timings$/ { if ($1 == "frame" && $2 == "(wall)") wall = $3; next }
        FILENAME ~ /cpu1$/ { one = $1 + $2; next }
        { all = $1 + $2 }
        END { printf "%s %.1f\n", wall, 1000 * (all - one) / (frames - 1) }' \
        "$dir/timings" "$dir/cpu1" "$dir/cpu"
}

echo "light octree on llvmpipe; $(nproc) cores; $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "depth $OCTREE_DEPTH, K $OCTREE_KNN; frames at $OCTREE_SIZE (frames 2..$OCTREE_FRAMES);"
echo "indirect term against reference --mode full --min-bounces 2"
for entry in $scenes; do
    scene_entry "$entry"
    "$GB_BIN/photons" -q --stats -n "$emitted" "$scene" -o "$dir/$name.phot" >"$dir/photons" ||
        exit 1
    "$GB_BIN/reference" -q --mode full --min-bounces 2 --spp "$spp" \
        --resolution "$error_size" "$scene" -o "$dir/$name.ref.exr" || exit 1
    # The reference's own noise: another seed.
    "$GB_BIN/reference" -q --mode full --min-bounces 2 --spp "$spp" --seed 1 \
        --resolution "$error_size" "$scene" -o "$dir/$name.ref1.exr" || exit 1
    "$GB_BIN/imgdiff" "$dir/$name.ref1.exr" "$dir/$name.ref.exr" >"$dir/noise"
    "$GB_BIN/gbview" --headless --quiet --method direct --terms indirect \
        --resolution "$error_size" "$scene" -o "$dir/black.exr" 2>/dev/null || exit 1
    "$GB_BIN/imgdiff" "$dir/black.exr" "$dir/$name.ref.exr" >"$dir/e"
    echo
    echo "### $name: $emitted photons emitted, $(value stored "$dir/photons") stored;" \
        "error at $error_size, reference $spp spp (a black image: relative MSE $(value relative_mse "$dir/e")," \
        "8-bit MSE $(value mse_srgb8 "$dir/e"); the reference with another seed:" \
        "$(value relative_mse "$dir/noise"), $(value mse_srgb8 "$dir/noise"))"
    echo
    echo "| k_max | bake s (wall) | bake s (CPU) | leaves | VDLs | spread ° | frame ms | fps | octree ms (wall) | octree ms (CPU) | relative MSE | 8-bit MSE |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
    for k in $OCTREE_KS 8s; do
        tolerance=0
        label=$k
        if [ "$k" = 8s ]; then
            tolerance=0.2
            label="8, tolerance 0.2 (the default)"
        fi
        /usr/bin/time -f '%e %U %S' -o "$dir/time" "$GB_BIN/cluster" -q --stats \
            --depth "$OCTREE_DEPTH" --knn "$OCTREE_KNN" --vdls "${k%s}" --tolerance $tolerance \
            "$scene" "$dir/$name.phot" -o "$bake/$name.lot" >"$dir/cluster" || exit 1
        read -r wall user system <"$dir/time"
        full=$(time_frames --method octree --bake "$bake" "$scene") || exit 1
        # The octree pass: g-buffer + octree less g-buffer alone, run one after the other.
        base=$(time_frames --method direct --terms indirect "$scene") || exit 1
        alone=$(time_frames --method octree --bake "$bake" --terms indirect "$scene") || exit 1
        "$GB_BIN/gbview" --headless --quiet --method octree --bake "$bake" --terms indirect \
            --resolution "$error_size" "$scene" -o "$dir/octree.exr" 2>/dev/null || exit 1
        "$GB_BIN/imgdiff" "$dir/octree.exr" "$dir/$name.ref.exr" >"$dir/e"
        echo "$full $base $alone" | awk -v k="$label" -v wall="$wall" -v cpu="$user $system" \
            -v leaves="$(value leaves "$dir/cluster")" -v vdls="$(value vdls "$dir/cluster")" \
            -v spread="$(value mean_spread_degrees "$dir/cluster")" \
            -v rel="$(value relative_mse "$dir/e")" -v mse="$(value mse_srgb8 "$dir/e")" '
            { split(cpu, c, " ");
              printf "| %s | %.2f | %.2f | %d | %d | %.1f | %.0f | %.1f | %.0f | %.0f | %.4f | %.2f |\n",
                     k, wall, c[1] + c[2], leaves, vdls, spread, $1, 1000 / $1,
                     $5 - $3, $6 - $4, rel, mse }'
    done
done
echo
echo "frame ms: a whole frame (direct light + octree), wall; octree ms: the octree"
echo "pass alone (frames with --terms indirect, less the g-buffer-only frame), wall and CPU."
echo "bake: cluster alone (the photon map is shared). Timings taken on a shared machine."
