#!/bin/sh
# flc.sh — Forward Light Cuts on llvmpipe (the paper's Fig. 10 and the
# progressive mode): for the Cornell box and Sponza, the frame time at
# FLC_SIZE (default 1024x512) for N_avg 64..512 and tiling 0..2, and the
# relative MSE of the indirect light against `reference --mode
# indirect1-unshadowed` after 1, 4 and 16 frames at FLC_ERROR_SIZE
# (default 128x72, the reference at FLC_SPP, default 256).
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
FLC_SCENES=${FLC_SCENES:-"$GB_ROOT/scenes/cornell/cornell.scene $GB_ROOT/scenes/shared/sponza.scene"}
FLC_SIZE=${FLC_SIZE:-1024x512}
FLC_ERROR_SIZE=${FLC_ERROR_SIZE:-128x72}
FLC_SPP=${FLC_SPP:-256}
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-flc.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

if [ ! -x "$GB_BIN/gbview" ] || [ ! -x "$GB_BIN/reference" ] || [ ! -x "$GB_BIN/imgdiff" ]; then
    echo "flc.sh: gbview, reference or imgdiff not built in $GB_BIN"
    exit 1
fi

# The mean of a pass over the frames after the first, from --timings.
mean_ms() {
    sed -n "s/^$1  *\([0-9.]*\).*/\1/p" "$2"
}

for scene in $FLC_SCENES; do
    name=$(basename "$scene" .scene)
    echo "== $name, $FLC_SIZE, 4 frames (times: means over frames 2-4, ms)"
    printf "%-6s %-6s %12s %12s\n" N_avg tiling indirect frame
    for navg in 64 128 256 512; do
        for tiling in 0 1 2; do
            "$GB_BIN/gbview" --headless --quiet --method flc --resolution "$FLC_SIZE" \
                --frames 4 --navg $navg --tiling $tiling --timings "$scene" >"$dir/t" || exit 1
            printf "%-6s %-6s %12s %12s\n" $navg $tiling "$(mean_ms "indirect light" "$dir/t")" \
                "$(mean_ms "frame (gpu)" "$dir/t")"
        done
    done
    echo "== $name, $FLC_ERROR_SIZE: relative MSE to the unshadowed reference ($FLC_SPP spp)"
    "$GB_BIN/reference" --mode indirect1-unshadowed --resolution "$FLC_ERROR_SIZE" \
        --spp "$FLC_SPP" --quiet "$scene" -o "$dir/ref.exr" || exit 1
    printf "%-6s %-6s %12s\n" frames tiling relative_mse
    for tiling in 0 1; do
        for frames in 1 4 16; do
            "$GB_BIN/gbview" --headless --quiet --method flc --terms indirect \
                --resolution "$FLC_ERROR_SIZE" --frames $frames --tiling $tiling "$scene" \
                -o "$dir/f.exr" || exit 1
            "$GB_BIN/imgdiff" "$dir/f.exr" "$dir/ref.exr" >"$dir/e"
            printf "%-6s %-6s %12s\n" $frames $tiling "$(sed -n 's/^relative_mse //p' "$dir/e")"
        done
    done
done
