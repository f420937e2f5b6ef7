#!/bin/sh
# topo.sh — the topological method (Noël & Biri 2014) on llvmpipe: Table I
# (ms per pass GP, IUGC, LA, IL and the frame, for 512, 1024, 2048 VPLs, at
# TOPO_SIZE, default 1024x512; bench/topo_passes.c) and Table II (8-bit MSE
# with imgdiff against `reference --vpl` of the same VPLs: direct only, no
# visibility on the indirect light, this method; at TOPO_ERROR_SIZE, default
# 512x256, 512 VPLs; reference direct at TOPO_SPP, default 16, added to the
# VPL image with oiiotool, Debian openimageio-tools, for the full images). Bakes each scene into a
# temporary folder (voxelize -r TOPO_VOXELS: 48 for the Cornell box, 128 for
# Sponza). Prints Markdown tables on stdout.
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
TOPO_SIZE=${TOPO_SIZE:-1024x512}
TOPO_ERROR_SIZE=${TOPO_ERROR_SIZE:-512x256}
TOPO_SPP=${TOPO_SPP:-16}
TOPO_FRAMES=${TOPO_FRAMES:-3}
scenes=${TOPO_SCENES:-"cornell/cornell.scene:48 shared/sponza.scene:128"}
build=$(dirname "$GB_BIN")
helper=$build/bench/topo_passes
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-topo.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM
for tool in voxelize thin segment gbview reference imgdiff; do
    if [ ! -x "$GB_BIN/$tool" ]; then
        echo "topo.sh: $GB_BIN/$tool not built"
        exit 1
    fi
done

# The helper is bench code that `make bench` builds into build/bench/.
if [ ! -x "$helper" ]; then
    echo "topo.sh: $helper not built: run make bench" >&2
    exit 1
fi

mse() {
    [ -f "$2" ] || { echo "n/a (no oiiotool)"; return; }
    "$GB_BIN/imgdiff" "$1" "$2" | sed -n 's/^mse_srgb8 //p'
}

echo "topological GI on llvmpipe; $(nproc) cores; $(date -u +%Y-%m-%d)"
for entry in $scenes; do
    scene=$root/scenes/${entry%:*}
    voxels=${entry#*:}
    name=$(basename "$scene" .scene)
    bake=$dir/$name
    mkdir -p "$bake"
    "$GB_BIN/voxelize" -q -r "$voxels" "$scene" -o "$bake/$name.vdb" &&
        "$GB_BIN/thin" -q "$bake/$name.vdb" -o "$bake/$name.skel" --grid "$bake/$name.grid.vdb" &&
        "$GB_BIN/segment" -q "$bake/$name.skel" -o "$bake/$name.seg" || exit 1

    echo
    echo "Table I, $name ($voxels voxels), $TOPO_SIZE, ms per pass (GP = G-buffer + visibility clusters)"
    echo
    echo "| VPLs | GP | IUGC | LA | IL | total |"
    echo "|---:|---:|---:|---:|---:|---:|"
    "$helper" "$scene" "$bake" "$TOPO_SIZE" "$TOPO_FRAMES" 512 1024 2048 2>/dev/null |
        awk 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6 }'

    view="--headless --quiet -r $TOPO_ERROR_SIZE"
    "$GB_BIN/gbview" $view "$scene" -o "$dir/direct.exr" 2>/dev/null
    "$GB_BIN/gbview" $view --terms indirect "$scene" -o "$dir/black.exr" 2>/dev/null
    for v in none full; do
        "$GB_BIN/gbview" $view --bake "$bake" -m topo --vpls 512 --topo-visibility $v \
            --write-vpls "$dir/v.vpls" "$scene" -o "$dir/both_$v.exr" 2>/dev/null
        "$GB_BIN/gbview" $view --bake "$bake" -m topo --vpls 512 --topo-visibility $v \
            --terms indirect "$scene" -o "$dir/ind_$v.exr" 2>/dev/null
    done
    "$GB_BIN/reference" -q --vpl "$dir/v.vpls" --spp 1 -r "$TOPO_ERROR_SIZE" "$scene" \
        -o "$dir/ref_vpl.exr"
    "$GB_BIN/reference" -q --mode direct --spp "$TOPO_SPP" -r "$TOPO_ERROR_SIZE" "$scene" \
        -o "$dir/ref_direct.exr"
    command -v oiiotool >/dev/null &&
        oiiotool "$dir/ref_direct.exr" "$dir/ref_vpl.exr" --add -o "$dir/ref_full.exr"

    echo
    echo "Table II, $name, $TOPO_ERROR_SIZE, 512 VPLs: 8-bit MSE against reference --vpl"
    echo
    echo "| image | direct only | no visibility | this method |"
    echo "|---|---:|---:|---:|"
    echo "| full (direct + indirect) | $(mse "$dir/direct.exr" "$dir/ref_full.exr") |" \
        "$(mse "$dir/both_none.exr" "$dir/ref_full.exr") |" \
        "$(mse "$dir/both_full.exr" "$dir/ref_full.exr") |"
    echo "| indirect light only | $(mse "$dir/black.exr" "$dir/ref_vpl.exr") |" \
        "$(mse "$dir/ind_none.exr" "$dir/ref_vpl.exr") |" \
        "$(mse "$dir/ind_full.exr" "$dir/ref_vpl.exr") |"
done
