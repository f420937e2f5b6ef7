#!/bin/sh
# octree.t — gbview --method octree (the light octree, vivianloc-2007 §3.2,
# §4.2) on the Cornell box: photons and cluster bake NAME.lot into a bake
# folder, gbview renders its indirect term headless, twice the same image,
# without NaN, close to the reference's indirect light; a missing .lot is a
# clear error. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
tool=$GB_BIN/gbview
photons=$GB_BIN/photons
cluster=$GB_BIN/cluster
reference=$GB_BIN/reference
imgdiff=$GB_BIN/imgdiff
scene=$GB_ROOT/scenes/cornell/cornell.scene
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-octree.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM
count=0
failed=0

ok() {
    count=$((count + 1))
    if [ "$1" = 0 ]; then
        echo "ok $count - $2"
    else
        failed=$((failed + 1))
        echo "not ok $count - $2"
    fi
}

skip() {
    count=$((count + 1))
    echo "ok $count # skip $1"
}

value() {
    sed -n "s/^$1 //p" "$2"
}

below() {
    awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a + 0 < b + 0) }'
}

for t in "$tool" "$photons" "$cluster" "$imgdiff"; do
    if [ ! -x "$t" ]; then
        echo "Bail out! $t not built"
        exit 1
    fi
done

# The bake: NAME.lot, NAME the scene file's name, as gbview --bake looks for it.
mkdir "$dir/bake"
"$photons" -n 200000 --quiet "$scene" -o "$dir/cornell.phot" >/dev/null 2>"$dir/err" &&
    "$cluster" --depth 5 --quiet "$scene" "$dir/cornell.phot" -o "$dir/bake/cornell.lot" \
        >/dev/null 2>>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
ok $status "photons -n 200000 and cluster --depth 5 bake cornell.lot"

small="--headless --method octree --terms indirect --resolution 96x96 --quiet"
"$tool" $small --bake "$dir/bake" "$scene" -o "$dir/a.exr" >"$dir/out" 2>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
ok $status "--method octree renders the Cornell box headless"
"$tool" $small --bake "$dir/bake" "$scene" -o "$dir/b.exr" 2>/dev/null
"$imgdiff" "$dir/a.exr" "$dir/b.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" "rendering twice: identical images"
# A NaN pixel would make the error against itself NaN, not 0.
ok "$([ "$(value relative_mse "$dir/same")" = 0 ]; echo $?)" "no NaN: relative MSE to itself is 0"
"$tool" --headless --method direct --terms indirect --resolution 96x96 --quiet "$scene" \
    -o "$dir/black.exr" 2>/dev/null
"$imgdiff" "$dir/a.exr" "$dir/black.exr" >"$dir/light"
ok "$(below 0.01 "$(value max_error "$dir/light")"; echo $?)" "the octree adds indirect light"

# The photons store light reflected at least once (photons --store indirect,
# several bounces), so the octree's term is every path reflected at least
# twice: reference --mode full --min-bounces 2. Measured at 96x96, 64 spp,
# photons -n 200000, cluster --depth 5: 0.0058 (a black image: 0.106; two
# reference images of different seeds: 0.010; VDL irradiance taken as facing
# its direction, octree.h: 0.016).
if [ -x "$reference" ]; then
    "$reference" --mode full --min-bounces 2 --spp 64 --resolution 96x96 --quiet "$scene" \
        -o "$dir/ref.exr"
    "$imgdiff" "$dir/a.exr" "$dir/ref.exr" >"$dir/error"
    error=$(value relative_mse "$dir/error")
    echo "# relative MSE of the indirect term to reference --mode full --min-bounces 2: $error"
    ok "$(below "$error" 0.012; echo $?)" "indirect term: relative MSE below 0.012"
else
    skip "$reference not built"
fi

# A bake folder without the .lot: a clear error, no image.
mkdir "$dir/empty"
"$tool" $small --bake "$dir/empty" "$scene" -o "$dir/none.exr" >"$dir/out" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ]; echo $?)" "no cornell.lot: exit status 1 (got $status)"
ok "$(grep -q "^gbview: octree: no usable light octree: .*cornell.lot" "$dir/err"; echo $?)" \
    "no cornell.lot: says so on stderr"
ok "$([ ! -e "$dir/none.exr" ]; echo $?)" "no cornell.lot: no image"

echo "1..$count"
[ $failed = 0 ]
