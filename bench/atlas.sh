#!/bin/sh
# atlas.sh — the lightmap atlas (tools/atlas: normal-cone charts, CGAL LSCM,
# packing by shape) at ATLAS_SIZE (default 1024, i.e. --size 1024: the
# largest density whose charts fit 1024 x 1024) with the default cone and
# padding, on ATLAS_SCENES (default the two Cornell boxes, Sponza and the
# staircase):
#   triangles, charts (and of them lone triangles), fill ratio (the
#   triangles' UV area in texels over the atlas's area; goal >= 0.6), the
#   texel density chosen, max and mean angle distortion (degrees, per
#   triangle corner: |UV angle - 3-D angle|; needle corners, at an edge
#   under 4 UV steps, left out and counted), the build seconds atlas
#   reports (goal <= 5 s on Sponza at 1024^2), the wall seconds of the run
#   (with the scene's load) and its peak memory, the file's bytes; and
#   where the texels go (bench/atlas_texels.c, when built: the masks'
#   slack, the gutters, the unused share; with the fill ratio they add up
#   to 1; "-" for an atlas its reader does not read).
# Prints a Markdown table on stdout. Run by `make bench`.

. "$(dirname "$0")/common.sh"
ATLAS_SIZE=${ATLAS_SIZE:-1024}
s=$root/scenes
ATLAS_SCENES=${ATLAS_SCENES:-"$s/cornell/cornell.scene $s/shared/cornell-original.scene $s/shared/sponza.scene $s/shared/staircase.scene"}

echo "atlas --size $ATLAS_SIZE (default cone and padding); $(nproc) cores, load" \
    "$(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
texels=$(bench_program atlas_texels 2>/dev/null)
echo "| scene | triangles | charts | lone triangles | fill ratio | texels per unit | max distortion (deg) | mean distortion (deg) | needle corners | build (s) | wall (s) | peak (MiB) | bytes | mask slack | gutters | unused |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in $ATLAS_SCENES; do
    name=$(basename "$scene" .scene)
    /usr/bin/time -f "%e %M" -o "$dir/time" "$GB_BIN/atlas" --quiet --stats \
        --size "$ATLAS_SIZE" "$scene" -o "$dir/$name.atlas" >"$dir/stats" || exit 1
    v() { value "$1" "$dir/stats"; }
    read -r wall peak <"$dir/time"
    { [ -n "$texels" ] && "$texels" "$dir/$name.atlas"; } >"$dir/texels" 2>/dev/null
    t() { value "$1" "$dir/texels" | grep . || echo -; }
    printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.0f | %s | %s | %s | %s |\n" \
        "$name" "$(v triangles)" "$(v charts)" "$(v lone_triangles)" "$(v fill_ratio)" \
        "$(v texels_per_unit)" "$(v max_angle_distortion)" "$(v mean_angle_distortion)" \
        "$(v needle_corners)" "$(v seconds)" "$wall" "$(echo "$peak" | awk '{ print $1 / 1024 }')" \
        "$(v bytes)" "$(t masks)" "$(t gutters)" "$(t unused)"
done
