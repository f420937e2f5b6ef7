#!/bin/sh
# implicit_large.sh — implicit visibility (Dong et al. 2007) on the shared
# scenes of 66 000 triangles and more, at the runtime's defaults (6x12x12
# bins, 1 bounce, element size and cell):
#   the model (vertices of the finer mesh, elements), the CPU seconds of
#   CreateHierarchicalLinks on one thread, its wall seconds on 2 (the
#   runtime's default), and of Refine + Push (bench/implicit_steps.c, one
#   frame), and the peak memory of gbview --method implicit;
#   the error (imgdiff relative_mse) of gbview --method implicit and of
#   gbview --method direct (direct light only) against reference --mode
#   full (IMPLICIT_SPP samples a pixel, default 256) at IMPLICIT_SIZE
#   (default 128x128);
#   with the paper's rules alone (gbview --paper-rules,
#   IMPLICIT_PAPER_RULES=1): the links' wall seconds on 2 threads and the
#   error against the same reference.
# IMPLICIT_SCENES: the scene files (default scenes/shared/{sponza,
# staircase,living-room}.scene). Prints a Markdown table on stdout.
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).

. "$(dirname "$0")/common.sh"
IMPLICIT_SPP=${IMPLICIT_SPP:-256}
IMPLICIT_SIZE=${IMPLICIT_SIZE:-128x128}
IMPLICIT_SCENES=${IMPLICIT_SCENES:-"$root/scenes/shared/sponza.scene $root/scenes/shared/staircase.scene $root/scenes/shared/living-room.scene"}
helper=$(bench_program implicit_steps) || exit 1

echo "implicit visibility on large scenes; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg);" \
    "$(date -u +%Y-%m-%d)"
echo
echo "| scene | vertices | elements | create links (s) | on 2 threads (wall s) | refine & push (s) | gbview peak memory (MiB) |" \
    "implicit: relative MSE | direct only: relative MSE | paper's rules: on 2 threads (wall s) | paper's rules: relative MSE |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in $IMPLICIT_SCENES; do
    name=$(basename "$scene" .scene)
    "$helper" scene "$scene" 1 1 12 >"$dir/steps" 2>"$dir/err" || { cat "$dir/err" >&2; exit 1; }
    IMPLICIT_LINK_THREADS=2 "$helper" scene "$scene" 1 1 12 >"$dir/steps2" 2>"$dir/err" ||
        { cat "$dir/err" >&2; exit 1; }
    threaded=$(awk 'NR == 2 { print $NF / 1000 }' "$dir/steps2")
    IMPLICIT_PAPER_RULES=1 IMPLICIT_LINK_THREADS=2 "$helper" scene "$scene" 1 1 12 \
        >"$dir/steps_paper" 2>"$dir/err" || { cat "$dir/err" >&2; exit 1; }
    paper_threaded=$(awk 'NR == 2 { print $NF / 1000 }' "$dir/steps_paper")
    "$GB_BIN/gbview" --headless --quiet -m implicit --paper-rules -r "$IMPLICIT_SIZE" \
        -o "$dir/paper.exr" "$scene" || exit 1
    /usr/bin/time -f "%M" -o "$dir/memory" "$GB_BIN/gbview" --headless --quiet -m implicit \
        -r "$IMPLICIT_SIZE" -o "$dir/implicit.exr" "$scene" || exit 1
    "$GB_BIN/gbview" --headless --quiet -m direct -r "$IMPLICIT_SIZE" -o "$dir/direct.exr" \
        "$scene" || exit 1
    "$GB_BIN/reference" --quiet --mode full --spp "$IMPLICIT_SPP" -r "$IMPLICIT_SIZE" \
        -o "$dir/reference.exr" "$scene" || exit 1
    implicit=$(relative_mse "$dir/implicit.exr" "$dir/reference.exr")
    direct=$(relative_mse "$dir/direct.exr" "$dir/reference.exr")
    paper=$(relative_mse "$dir/paper.exr" "$dir/reference.exr")
    awk -v name="$name" -v memory="$(cat "$dir/memory")" -v implicit="$implicit" \
        -v direct="$direct" -v threaded="$threaded" -v paper="$paper" \
        -v paper_threaded="$paper_threaded" 'NR == 2 {
        printf "| %s | %s | %s | %.1f | %.1f | %.1f | %.0f | %.3f | %.3f | %.1f | %.3f |\n",
            name, $2, $3, $5 / 1000, threaded, $6 / 1000, memory / 1024, implicit, direct,
            paper_threaded, paper
    }' "$dir/steps"
done
