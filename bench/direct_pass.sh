#!/bin/sh
# direct_pass.sh — the direct pass (every gbview frame's floor) against
# `reference --mode direct`, one Markdown table: for each scene of
# DIRECT_SCENES (NAME:PATH:REPORT-SIZE, PATH under the repository) at
# DIRECT_SIZE (default 512x288) and at the report's size (bench/report.sweep)
# with --supersample 1, 2 and 4 (the reference's box filter), imgdiff's
# relative MSE and its trimmed twin (the 0.1 % largest pixel errors left
# out), and the reference's own noise (seed 1 against seed 0, at
# DIRECT_SPP samples a pixel, default 256), under which nothing can be told.
# GB_BIN: the tools (default build/bin); run it with an older build's to
# compare.
. "$(dirname "$0")/common.sh"
needs gbview reference imgdiff

scenes=${DIRECT_SCENES:-"cornell:scenes/cornell/cornell.scene:96x96 \
cornell-original:scenes/shared/cornell-original.scene:96x96 \
sponza:scenes/shared/sponza.scene:128x72 staircase:scenes/shared/staircase.scene:72x128 \
living-room:scenes/shared/living-room.scene:128x72"}
size=${DIRECT_SIZE:-512x288}
spp=${DIRECT_SPP:-256}

# row NAME SCENE SIZE SUPERSAMPLE
row() {
    ref="$dir/$1-$3-ref0.exr"
    if [ ! -f "$ref" ]; then
        "$GB_BIN/reference" --quiet --mode direct --spp "$spp" --resolution "$3" "$2" -o "$ref"
        "$GB_BIN/reference" --quiet --mode direct --spp "$spp" --seed 1 --resolution "$3" "$2" \
            -o "$dir/$1-$3-ref1.exr"
    fi
    "$GB_BIN/gbview" --headless --quiet --method direct --supersample "$4" --resolution "$3" \
        "$2" -o "$dir/$1.exr"
    "$GB_BIN/imgdiff" "$dir/$1.exr" "$ref" >"$dir/frame.diff"
    "$GB_BIN/imgdiff" "$dir/$1-$3-ref1.exr" "$ref" >"$dir/floor.diff"
    printf '| %s | %s | %s | %.4f | %.4f | %.4f |\n' "$1" "$3" "$4" \
        "$(value relative_mse "$dir/frame.diff")" "$(value relative_mse_trimmed "$dir/frame.diff")" \
        "$(value relative_mse "$dir/floor.diff")"
}

echo "load average: $(cut -d ' ' -f 1-3 /proc/loadavg)"
echo
echo "| scene | size | supersample | relative MSE | trimmed | reference noise |"
echo "|---|---|---:|---:|---:|---:|"
for entry in $scenes; do
    name=${entry%%:*}
    rest=${entry#*:}
    path=$root/${rest%%:*}
    small=${rest#*:}
    if [ ! -f "$path" ]; then
        echo "direct_pass.sh: $path missing" >&2
        exit 1
    fi
    row "$name" "$path" "$size" 1
    for s in 1 2 4; do
        row "$name" "$path" "$small" "$s"
    done
done
