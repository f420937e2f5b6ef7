#!/bin/sh
# reference.sh — rays per second of the reference renderer against raw
# Embree on the same scene in the same run (bench/reference_rate.c), on 1 and
# 2 threads, for the Cornell box, the Stanford bunny and Sponza. Target
# (issue 6): ratio >= 0.8 against the path yardstick. Prints a Markdown table
# on stdout.
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).
# REFERENCE_SCENES, REFERENCE_THREADS, REFERENCE_ROUNDS override the lists.
#
# ref: every ray the reference traces (closest-hit and shadow rays) over its
# rendering time, full mode, 320x240, 4 spp, 64 bounces, first camera.
# Two yardsticks, raw Embree with no shading, on an Embree scene built as the
# reference builds it:
#   path (the main figure, like for like; bench/raw_path_rate.h): the rays
#     the reference's paths are made of: camera rays through the same pixels,
#     samples and tiles, at each hit the reference's shadow rays (an area-
#     light point picked as it picks it, each delta light) and one bounce,
#     cosine about the geometric normal, for 3 bounces: there the
#     reference's Russian roulette starts (it needs the materials), so the
#     path yardstick's paths can be a little shorter: "rays/sample" gives
#     both programs' mean;
#   raw (context; bench/raw_ray_rate.h): rtcIntersect1 alone on incoherent
#     rays drawn in advance (origins uniform in the scene's bounds,
#     directions uniform), which coherent camera rays and shadow rays beat.
# Each figure is the median of alternating rounds; the cpu columns count
# process CPU time rather than wall time, which other processes on the same
# cores disturb less.

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
scenes=${REFERENCE_SCENES:-"scenes/cornell/cornell.scene scenes/shared/bunny.scene
scenes/shared/sponza.scene"}
threads_list=${REFERENCE_THREADS:-"1 2"}
rounds=${REFERENCE_ROUNDS:-3}
build=$(dirname "$GB_BIN")
helper=$build/bench/reference_rate
# The helper is bench code that `make bench` builds into build/bench/.
if [ ! -x "$helper" ]; then
    echo "reference.sh: $helper not built: run make bench" >&2
    exit 1
fi

echo "reference renderer against raw Embree on its own paths (path) and on incoherent rays (raw)," \
    "Mrays/s; $(nproc) cores; load average $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
echo "| scene | triangles | threads | ref | path | ratio | raw | ratio raw |" \
    "ref cpu | path cpu | ratio cpu | raw cpu | ratio raw cpu | rays/sample ref / path |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for threads in $threads_list; do
    for scene in $scenes; do
        path=$root/$scene
        if [ ! -f "$path" ]; then
            echo "| $scene | missing: $path |"
            continue
        fi
        "$helper" --threads "$threads" --rounds "$rounds" "$path" | grep -v '^#' |
            awk '{ printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s |\n",
                   $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15 }'
    done
done
