#!/bin/sh
# implicit.sh — implicit visibility (Dong et al. 2007) on the CPU, every
# step every frame (bench/implicit_steps.c):
#   Table 1: ms for UpdateElements, CreateHierarchicalLinks, Refine + Push
#            (with the per-element lists), illumination (1 bounce) and the
#            frame, for a bumpy sphere on a ground plane (IMPLICIT_VERTICES,
#            default 3400, the paper's monster has 3378) under a white
#            environment, deformed each frame, at 6x8x8, 6x12x12, 6x16x16;
#            then the same with the paper's rules alone (IMPLICIT_PAPER_RULES);
#   scaling: the frame against the vertex count (IMPLICIT_SIZES, 1k-50k) at
#            6x8x8, and the exponent p of a least-squares fit t ~ N^p (the
#            paper: about O(N log N); over the same range N log N has the
#            slope printed beside it);
#   the same models at the runtime's element size and cell, from 1 000 to
#            300 000 vertices (IMPLICIT_RUNTIME_SIZES), with each run's peak
#            memory: the elements a scene gets stop growing with its mesh;
#   the Cornell box (scenes/cornell) at the runtime's element size.
# Means over IMPLICIT_FRAMES frames (default 3; 1 for the scaling), each
# after a frame that is not counted (its page faults, once). Prints
# Markdown tables on stdout.
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
IMPLICIT_VERTICES=${IMPLICIT_VERTICES:-3400}
IMPLICIT_FRAMES=${IMPLICIT_FRAMES:-3}
IMPLICIT_SIZES=${IMPLICIT_SIZES:-"1000 2000 4000 8000 16000 32000 50000"}
IMPLICIT_RUNTIME_SIZES=${IMPLICIT_RUNTIME_SIZES:-"1000 3000 10000 30000 100000 300000"}
helper=$(dirname "$GB_BIN")/bench/implicit_steps
out=$(mktemp "${TMPDIR:-/tmp}/gibake-bench-implicit.XXXXXX") || exit 1
err=$out.err
trap 'rm -f "$out" "$err"' EXIT INT TERM

# The helper is bench code that `make bench` builds into build/bench/.
if [ ! -x "$helper" ]; then
    echo "implicit.sh: $helper not built: run make bench" >&2
    exit 1
fi

echo "implicit visibility on the CPU; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg);" \
    "$(date -u +%Y-%m-%d)"

# Columns of implicit_steps: bins vertices elements update create refine
# illuminate total cpu.
percent_table() {
    echo "| bins | vertices | elements | update | create links | refine & push | illumination | total | wall | once: steps 1-2 |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    awk 'NR > 1 {
        p = $8
        printf "| 6x%sx%s | %s | %s | %.1f (%.0f %%) | %.1f (%.0f %%) | %.1f (%.0f %%) | %.1f (%.0f %%) | %.1f | %.1f | %.1f |\n",
            $1, $1, $2, $3, $4, 100 * $4 / p, $5, 100 * $5 / p, $6, 100 * $6 / p,
            $7, 100 * $7 / p, $8, $9, $10
    }' "$1"
}

# Table 1's model at 6x8x8, 6x12x12 and 6x16x16 into the file $1, run with
# the settings (VAR=VALUE) that follow.
table_1() {
    file=$1
    shift
    env "$@" "$helper" table "$IMPLICIT_VERTICES" "$IMPLICIT_FRAMES" 1 8 12 16 >"$file" 2>"$err" ||
        { cat "$err" >&2; exit 1; }
}

echo
echo "Table 1: bumpy sphere on a plane, ~$IMPLICIT_VERTICES vertices, 1 bounce, ms a frame" \
    "(CPU ms of each step, process time, both threads counted; wall: the frame)"
echo
table_1 "$out"
percent_table "$out"

echo
echo "The same model with the paper's rules alone (IMPLICIT_PAPER_RULES=1: subdivide at a whole bin," \
    "a link stored in the bin of the other's centre only), same run: what the runtime's additions cost"
echo
table_1 "$out.paper" IMPLICIT_PAPER_RULES=1
percent_table "$out.paper"
rm -f "$out.paper"

echo
echo "CreateHierarchicalLinks on 1 and 2 threads (IMPLICIT_LINK_THREADS), same model, same run:" \
    "wall ms a frame (the links are the same bytes: test_implicit)"
echo
echo "| bins | 1 thread | 2 threads | 2 / 1 |"
echo "|---|---:|---:|---:|"
table_1 "$out.2" IMPLICIT_LINK_THREADS=2
paste "$out" "$out.2" | awk 'NR > 1 { n = NF / 2
    printf "| 6x%sx%s | %.1f | %.1f | %.2f |\n", $1, $1, $n, $NF, $NF / $n }'
rm -f "$out.2"

echo
echo "Scaling at 6x8x8, 1 bounce, CPU ms a frame (wall: the frame)"
echo
echo "| vertices | elements | update | create links | refine & push | illumination | total | wall | once: steps 1-2 |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
# shellcheck disable=SC2086
"$helper" scale 8 1 $IMPLICIT_SIZES >"$out" 2>"$err" || { cat "$err" >&2; exit 1; }
awk 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $2, $3, $4, $5, $6, $7, $8, $9, $10 }' "$out"
awk 'NR > 1 && $8 > 0 {
        x = log($2); y = log($8); n++; sx += x; sy += y; sxx += x * x; sxy += x * y
        z = log($2 * log($2)); sz += z; sxz += x * z
        if (n == 1) first = $2; last = $2
    }
    END {
        if (n < 2) exit 1
        d = n * sxx - sx * sx
        printf "\nfit of frame CPU ms ~ N^p over N = %d..%d vertices: p = %.2f (N log N over that range: p = %.2f)\n",
            first, last, (n * sxy - sx * sy) / d, (n * sxz - sx * sz) / d
    }' "$out"

echo
echo "Scaling at the runtime's element size and cell, 6x8x8, 1 bounce, CPU ms a frame" \
    "(wall: the frame), and the run's peak memory"
echo
echo "| vertices | elements | update | create links | refine & push | illumination | total | wall | once: steps 1-2 | peak memory (MiB) |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for size in $IMPLICIT_RUNTIME_SIZES; do
    /usr/bin/time -f "%M" -o "$err.memory" "$helper" runtime-scale 8 1 "$size" >"$out" 2>"$err" ||
        { cat "$err" >&2; exit 1; }
    awk -v memory="$(cat "$err.memory")" 'NR > 1 {
        printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %.0f |\n",
            $2, $3, $4, $5, $6, $7, $8, $9, $10, memory / 1024
    }' "$out"
done
rm -f "$err.memory"

echo
echo "Cornell box (scenes/cornell, runtime element size), 1 bounce, CPU ms a frame (wall: the frame)"
echo
"$helper" scene "$root/scenes/cornell/cornell.scene" "$IMPLICIT_FRAMES" 1 8 12 16 >"$out" 2>"$err" || { cat "$err" >&2; exit 1; }
percent_table "$out"
