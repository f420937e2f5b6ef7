#!/bin/sh
# sky_methods.sh — every method on a scene lit by its sky (default the
# living room, lit only through its windows) against `reference --mode
# full` (SKY_SPP samples a pixel, default 512) at SKY_SIZE (default
# 128x72): relative MSE and its trimmed twin with --environment-lights 0
# (the sky only seen, what every method drew before the sky had lights)
# and with the default lights. flc and flc-iv after 16 frames; topo on a
# make bake with VOXELIZE_FLAGS="-r 64". One Markdown table.
# SKY_SCENE: the scene; GB_BIN: the tools (default build/bin).
. "$(dirname "$0")/common.sh"
needs gbview reference imgdiff voxelize thin segment

scene=${SKY_SCENE:-$root/scenes/shared/living-room.scene}
size=${SKY_SIZE:-128x72}
spp=${SKY_SPP:-512}
make -s -f "$root/bake.mk" BIN="$GB_BIN" BAKE="$dir/bake" SCENE="$scene" \
    VOXELIZE_FLAGS="-r 64" "$dir/bake/$(basename "$scene" .scene).seg" >"$dir/bake.log" 2>&1 || {
    echo "sky_methods.sh: the bake failed:" >&2
    cat "$dir/bake.log" >&2
    exit 1
}
"$GB_BIN/reference" --quiet --mode full --spp "$spp" --resolution "$size" "$scene" -o "$dir/ref.exr"

echo "| method | relative MSE, no sky lights | trimmed | relative MSE, sky lights | trimmed |"
echo "|---|---:|---:|---:|---:|"
for method in direct topo flc flc-iv implicit; do
    line="| $method"
    for lights in 0 default; do
        flags="--method $method --resolution $size"
        [ "$lights" = 0 ] && flags="$flags --environment-lights 0"
        case $method in
        flc | flc-iv) flags="$flags --frames 16" ;;
        topo) flags="$flags --bake $dir/bake" ;;
        esac
        # shellcheck disable=SC2086
        "$GB_BIN/gbview" --headless --quiet $flags "$scene" -o "$dir/$method.exr"
        "$GB_BIN/imgdiff" "$dir/$method.exr" "$dir/ref.exr" >"$dir/diff"
        line="$line | $(printf '%.3f | %.3f' "$(value relative_mse "$dir/diff")" \
            "$(value relative_mse_trimmed "$dir/diff")")"
    done
    echo "$line |"
done
