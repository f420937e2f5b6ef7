#!/bin/sh
# flc.sh — Forward Light Cuts (Laurent et al. 2016) on llvmpipe, three
# Markdown tables a scene (the Cornell box and Sponza by default):
#
#  1. the paper's Fig. 10: for N_avg 64, 128, 256, 512 (N = 5), the frame
#     and indirect-light times of `gbview --timings` at FLC_SIZE (default
#     1024x512, tiling FLC_TILING, default 0, the time of the frames after the
#     first of FLC_FRAMES, default 2; and the CPU time of the FLC passes from
#     bench/flc_passes.c), and the relative MSE (imgdiff) of the
#     indirect light after 1 and 16 progressive frames against `reference
#     --mode indirect1-unshadowed` at FLC_ERROR_SIZE (default 256x128, the
#     reference at FLC_SPP, default 128);
#  2. the paper's Table 1: ms per pass (bench/flc_passes.c) at FLC_SIZE,
#     N_avg 256, for each tiling of FLC_TABLE_TILINGS (default "0 3": none,
#     and the paper's x64);
#  3. on the scenes of FLC_BRUTE_SCENES (default Sponza): the same estimator
#     without decimation (every regular triangle and every tessellated
#     sub-triangle of the divergent ones a VPL, weighted by its own area:
#     flc_passes --no-decimation) against FLC at N_avg 256, at
#     FLC_ERROR_SIZE, 2 frames: the indirect times, their ratio and the
#     errors of both (after the 2 frames).
#
# The whole run took 514 s wall (249 s user CPU) on 2 cores shared with other
# jobs; the load average is printed first. GB_BIN: the folder of the tools
# (default build/bin); flc_passes is taken from GB_BIN/../bench (`make
# bench` builds it).

. "$(dirname "$0")/common.sh"
FLC_SCENES=${FLC_SCENES:-"$root/scenes/cornell/cornell.scene $root/scenes/shared/sponza.scene"}
FLC_BRUTE_SCENES=${FLC_BRUTE_SCENES:-"$root/scenes/shared/sponza.scene"}
FLC_SIZE=${FLC_SIZE:-1024x512}
FLC_TILING=${FLC_TILING:-0}
FLC_FRAMES=${FLC_FRAMES:-2}
FLC_ERROR_SIZE=${FLC_ERROR_SIZE:-256x128}
FLC_SPP=${FLC_SPP:-128}
FLC_TABLE_TILINGS=${FLC_TABLE_TILINGS:-"0 3"}
needs gbview reference imgdiff
helper=$(bench_program flc_passes) || exit 1

# The mean of a pass over the frames after the first, from --timings.
mean_ms() {
    sed -n "s/^$1  *\([0-9.]*\).*/\1/p" "$2"
}

# Column N of the row flc_passes printed (its second line) into FILE.
passes_column() { # FILE N
    awk -v n="$2" 'NR == 2 { print $n }' "$1"
}

# reference SCENE: the unshadowed first bounce at FLC_ERROR_SIZE, once.
reference() {
    out="$dir/$(basename "$1" .scene).ref.exr"
    [ -f "$out" ] || "$GB_BIN/reference" --mode indirect1-unshadowed \
        --resolution "$FLC_ERROR_SIZE" --spp "$FLC_SPP" --quiet "$1" -o "$out" || exit 1
    echo "$out"
}

# section SCENE TITLE: sets name and ref (the scene's reference) and prints
# the heading "### NAME: TITLE".
section() {
    name=$(basename "$1" .scene)
    ref=$(reference "$1") || exit 1
    echo "### $name: $2"
    echo
}

echo "Load average before the run: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
echo
for scene in $FLC_SCENES; do
    section "$scene" "Fig. 10"
    echo "Times at $FLC_SIZE, tiling $FLC_TILING (ms, frames after the first of $FLC_FRAMES);"
    echo "relative MSE of the indirect light at $FLC_ERROR_SIZE against the unshadowed"
    echo "reference ($FLC_SPP spp)."
    echo
    echo "Indirect CPU ms: the process's CPU time over the FLC passes (flc_passes, the"
    echo "second of 2 frames), less sensitive than wall times to other jobs."
    echo
    echo "| N_avg | frame ms | indirect ms | indirect CPU ms | rel. MSE, 1 frame | rel. MSE, 16 frames |"
    echo "|---:|---:|---:|---:|---:|---:|"
    for navg in 64 128 256 512; do
        "$GB_BIN/gbview" --headless --quiet --method flc --resolution "$FLC_SIZE" \
            --frames "$FLC_FRAMES" --navg $navg --tiling "$FLC_TILING" --timings "$scene" \
            >"$dir/t" || exit 1
        "$helper" "$scene" "$FLC_SIZE" 2 --navg $navg --tiling "$FLC_TILING" >"$dir/c" || exit 1
        cpu=$(passes_column "$dir/c" 13)
        errors=""
        for frames in 1 16; do
            "$GB_BIN/gbview" --headless --quiet --method flc --terms indirect \
                --resolution "$FLC_ERROR_SIZE" --frames $frames --navg $navg "$scene" \
                -o "$dir/f.exr" || exit 1
            errors="$errors | $(relative_mse "$dir/f.exr" "$ref")"
        done
        echo "| $navg | $(mean_ms "frame (gpu)" "$dir/t") | $(mean_ms "indirect light" "$dir/t") | $cpu$errors |"
    done
    echo
    echo "### $name: Table 1 (ms, $FLC_SIZE, N_avg 256, frames after the first of 3)"
    echo
    echo "| tiling | scene triangles (regular+divergent) | G-buffer | SM (once) | regular | divergent | upscaling+blur | indirect | full frame | tessellated VPLs a frame |"
    echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    for tiling in $FLC_TABLE_TILINGS; do
        "$helper" "$scene" "$FLC_SIZE" 3 --tiling "$tiling" >"$dir/p" || exit 1
        sed -n '2s/^ *//p' "$dir/p" | awk '{ printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
            $2, $4, $5, $6, $7, $8, $9, $10, $11, $12 }'
    done
    echo
done

for scene in $FLC_BRUTE_SCENES; do
    section "$scene" "FLC against no decimation ($FLC_ERROR_SIZE, N_avg 256, 2 frames)"
    echo "| VPLs | indirect ms | frame ms | FLC passes, CPU ms | rel. MSE |"
    echo "|---|---:|---:|---:|---:|"
    for mode in flc all; do
        flag=""
        [ $mode = all ] && flag=--no-decimation
        "$helper" "$scene" "$FLC_ERROR_SIZE" 2 --indirect $flag -o "$dir/$mode.exr" \
            >"$dir/$mode" || exit 1
        indirect=$(passes_column "$dir/$mode" 10)
        frame=$(passes_column "$dir/$mode" 11)
        cpu=$(passes_column "$dir/$mode" 13)
        eval "indirect_$mode=$indirect cpu_$mode=$cpu"
        label="FLC (Alg. 1)"
        [ $mode = all ] && label="every VPL triangle"
        echo "| $label | $indirect | $frame | $cpu | $(relative_mse "$dir/$mode.exr" "$ref") |"
    done
    echo
    awk -v a="$indirect_all" -v b="$indirect_flc" -v c="$cpu_all" -v d="$cpu_flc" \
        'BEGIN { printf "Speed-up of the decimation: %.1fx (indirect wall time), %.1fx (CPU time)\n\n", a / b, c / d }'
done
