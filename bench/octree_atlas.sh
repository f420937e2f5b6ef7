#!/bin/sh
# octree_atlas.sh — the light octree through its atlas (vivianloc-2007
# §4.2.3) against the octree walk, on llvmpipe, per scene:
#   atlas      atlas --size ATLAS_SIZE (default 1024) --stats: charts, fill
#              ratio, max and mean angle distortion (degrees), wall seconds,
#              file bytes;
#   lightmap   lightmap (the octree baked on the CPU into the atlas, EXR, and
#              the .glb): wall seconds, bytes of each;
#   frame      gbview --method octree at ATLAS_FRAME_SIZE (default
#              1024x512): wall ms of a whole frame (--timings "frame (wall)",
#              mean of frames 2..ATLAS_FRAMES), with the walk (--atlas none)
#              and through the atlas (--atlas FILE), and their ratio; the
#              render into the atlas is done once, in the first frame (the
#              headless renderer gives no budget), which the mean leaves out;
#   error      the indirect term (--terms indirect) at the scene's error
#              size against `reference --mode full --min-bounces 2`:
#              relative MSE (imgdiff) of the walk and of the atlas; the atlas
#              against the walk, split by bench/atlas_seams: pixels whose
#              bilinear fetch weighs a texel of the gutter (seams) and the
#              others.
# The octree of each scene: photons -n EMITTED, cluster's defaults.
# ATLAS_SCENES: entries path:emitted-photons:error-size:spp, paths under
# scenes/. Prints a Markdown table. GB_BIN: the tools (build/bin).

. "$(dirname "$0")/common.sh"
ATLAS_SIZE=${ATLAS_SIZE:-1024}
ATLAS_FRAME_SIZE=${ATLAS_FRAME_SIZE:-1024x512}
ATLAS_FRAMES=${ATLAS_FRAMES:-10}
scenes=${ATLAS_SCENES:-"cornell/cornell.scene:300000:128x128:512 shared/cornell-original.scene:300000:128x128:512 shared/sponza.scene:2500000:192x108:256 shared/staircase.scene:1000000:128x128:256"}
needs photons cluster atlas lightmap gbview reference imgdiff
seams=$(bench_program atlas_seams) || exit 1

# The wall ms of a frame at ATLAS_FRAME_SIZE, mean of frames 2..ATLAS_FRAMES.
frame_ms() { # gbview-arguments...
    "$GB_BIN/gbview" --headless --quiet --resolution "$ATLAS_FRAME_SIZE" \
        --frames "$ATLAS_FRAMES" --timings "$@" >"$dir/timings" 2>"$dir/gbview.err" ||
        { cat "$dir/gbview.err" >&2; return 1; }
    awk '$1 == "frame" && $2 == "(wall)" { print $3 }' "$dir/timings"
}

# The indirect term at the error size into FILE.
indirect() { # FILE gbview-arguments...
    out=$1
    shift
    "$GB_BIN/gbview" --headless --quiet --terms indirect --resolution "$error_size" "$@" \
        -o "$out" 2>"$dir/gbview.err" || { cat "$dir/gbview.err" >&2; return 1; }
}

