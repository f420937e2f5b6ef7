#!/bin/sh
# runtime.sh — per-pass and whole-frame GPU times of gbview (direct light)
# at 1024x512 on the Cornell box and Sponza, as a table. On llvmpipe (no GPU
# here) the figures are only relative: CPU rasterization.
# Shadow maps are drawn once (static scene and lights) in the first frame,
# which also compiles the shaders; the other columns are means over the
# later frames.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the
# repository; FRAMES: frames per scene (default 6).

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
FRAMES=${FRAMES:-6}
RESOLUTION=${RESOLUTION:-1024x512}
tool=$GB_BIN/gbview
out=$(mktemp "${TMPDIR:-/tmp}/gibake-bench.XXXXXX") || exit 1
trap 'rm -f "$out"' EXIT INT TERM

# The mean (or, for the once-only shadow maps, the first) of a --timings row.
column() { # PASS FIELD
    awk -v pass="$1" -v field="$2" '
        { name = $1; for (i = 2; i <= NF - 2; ++i) name = name " " $i }
        name == pass { print $(NF - 2 + field); found = 1 }
        END { if (!found) print "-" }' "$out"
}

echo "gbview --method direct, $RESOLUTION, $FRAMES frames (ms; means over frames 2..$FRAMES)"
printf '%-10s %10s %10s %12s %11s %12s %12s\n' scene "shadows*" g-buffer "direct light" \
    "frame gpu" "frame wall" "first frame"
for scene in "$GB_ROOT/scenes/cornell/cornell.scene" "$GB_ROOT/scenes/shared/sponza.scene"; do
    name=$(basename "$scene" .scene)
    if ! "$tool" --headless --quiet --resolution "$RESOLUTION" --frames "$FRAMES" --timings \
        "$scene" >"$out" 2>&1; then
        printf '%-10s %s\n' "$name" "failed: $(head -n 1 "$out")"
        continue
    fi
    printf '%-10s %10s %10s %12s %11s %12s %12s\n' "$name" "$(column "shadow maps" 2)" \
        "$(column g-buffer 1)" "$(column "direct light" 1)" "$(column "frame (gpu)" 1)" \
        "$(column "frame (wall)" 1)" "$(column "frame (wall)" 2)"
done
echo "* shadow maps: drawn once, in the first frame"
