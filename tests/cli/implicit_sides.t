#!/bin/sh
# implicit_sides.t — gbview --method implicit (Dong 2007) on surfaces seen
# from their back, against the reference, which shades both sides of a
# surface (common/brdf.h). A closed 2 x 2 x 2 room lit by a point light,
# the camera inside, in two windings: every face's normal into the room,
# and every face's normal out of it (as the staircase's far wall faces out
# of its scene). The reference renders both alike; implicit visibility must
# too: each side of an element gathers from its own hemisphere and a back
# face shows its back's light. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/gbview
reference=$GB_BIN/reference

needs gbview imgdiff reference

# room.obj: normals into the room. Corners: x, z in -1..1, y in 0..2.
cat >"$dir/inward.obj" <<'EOF_OBJ'
mtllib room.mtl
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
v -1 2 -1
v 1 2 -1
v 1 2 1
v -1 2 1
usemtl white
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 3 4 8 7
usemtl red
f 1 5 8 4
usemtl green
f 2 3 7 6
EOF_OBJ
# The same faces with their corners in the other order: normals outward.
awk '/^f / { print "f", $5, $4, $3, $2; next } { print }' "$dir/inward.obj" >"$dir/outward.obj"
cat >"$dir/room.mtl" <<'EOF_MTL'
newmtl white
Kd 0.7 0.7 0.7
newmtl red
Kd 0.7 0.15 0.1
newmtl green
Kd 0.15 0.6 0.1
EOF_MTL
for winding in inward outward; do
    cat >"$dir/$winding.scene" <<EOF_SCENE
gibake-scene 1
mesh $winding.obj
environment 0 0 0
light point position 0.3 1.6 0.2 intensity 2 2 2
camera position 0 1 0.95 target -0.1 0.8 -1 up 0 1 0 fov 75 resolution 48 48
EOF_SCENE
done

# Each winding against its own reference (--mode full: direct light and
# every bounce; 4 bounces here, the walls reflect 0.7), and against direct
# light alone. Measured (48x48, 6x12x12 bins, reference at 256 spp):
# relative MSE inward 0.0094, outward 0.0091, outward against inward
# 0.00002. Before elements had two sides the outward room got no indirect
# light at all: 0.394, the error of direct light alone (outward against
# inward 0.37).
for winding in inward outward; do
    "$reference" --mode full --spp 256 --quiet "$dir/$winding.scene" -o "$dir/$winding-ref.exr"
    "$tool" --headless --method implicit --bounces 4 --quiet "$dir/$winding.scene" \
        -o "$dir/$winding.exr" 2>"$dir/err"
    ok_run "the room wound $winding renders with --method implicit"
    "$tool" --headless --method direct --quiet "$dir/$winding.scene" -o "$dir/$winding-direct.exr"
done
inward=$(image_diff relative_mse "$dir/inward.exr" "$dir/inward-ref.exr")
outward=$(image_diff relative_mse "$dir/outward.exr" "$dir/outward-ref.exr")
direct=$(image_diff relative_mse "$dir/outward-direct.exr" "$dir/outward-ref.exr")
between=$(image_diff relative_mse "$dir/outward.exr" "$dir/inward.exr")
echo "# relative MSE to reference --mode full: inward $inward, outward $outward" \
    "(direct light alone: $direct); outward against inward: $between"
ok "$(below "$inward" 0.02; echo $?)" "room wound inward: relative MSE below 0.02"
ok "$(below "$outward" 0.02; echo $?)" "room wound outward: relative MSE below 0.02"
ok "$(below "$between" 0.001; echo $?)" "the two windings: the same image within a relative MSE of 0.001"

tap_done
