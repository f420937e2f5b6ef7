#!/bin/sh
# octree.t — gbview --method octree (the light octree, vivianloc-2007 §3.2,
# §4.2) on the Cornell box: photons and cluster bake NAME.lot into a bake
# folder, gbview renders its indirect term headless, twice the same image,
# without NaN, close to the reference's indirect light; on a sunlit floor
# written here, the octree of its direct photons gives the analytic
# Kd/π E cos θ, and the octree of its (no) indirect photons black; a
# missing .lot is a clear error. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/gbview
photons=$GB_BIN/photons
cluster=$GB_BIN/cluster
reference=$GB_BIN/reference
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs gbview photons cluster imgdiff

# The bake: NAME.lot, NAME the scene file's name, as gbview --bake looks for it.
mkdir "$dir/bake"
"$photons" -n 200000 --quiet "$scene" -o "$dir/cornell.phot" >/dev/null 2>"$dir/err" &&
    "$cluster" --depth 5 --quiet "$scene" "$dir/cornell.phot" -o "$dir/bake/cornell.lot" \
        >/dev/null 2>>"$dir/err"
ok_run "photons -n 200000 and cluster --depth 5 bake cornell.lot"

small="--headless --method octree --terms indirect --resolution 96x96 --quiet"
"$tool" $small --bake "$dir/bake" "$scene" -o "$dir/a.exr" >"$dir/out" 2>"$dir/err"
ok_run "--method octree renders the Cornell box headless"
"$tool" $small --bake "$dir/bake" "$scene" -o "$dir/b.exr" 2>/dev/null
"$GB_BIN/imgdiff" "$dir/a.exr" "$dir/b.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" "rendering twice: identical images"
# A NaN pixel would make the error against itself NaN, not 0.
ok "$([ "$(value relative_mse "$dir/same")" = 0 ]; echo $?)" "no NaN: relative MSE to itself is 0"
# As the window draws it: the atlas in slices, the image in parts, the walk
# shown meanwhile; the final image is the whole frame's bytes.
"$tool" $small --budget 1 --bake "$dir/bake" "$scene" -o "$dir/budget.exr" 2>/dev/null
cmp -s "$dir/a.exr" "$dir/budget.exr"
ok $? "--budget 1 (the atlas in slices, the image in parts): the whole frame's bytes"
"$tool" --headless --method direct --terms indirect --resolution 96x96 --quiet "$scene" \
    -o "$dir/black.exr" 2>/dev/null
ok "$(below 0.01 "$(image_diff max_error "$dir/a.exr" "$dir/black.exr")"; echo $?)" \
    "the octree adds indirect light"

# The photons store light reflected at least once (photons --store indirect,
# several bounces), so the octree's term is every path reflected at least
# twice: reference --mode full --min-bounces 2. Measured at 96x96, 64 spp,
# photons -n 200000, cluster --depth 5: 0.0058 (a black image: 0.106; two
# reference images of different seeds: 0.010; VDL irradiance taken as facing
# its direction, octree.h: 0.016).
if [ -x "$reference" ]; then
    "$reference" --mode full --min-bounces 2 --spp 64 --resolution 96x96 --quiet "$scene" \
        -o "$dir/ref.exr"
    close_to "indirect term" "reference --mode full --min-bounces 2" 0.012 "$dir/a.exr" \
        "$dir/ref.exr"
else
    missing "$reference not built"
fi

# A sun over a lone floor (Kd 0.8, the OBJ default; irradiance 2, cos θ =
# 0.8), written here. Its photons stored at every hit (--store all) are all
# direct hits, so the octree's term on the floor is the sun's reflected
# light Kd/π E cos θ = 0.4074 (octree.h: on a leaf's own plane a VDL gives
# Kd/π times its irradiance), which reference --mode direct gives exactly
# (a constant image). The camera sees 0.8 around the centre, the floor is
# 2 each side: no gathering disc crosses its edge. K = 1000 photons a leaf:
# ~3 % noise per leaf; measured relative MSE 0.00048 (the other convention,
# E facing the VDL's direction, would be 20 % low: 0.037).
floor_obj "$dir/floor.obj"
cat >"$dir/floor.scene" <<'EOF'
gibake-scene 1
mesh floor.obj
light directional direction 0.6 -0.8 0 irradiance 2 2 2
camera position 0 3 0 target 0 0 0 up 0 0 1 fov 30 resolution 64 64
EOF
floor=$dir/floor.scene
mkdir "$dir/floor-all" "$dir/floor-indirect"
"$photons" -q --store all -n 400000 "$floor" -o "$dir/all.phot" 2>"$dir/err" &&
    "$cluster" -q --depth 5 --knn 1000 "$floor" "$dir/all.phot" \
        -o "$dir/floor-all/floor.lot" 2>>"$dir/err" &&
    "$tool" --headless --quiet --method octree --terms indirect --bake "$dir/floor-all" \
        "$floor" -o "$dir/floor-octree.exr" 2>>"$dir/err"
ok_run "sun over a floor: photons --store all, cluster, gbview --method octree"
if [ -x "$reference" ]; then
    "$reference" -q --mode direct --spp 4 "$floor" -o "$dir/floor-direct.exr"
    error=$(image_diff relative_mse "$dir/floor-octree.exr" "$dir/floor-direct.exr")
    echo "# sun over a floor: relative MSE of the octree's term to Kd/pi E cos(theta): $error"
    ok "$(below "$error" 0.003; echo $?)" \
        "sun over a floor: the octree gives Kd/pi E cos(theta), relative MSE below 0.003"
else
    missing "$reference not built"
fi

# The same floor with the photons of indirect light only (the default): a
# lone floor reflects nothing onto itself, so no photon is stored, every
# leaf's VDL array is empty (V = 0) and the octree's term is black, not NaN.
"$photons" -q -n 20000 "$floor" -o "$dir/indirect.phot" 2>"$dir/err" &&
    "$cluster" -q --depth 5 "$floor" "$dir/indirect.phot" \
        -o "$dir/floor-indirect/floor.lot" 2>>"$dir/err" &&
    "$tool" --headless --quiet --method octree --terms indirect --bake "$dir/floor-indirect" \
        "$floor" -o "$dir/floor-none.exr" 2>>"$dir/err" &&
    "$tool" --headless --quiet --method direct --terms indirect "$floor" \
        -o "$dir/floor-black.exr" 2>>"$dir/err"
ok_run "lone floor, indirect photons only: an octree without VDLs renders"
"$GB_BIN/imgdiff" "$dir/floor-none.exr" "$dir/floor-black.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ] && [ "$(value relative_mse "$dir/same")" = 0 ]; \
    echo $?)" "lone floor, indirect photons only: black, no NaN"

# A bake folder without the .lot: a clear error, no image.
mkdir "$dir/empty"
"$tool" $small --bake "$dir/empty" "$scene" -o "$dir/none.exr" >"$dir/out" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ]; echo $?)" "no cornell.lot: exit status 1 (got $status)"
ok "$(grep -q "^gbview: octree: no usable light octree: .*cornell.lot" "$dir/err"; echo $?)" \
    "no cornell.lot: says so on stderr"
ok "$([ ! -e "$dir/none.exr" ]; echo $?)" "no cornell.lot: no image"

tap_done
