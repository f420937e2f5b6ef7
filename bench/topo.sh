#!/bin/sh
# topo.sh — the topological method (Noël & Biri 2014) on llvmpipe: Table I
# (ms per pass GP, IUGC, LA, IL and the frame, for 512, 1024, 2048 VPLs, at
# TOPO_SIZE, default 1024x512, Sponza only; bench/topo_passes.c) and Table II
# (8-bit MSE with imgdiff against `reference --vpl` of the same VPLs: direct
# only, no visibility on the indirect light, clusters only (gates off), this
# method, and this method over no visibility; at TOPO_ERROR_SIZE, default
# 512x256, 512 VPLs; reference direct at TOPO_SPP, default 16, added to the
# VPL image with oiiotool, Debian openimageio-tools, for the full images).
#
# Three configurations, as the paper's Table II compares two of Sponza:
#   cornell         the Cornell box, its camera (voxelize -r 48)
#   sponza          Sponza, its camera in the court: sun and point light
#                   (voxelize -r 128)
#   sponza-gallery  the same Sponza and bake, camera in the lower gallery on
#                   the -z side looking along it: mostly indirect light
# Bakes each scene into a temporary folder. Prints Markdown tables on stdout.
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).
# TOPO_CONFIGS: a subset of the names above; TOPO_TABLE1=0 skips Table I.

. "$(dirname "$0")/common.sh"
TOPO_SIZE=${TOPO_SIZE:-1024x512}
TOPO_ERROR_SIZE=${TOPO_ERROR_SIZE:-512x256}
TOPO_SPP=${TOPO_SPP:-16}
TOPO_FRAMES=${TOPO_FRAMES:-3}
TOPO_TABLE1=${TOPO_TABLE1:-1}
configs=${TOPO_CONFIGS:-"cornell sponza sponza-gallery"}
needs voxelize thin segment gbview reference imgdiff
helper=$(bench_program topo_passes) || exit 1

mse() {
    [ -f "$2" ] || { echo "n/a"; return; }
    "$GB_BIN/imgdiff" "$1" "$2" | value mse_srgb8 -
}

ratio() {
    awk -v a="$1" -v b="$2" 'BEGIN { if (b + 0 > 0) printf "%.2f", a / b; else print "n/a" }'
}

# bake NAME SCENE VOXELS: voxelize, thin --grid, segment --voxels --grid
# into $dir/NAME, as make bake does
bake() {
    mkdir -p "$dir/$1"
    "$GB_BIN/voxelize" -q -r "$3" "$2" -o "$dir/$1/$1.vdb" &&
        "$GB_BIN/thin" -q "$dir/$1/$1.vdb" -o "$dir/$1/$1.skel" --grid "$dir/$1/$1.grid.vdb" &&
        "$GB_BIN/segment" -q "$dir/$1/$1.skel" --voxels "$dir/$1/$1.vdb" \
            --grid "$dir/$1/$1.grid.vdb" -o "$dir/$1/$1.seg"
}

# The gallery view: sponza.scene with its mesh path made absolute and
# another camera; the bake is Sponza's (the scene hash leaves cameras out),
# linked under this scene's name.
gallery_scene() {
    shared=$root/scenes/shared
    mesh=$(sed -n 's/^mesh //p' "$shared/sponza.scene")
    camera="camera position -12 2 -5.6 target 10 3 -5.0 up 0 1 0 fov 60"
    sed -e "s|^mesh .*|mesh $shared/$mesh|" -e "s|^camera .*|$camera resolution 640 360|" \
        "$shared/sponza.scene" >"$dir/sponza-gallery.scene"
    [ -d "$dir/sponza" ] || bake sponza "$shared/sponza.scene" 128 || return 1
    mkdir -p "$dir/sponza-gallery"
    for ext in vdb skel grid.vdb seg; do
        ln -sf "$dir/sponza/sponza.$ext" "$dir/sponza-gallery/sponza-gallery.$ext"
    done
}

table1() {
    echo
    echo "Table I, $1 ($3 voxels), $TOPO_SIZE, ms per pass (GP = G-buffer + visibility clusters)"
    echo
    echo "| VPLs | GP | IUGC | LA | IL | total |"
    echo "|---:|---:|---:|---:|---:|---:|"
    "$helper" "$2" "$dir/$1" "$TOPO_SIZE" "$TOPO_FRAMES" 512 1024 2048 2>/dev/null |
        awk 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6 }'
}

# table2 NAME SCENE
table2() {
    out=$dir/out-$1
    mkdir -p "$out"
    view="--headless --quiet -r $TOPO_ERROR_SIZE"
    "$GB_BIN/gbview" $view "$2" -o "$out/direct.exr" 2>/dev/null
    "$GB_BIN/gbview" $view --terms indirect "$2" -o "$out/black.exr" 2>/dev/null
    for v in none clusters full; do
        "$GB_BIN/gbview" $view --bake "$dir/$1" -m topo --vpls 512 --topo-visibility $v \
            --write-vpls "$out/v.vpls" "$2" -o "$out/both_$v.exr" 2>/dev/null
        "$GB_BIN/gbview" $view --bake "$dir/$1" -m topo --vpls 512 --topo-visibility $v \
            --terms indirect "$2" -o "$out/ind_$v.exr" 2>/dev/null
    done
    "$GB_BIN/reference" -q --vpl "$out/v.vpls" --spp 1 -r "$TOPO_ERROR_SIZE" "$2" \
        -o "$out/ref_vpl.exr"
    "$GB_BIN/reference" -q --mode direct --spp "$TOPO_SPP" -r "$TOPO_ERROR_SIZE" "$2" \
        -o "$out/ref_direct.exr"
    command -v oiiotool >/dev/null &&
        oiiotool "$out/ref_direct.exr" "$out/ref_vpl.exr" --add -o "$out/ref_full.exr"

    echo
    echo "Table II, $1, $TOPO_ERROR_SIZE, 512 VPLs: 8-bit MSE against reference --vpl"
    echo
    printf '| image | direct only | no visibility | clusters only | this method |'
    echo ' this / no visibility |'
    echo "|---|---:|---:|---:|---:|---:|"
    for image in full indirect; do
        if [ $image = full ]; then
            ref=$out/ref_full.exr first=$out/direct.exr prefix=both
            [ -f "$ref" ] || { echo "| full | n/a (no oiiotool) | | | | |"; continue; }
        else
            ref=$out/ref_vpl.exr first=$out/black.exr prefix=ind
        fi
        none=$(mse "$out/${prefix}_none.exr" "$ref")
        full=$(mse "$out/${prefix}_full.exr" "$ref")
        echo "| $image | $(mse "$first" "$ref") | $none |" \
            "$(mse "$out/${prefix}_clusters.exr" "$ref") | $full | $(ratio "$full" "$none") |"
    done
}

echo "topological GI on llvmpipe; $(nproc) cores; $(date -u +%Y-%m-%d)"
for name in $configs; do
    case $name in
    cornell)
        scene=$root/scenes/cornell/cornell.scene voxels=48
        bake cornell "$scene" $voxels || exit 1 ;;
    sponza)
        scene=$root/scenes/shared/sponza.scene voxels=128
        [ -d "$dir/sponza" ] || bake sponza "$scene" $voxels || exit 1
        [ "$TOPO_TABLE1" = 0 ] || table1 sponza "$scene" $voxels ;;
    sponza-gallery)
        scene=$dir/sponza-gallery.scene voxels=128
        gallery_scene || exit 1 ;;
    *)
        echo "topo.sh: unknown configuration $name" >&2
        exit 2 ;;
    esac
    table2 "$name" "$scene"
done
