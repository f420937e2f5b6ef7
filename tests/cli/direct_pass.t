#!/bin/sh
# direct_pass.t — the direct pass (every gbview frame's floor) against what
# it must give: a floor under a white sky reflects Kd L (the sky's pi L,
# worked out by hand, through 64 directional lights), a box on that floor
# shadows it as `reference --mode direct` does, and Sponza's sun, point
# light and sky match the reference through the cascades fitted to the
# view. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/gbview
reference=$GB_BIN/reference

needs gbview imgdiff

# A lone floor (Kd 0.8) under a sky of radiance 0.5, seen from above: every
# pixel Kd / pi x pi L = 0.4.
floor_obj "$dir/floor.obj"
cat >"$dir/floor.scene" <<'EOF2'
gibake-scene 1
mesh floor.obj
environment 0.5 0.5 0.5
camera position 0 1 0 target 0 0 0.001 up 0 0 -1 fov 60 resolution 32 32
EOF2
"$tool" --headless --quiet --method direct "$dir/floor.scene" -o "$dir/floor.exr" 2>"$dir/err"
ok_run "a floor under the sky renders"
if command -v oiiotool >/dev/null; then
    oiiotool --pattern constant:color=0.4,0.4,0.4 32x32 3 -d float -o "$dir/kd_l.exr"
    close_to "floor under a sky of 0.5" "Kd L = 0.4" 0.002 "$dir/floor.exr" "$dir/kd_l.exr"
else
    missing "oiiotool missing"
fi

# A unit box on a floor under a white sky (box_under_sky), seen from the
# side: the box's soft shadow from the sky against the reference's direct
# light (measured 0.0045; without the sky's lights, --environment-lights 0,
# 0.51).
box_under_sky "$dir"
if [ -x "$reference" ]; then
    "$reference" --quiet --mode direct --spp 64 "$dir/box.scene" -o "$dir/box_ref.exr"
    "$tool" --headless --quiet --method direct "$dir/box.scene" -o "$dir/box.exr"
    close_to "box under the sky" "reference --mode direct" 0.01 "$dir/box.exr" "$dir/box_ref.exr"
else
    missing "$reference not built"
fi

# Sponza, 256x144: the sun's shadows of the arches and columns through the
# cascades, the point light's, the sky's. Measured 0.0145; every pixel
# through the farthest cascade 0.0176, the scene-wide map alone
# (--cascade-size 0) 0.052.
sponza=$GB_ROOT/scenes/shared/sponza.scene
if [ -x "$reference" ] && [ -r "$GB_ROOT/../shared/scenes/sponza-dabrovic/sponza.obj" ]; then
    "$reference" --quiet --mode direct --spp 64 --resolution 256x144 "$sponza" \
        -o "$dir/sponza_ref.exr"
    "$tool" --headless --quiet --method direct --resolution 256x144 "$sponza" \
        -o "$dir/sponza.exr"
    close_to "Sponza" "reference --mode direct" 0.016 "$dir/sponza.exr" "$dir/sponza_ref.exr"
else
    missing "$reference or ../shared/scenes/sponza-dabrovic missing"
fi

tap_done
