#!/bin/sh
# sweep_voxels.sh — a parameter sweep with nothing but make and a shell loop
# (docs/usage.md, "make bake"): one scene baked at several voxel resolutions, each
# into its own BAKE folder side by side, then each bake's clusters and gates
# and segment --evaluate's precision and recall. Rerun it and only what
# changed is baked again.
#
#   sh bench/sweep_voxels.sh [SCENE [OUT]]    SWEEP_RESOLUTIONS="32 64 128"
#
# GB_BIN: the tools (default build/bin, built by make); OUT default sweep/.

root=$(cd "$(dirname "$0")/.." && pwd)
scene=${1:-$root/scenes/cornell/cornell.scene}
out=${2:-sweep}
name=$(basename "$scene" | sed 's/\.[^.]*$//')
GB_BIN=${GB_BIN:-$root/build/bin}

echo "| voxelize -r | clusters | gates | same-cluster precision / recall |" \
    "one-gate precision / recall |"
echo "|---:|---:|---:|---|---|"
for r in ${SWEEP_RESOLUTIONS:-32 64 128}; do
    make --no-print-directory -s -f "$root/bake.mk" BIN="$GB_BIN" BAKE="$out/r$r" \
        SCENE="$scene" VOXELIZE_FLAGS="-q -r $r" THIN_FLAGS=-q SEGMENT_FLAGS=-q \
        "$out/r$r/$name.seg" || exit 1
    "$GB_BIN/segment" --evaluate --quiet --pairs 20000 "$scene" "$out/r$r/$name.seg" \
        "$out/r$r/$name.grid.vdb" >"$out/r$r/evaluate.txt" || exit 1
    awk -v r="$r" '$1 == "clusters" { c = $2 } $1 == "gates" { g = $2 }
        $1 == "same-cluster" { s = $2 " / " $3 } $1 == "one-gate" { o = $2 " / " $3 }
        END { printf "| %s | %s | %s | %s | %s |\n", r, c, g, s, o }' "$out/r$r/evaluate.txt"
done
