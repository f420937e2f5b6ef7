#!/bin/sh
# flc.t — Forward Light Cuts (gbview --method flc) as a user types it,
# headless on llvmpipe: the indirect light of the Cornell box against
# `reference --mode indirect1-unshadowed` at the same camera and size, the
# error falling as progressive frames grow, the same image for the same
# frame count, tiling, the options and their bad values.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/gbview
reference=$GB_BIN/reference
imgdiff=$GB_BIN/imgdiff
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs gbview imgdiff reference

# The relative MSE of 16 frames at 64x64 against the reference at 1024 spp
# is about 0.0005 (1 frame about 0.0017); the threshold leaves room.
threshold=0.001
flc="--headless --resolution 64x64 --quiet --method flc --terms indirect"

"$reference" --mode indirect1-unshadowed --resolution 64x64 --spp 1024 --quiet "$scene" \
    -o "$dir/ref.exr"
ok $? "reference --mode indirect1-unshadowed of the Cornell box"

"$tool" $flc "$scene" -o "$dir/f1.exr" >"$dir/out" 2>"$dir/err"
ok "$([ $? = 0 ] && [ -s "$dir/f1.exr" ] && [ ! -s "$dir/err" ]; echo $?)" \
    "gbview --method flc --terms indirect: exit 0, an image, nothing on stderr"
for k in 4 16; do
    "$tool" $flc --frames $k "$scene" -o "$dir/f$k.exr"
done
for k in 1 4 16; do
    "$imgdiff" "$dir/f$k.exr" "$dir/ref.exr" >"$dir/e$k"
done
e1=$(value relative_mse "$dir/e1")
e4=$(value relative_mse "$dir/e4")
e16=$(value relative_mse "$dir/e16")
echo "# relative MSE to the reference: 1 frame $e1, 4 frames $e4, 16 frames $e16"
ok "$(below "$e4" "$e1" && below "$e16" "$e4"; echo $?)" "the error falls: 16 < 4 < 1 frames"
ok "$(below "$e16" $threshold; echo $?)" "16 frames: relative MSE below $threshold"

"$tool" $flc --frames 3 "$scene" -o "$dir/a.exr"
"$tool" $flc --frames 3 "$scene" -o "$dir/b.exr"
"$imgdiff" "$dir/a.exr" "$dir/b.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" "--frames 3 twice: the same image"
"$imgdiff" "$dir/a.exr" "$dir/f4.exr" >"$dir/other"
ok "$([ "$(value max_error "$dir/other")" != 0 ]; echo $?)" "--frames 4: another image"

"$tool" $flc --frames 4 --tiling 1 "$scene" -o "$dir/tiled.exr"
"$imgdiff" "$dir/tiled.exr" "$dir/ref.exr" >"$dir/e-tiled"
tiled=$(value relative_mse "$dir/e-tiled")
echo "# --tiling 1, 4 frames: $tiled"
ok "$(below "$tiled" 0.003; echo $?)" "--tiling 1: relative MSE below 0.003"

# Without decimation every triangle is a VPL: the estimator's mean with no
# light-cut variance (measured: about 0.0007 after 1 frame).
"$tool" $flc --no-decimation "$scene" -o "$dir/every.exr"
"$imgdiff" "$dir/every.exr" "$dir/ref.exr" >"$dir/e-every"
every=$(value relative_mse "$dir/e-every")
echo "# --no-decimation, 1 frame: $every"
ok "$(below "$every" $threshold && below "$every" "$e1"; echo $?)" \
    "--no-decimation: below $threshold and below 1 decimated frame"

"$tool" $flc --navg 64 --mu 3 --levels 4 --epsilon 5 "$scene" -o "$dir/options.exr"
ok $? "--navg 64 --mu 3 --levels 4 --epsilon 5"

"$tool" --headless --resolution 64x64 --quiet --method flc "$scene" -o "$dir/both.exr" &&
    "$tool" --headless --resolution 64x64 --quiet --method flc --terms direct "$scene" \
        -o "$dir/direct.exr"
"$imgdiff" "$dir/both.exr" "$dir/direct.exr" >"$dir/added"
ok "$([ "$(value max_error "$dir/added")" != 0 ]; echo $?)" "--terms both adds the indirect light"

expect_failure "--tiling 9" 2 "^gbview: --tiling: '9' is not an integer in 0\.\.4$" $flc --tiling 9 "$scene"
expect_failure "--mu 1" 2 "^gbview: --mu: '1' is not a number in \[1\.01, 1000\]$" $flc --mu 1 "$scene"
expect_failure "--navg 0" 2 "^gbview: --navg: '0' is not a number in \[1, 1e+06\]$" $flc --navg 0 "$scene"
expect_failure "--levels 17" 2 "^gbview: --levels: '17' is not an integer in 1\.\.16$" $flc --levels 17 "$scene"

"$tool" --help >"$dir/out"
ok "$(grep -q -- "--navg" "$dir/out" && grep -q -- "--tiling" "$dir/out"; echo $?)" \
    "--help lists the flc options"

tap_done
