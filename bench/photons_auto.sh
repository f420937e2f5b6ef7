#!/bin/sh
# photons_auto.sh — what `photons -n auto` chooses (photons.h: doubling
# counts until the map's power in 16^3 cells changes by less than the
# tolerance) on each scene, and what it costs and gives:
#   the chosen count, the passes, the change at the end;
#   CPU seconds of -n auto against -n CHOSEN (the same map) in the same run;
#   the light octree of that map (cluster, defaults) rendered by gbview
#   --method octree, against the octree of a map of twice the photons
#   (imgdiff relative MSE): how far the image is from converged.
#
#   sh bench/photons_auto.sh [SCENE...]     AUTO_TOLERANCE (default 0.05),
#                                           AUTO_SIZE (default 128x128)
#
# GB_BIN: the tools (default build/bin). Prints a Markdown table.

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
tolerance=${AUTO_TOLERANCE:-0.05}
size=${AUTO_SIZE:-128x128}
[ $# -gt 0 ] || set -- "$root/scenes/cornell/cornell.scene" "$root/scenes/shared/sponza.scene" \
    "$root/scenes/shared/staircase.scene"
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-photons-auto.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

# cpu_of COMMAND...: runs it, prints its CPU seconds (user + sys).
cpu_of() {
    /usr/bin/time -f "%U %S" -o "$dir/time" "$@" >"$dir/out" || exit 1
    awk '{ print $1 + $2 }' "$dir/time"
}

# octree_image MAP NAME: cluster the map, render it; $dir/NAME.exr.
octree_image() {
    mkdir -p "$dir/$2"
    "$GB_BIN/cluster" -q "$scene" "$1" -o "$dir/$2/$base.lot" || exit 1
    "$GB_BIN/gbview" --headless -q --method octree -r "$size" --bake "$dir/$2" "$scene" \
        -o "$dir/$2.exr" || exit 1
}

echo "photons -n auto --tolerance $tolerance; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg);" \
    "$(date -u +%Y-%m-%d)"
echo
echo "| scene | chosen count | passes | change | CPU s, -n auto | CPU s, -n chosen | ratio |" \
    "octree image against 2x the photons: relative MSE |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
for scene in "$@"; do
    base=$(basename "$scene" .scene)
    auto=$(cpu_of "$GB_BIN/photons" -q --stats -n auto --tolerance "$tolerance" "$scene" \
        -o "$dir/auto.phot")
    count=$(sed -n 's/^photons //p' "$dir/out")
    passes=$(sed -n 's/^passes //p' "$dir/out")
    change=$(sed -n 's/^change //p' "$dir/out")
    fixed=$(cpu_of "$GB_BIN/photons" -q -n "$count" "$scene" -o "$dir/fixed.phot")
    cmp -s "$dir/auto.phot" "$dir/fixed.phot" || { echo "$base: -n auto is not -n $count" >&2; exit 1; }
    cpu_of "$GB_BIN/photons" -q -n $((2 * count)) "$scene" -o "$dir/double.phot" >/dev/null
    octree_image "$dir/auto.phot" chosen
    octree_image "$dir/double.phot" double
    error=$("$GB_BIN/imgdiff" "$dir/chosen.exr" "$dir/double.exr" | sed -n 's/^relative_mse //p')
    awk -v s="$base" -v n="$count" -v p="$passes" -v c="$change" -v a="$auto" -v f="$fixed" \
        -v e="$error" 'BEGIN { printf "| %s | %d | %d | %.4f | %.2f | %.2f | %.2f | %.2g |\n",
            s, n, p, c, a, f, a / f, e }'
done
