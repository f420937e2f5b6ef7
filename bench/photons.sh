#!/bin/sh
# photons.sh — the photon tracer on Sponza (sun through the roof and a point
# light), 1 000 000 photons on 2 threads: photon paths and rays per second
# against Embree's raw rtcIntersect1 on the same scene in the same run
# (bench/photons_rate.c, when built beside the tools as ../bench/photons_rate),
# then the whole command as a user runs it, with its --stats.
# Targets (issue 7): rays/s >= 80 % of raw; 1 M photons <= 1.5 s on 2 cores;
# <= 32 bytes per stored photon.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the
# repository; COUNT, THREADS, ROUNDS override the defaults.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
COUNT=${COUNT:-1000000}
THREADS=${THREADS:-2}
ROUNDS=${ROUNDS:-3}
scene=$GB_ROOT/scenes/shared/sponza.scene
rate=$GB_BIN/../bench/photons_rate
out=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-photons.XXXXXX") || exit 1
trap 'rm -rf "$out"' EXIT INT TERM

echo "photons: $COUNT photons, $THREADS threads (Mrays/s; medians of $ROUNDS rounds)"
if [ -x "$rate" ]; then
    "$rate" --threads "$THREADS" --count "$COUNT" --rounds "$ROUNDS" "$scene" \
        "$GB_ROOT/scenes/cornell/cornell.scene"
else
    echo "(no $rate: the raw rtcIntersect1 comparison needs it built)"
fi
seconds() { awk '{ print $1 }' /proc/uptime; }
start=$(seconds)
if ! "$GB_BIN/photons" --quiet --stats --threads "$THREADS" --count "$COUNT" "$scene" \
    -o "$out/sponza.phot" >"$out/stats" 2>&1; then
    echo "photons failed: $(head -n 1 "$out/stats")"
    exit 1
fi
end=$(seconds)
stored=$(sed -n 's/^stored //p' "$out/stats")
size=$(wc -c <"$out/sponza.phot")
printf 'sponza command: %.2f s wall (scene load, build, trace, write); ' \
    "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')"
printf 'trace %s s (cpu %s s), build %s s; %s Mrays/s; %s photons stored, %.1f bytes each\n' \
    "$(sed -n 's/^seconds //p' "$out/stats")" "$(sed -n 's/^cpu_seconds //p' "$out/stats")" \
    "$(sed -n 's/^build_seconds //p' "$out/stats")" \
    "$(sed -n 's/^mrays_per_second //p' "$out/stats")" "$stored" \
    "$(awk -v s="$size" -v n="$stored" 'BEGIN { print s / n }')"
