#!/bin/sh
# flc_iv.sh — Forward Light Cuts with implicit visibility (gbview --method
# flc-iv) against plain FLC (--method flc), both against the shadowed
# `reference --mode indirect1` (FLC_IV_SPP samples a pixel, default 256)
# at FLC_IV_SIZE (default 96x96), indirect light only, N_avg FLC_IV_NAVG
# (default 64), on FLC_IV_SCENES (default the two Cornell boxes, the two
# rooms, Sponza, the classroom and the staircase):
#   the relative MSE (imgdiff) after 1, 4, 16 and 64 progressive frames,
#   and the slope of log(error) over log(frames) fitted by least squares
#     (0: converged to a bias; -1: variance alone, falling as 1/frames);
#   the mean frame time (--timings, "frame (wall)") of the 64-frame run,
#     and its ratio flc-iv / flc in the same run;
#   flc-iv's other bin filter, --bin-filter nearest, after 64 frames;
#   gbview's start-up seconds (its wall time less its frames' at 1 frame:
#     flc-iv builds implicit visibility's links there) and peak memory.
# Prints a Markdown table on stdout. Run by `make bench`.

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
FLC_IV_SPP=${FLC_IV_SPP:-256}
FLC_IV_SIZE=${FLC_IV_SIZE:-96x96}
FLC_IV_NAVG=${FLC_IV_NAVG:-64}
s=$root/scenes
FLC_IV_SCENES=${FLC_IV_SCENES:-"$s/cornell/cornell.scene $s/shared/cornell-original.scene $s/two-rooms/two-rooms.scene $s/shared/sponza.scene $s/shared/classroom.scene $s/shared/staircase.scene"}
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-flc-iv.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

relative_mse() {
    "$GB_BIN/imgdiff" "$1" "$2" | sed -n 's/^relative_mse //p'
}

# The mean of the "frame (wall)" line of a --timings output.
frame_ms() {
    awk 'index($0, "frame (wall)") == 1 { print $(NF - 1); exit }' "$1"
}

# render METHOD SCENE FRAMES [OPTION...]: the image $dir/METHOD-FRAMES.exr,
# its timings, wall seconds and peak KiB.
render() {
    out=$dir/$1-$3 render_method=$1 render_scene=$2 render_frames=$3
    shift 3
    /usr/bin/time -f "%e %M" -o "$out.time" "$GB_BIN/gbview" --headless --quiet --timings \
        --method "$render_method" --terms indirect --navg "$FLC_IV_NAVG" -r "$FLC_IV_SIZE" \
        --frames "$render_frames" "$@" -o "$out.exr" "$render_scene" >"$out.timings" || exit 1
}

echo "flc-iv against flc, indirect light, ${FLC_IV_SIZE}, N_avg $FLC_IV_NAVG, against" \
    "reference --mode indirect1 at $FLC_IV_SPP spp; $(nproc) cores, load" \
    "$(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
echo "| scene | method | 1 frame | 4 | 16 | 64 | slope | frame (ms) | flc-iv / flc | nearest, 64 | start-up (s) | peak (MiB) |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in $FLC_IV_SCENES; do
    name=$(basename "$scene" .scene)
    "$GB_BIN/reference" --quiet --mode indirect1 --spp "$FLC_IV_SPP" -r "$FLC_IV_SIZE" \
        -o "$dir/reference.exr" "$scene" || exit 1
    flc_ms=
    for method in flc flc-iv; do
        errors=
        for frames in 1 4 16 64; do
            render $method "$scene" $frames
            errors="$errors $(relative_mse "$dir/$method-$frames.exr" "$dir/reference.exr")"
        done
        ms=$(frame_ms "$dir/$method-64.timings")
        one=$(frame_ms "$dir/$method-1.timings")
        time=$(cat "$dir/$method-1.time")
        nearest=-
        if [ $method = flc ]; then
            flc_ms=$ms
        else
            render flc-iv "$scene" 64 --bin-filter nearest
            nearest=$(relative_mse "$dir/flc-iv-64.exr" "$dir/reference.exr")
        fi
        echo "$errors" | awk -v name="$name" -v method="$method" -v ms="$ms" -v flc="$flc_ms" \
            -v one="$one" -v time="$time" -v nearest="$nearest" '{
            n = 0; sx = sy = sxx = sxy = 0
            for (i = 1; i <= 4; ++i) {
                x = log(4 ^ (i - 1)); y = log($i > 0 ? $i : 1e-30)
                n++; sx += x; sy += y; sxx += x * x; sxy += x * y
            }
            slope = (n * sxy - sx * sy) / (n * sxx - sx * sx)
            split(time, t, " ")
            ratio = method == "flc" ? "-" : sprintf("%.2f", ms / flc)
            if (nearest != "-") nearest = sprintf("%.5f", nearest)
            printf "| %s | %s | %.5f | %.5f | %.5f | %.5f | %.2f | %.1f | %s | %s | %.1f | %.0f |\n",
                name, method, $1, $2, $3, $4, slope, ms, ratio, nearest, t[1] - one / 1000, t[2] / 1024
        }'
    done
done