echo "light octree through its atlas on llvmpipe; $(nproc) cores; $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "atlas --size $ATLAS_SIZE; frames at $ATLAS_FRAME_SIZE (mean of frames 2..$ATLAS_FRAMES);"
echo "indirect term against reference --mode full --min-bounces 2"
echo
echo "| scene | triangles | charts | fill | max ° | mean ° | atlas s | atlas MiB | lightmap s | EXR MiB | glb MiB | frame ms walk | frame ms atlas | atlas / walk | rel. MSE walk | rel. MSE atlas | atlas vs walk: seams (pixels) | others (pixels) |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for entry in $scenes; do
    scene_entry "$entry"
    "$GB_BIN/photons" -q -n "$emitted" "$scene" -o "$dir/$name.phot" || exit 1
    "$GB_BIN/cluster" -q "$scene" "$dir/$name.phot" -o "$bake/$name.lot" || exit 1
    /usr/bin/time -f '%e' -o "$dir/atlas.time" "$GB_BIN/atlas" -q --stats --size "$ATLAS_SIZE" \
        "$scene" -o "$dir/$name.atlas" >"$dir/atlas.stats" || exit 1
    /usr/bin/time -f '%e' -o "$dir/lightmap.time" "$GB_BIN/lightmap" -q "$scene" \
        "$dir/$name.atlas" "$bake/$name.lot" -o "$dir/$name.lightmap.exr" \
        --glb "$dir/$name.glb" || exit 1
    walk_ms=$(frame_ms --method octree --bake "$bake" --atlas none "$scene") || exit 1
    atlas_ms=$(frame_ms --method octree --bake "$bake" --atlas "$dir/$name.atlas" "$scene") ||
        exit 1
    "$GB_BIN/reference" -q --mode full --min-bounces 2 --spp "$spp" \
        --resolution "$error_size" "$scene" -o "$dir/ref.exr" || exit 1
    indirect "$dir/walk.exr" --method octree --bake "$bake" --atlas none "$scene" || exit 1
    indirect "$dir/atlas.exr" --method octree --bake "$bake" --atlas "$dir/$name.atlas" \
        "$scene" || exit 1
    "$GB_BIN/imgdiff" "$dir/walk.exr" "$dir/ref.exr" >"$dir/walk.err"
    "$GB_BIN/imgdiff" "$dir/atlas.exr" "$dir/ref.exr" >"$dir/atlas.err"
    "$seams" "$scene" "$dir/$name.atlas" "$dir/atlas.exr" "$dir/walk.exr" \
        >"$dir/seams" || exit 1
    awk -v name="$name" -v triangles="$(value triangles "$dir/atlas.stats")" \
        -v charts="$(value charts "$dir/atlas.stats")" \
        -v fill="$(value fill_ratio "$dir/atlas.stats")" \
        -v max="$(value max_angle_distortion "$dir/atlas.stats")" \
        -v mean="$(value mean_angle_distortion "$dir/atlas.stats")" \
        -v atlas_s="$(cat "$dir/atlas.time")" -v lightmap_s="$(cat "$dir/lightmap.time")" \
        -v atlas_b="$(stat -c %s "$dir/$name.atlas")" \
        -v exr_b="$(stat -c %s "$dir/$name.lightmap.exr")" \
        -v glb_b="$(stat -c %s "$dir/$name.glb")" -v walk="$walk_ms" -v atlas="$atlas_ms" \
        -v walk_err="$(value relative_mse "$dir/walk.err")" \
        -v atlas_err="$(value relative_mse "$dir/atlas.err")" \
        -v seam="$(value seam_relative_mse "$dir/seams")" \
        -v seam_n="$(value seam_pixels "$dir/seams")" \
        -v other="$(value other_relative_mse "$dir/seams")" \
        -v other_n="$(value other_pixels "$dir/seams")" 'BEGIN {
        mib = 1048576
        printf "| %s | %d | %d | %.3f | %.1f | %.2f | %.2f | %.1f | %.2f | %.1f | %.1f | %.0f | %.0f | %.2f | %.4f | %.4f | %.2g (%d) | %.2g (%d) |\n",
               name, triangles, charts, fill, max, mean, atlas_s, atlas_b / mib, lightmap_s,
               exr_b / mib, glb_b / mib, walk, atlas, atlas / walk, walk_err, atlas_err,
               seam, seam_n, other, other_n }'
done
echo
echo "fill: the charts' triangles' texel area over the atlas's; frame ms: whole frames"
echo "(direct light + octree), wall; seams: pixels whose bilinear fetch weighs a gutter"
echo "texel (bench/atlas_seams.c), relative MSE of the atlas's image against the walk's."
