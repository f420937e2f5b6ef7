#!/bin/sh
# reference.sh — rays per second of the reference renderer against Embree's
# raw rtcIntersect1 on incoherent rays, on the same scene in the same run
# (bench/reference_rate.c), on 1 and 2 threads, for the Cornell box, the
# Stanford bunny and Sponza. Target (issue 6): ratio >= 0.8. Prints a
# Markdown table on stdout.
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).
# REFERENCE_SCENES, REFERENCE_THREADS, REFERENCE_ROUNDS override the lists.
#
# raw: rtcIntersect1 alone on rays drawn in advance (origins uniform in the
# scene's bounds, directions uniform), on an Embree scene built as the
# reference builds it. ref: every ray the reference traces (closest-hit and
# shadow rays) over its rendering time, full mode, 320x240, 4 spp, first
# camera. Each figure is the median of alternating rounds; the cpu columns
# count process CPU time rather than wall time, which other processes on the
# same cores disturb less.

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

echo "reference renderer against raw rtcIntersect1 (Mrays/s); $(nproc) cores; $(date -u +%Y-%m-%d)"
echo
echo "| scene | triangles | threads | raw | ref | ratio | raw cpu | ref cpu | ratio cpu |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for threads in $threads_list; do
    for scene in $scenes; do
        path=$root/$scene
        if [ ! -f "$path" ]; then
            echo "| $scene | missing: $path |"
            continue
        fi
        "$helper" --threads "$threads" --rounds "$rounds" "$path" | grep -v '^#' |
            awk '{ printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
                   $1, $2, $3, $4, $5, $6, $7, $8, $9 }'
    done
done
