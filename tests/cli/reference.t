#!/bin/sh
# reference.t — the reference renderer as a user types it, on the Cornell box
# at a few pixels: images written (EXR, PNG), the same bytes whatever the
# threads, errors reported as a Unix tool should.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/reference
imgdiff=$GB_BIN/imgdiff
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs reference imgdiff

small="--resolution 24x16 --spp 4 --quiet"

"$tool" $small --mode direct --png "$scene" -o "$dir/direct.exr" >"$dir/out" 2>"$dir/err"
ok $? "direct mode on the Cornell box: exit status 0"
ok "$([ -s "$dir/direct.exr" ] && [ -s "$dir/direct.png" ]; echo $?)" \
    "writes OUT.exr and, with --png, OUT.png"
ok "$([ ! -s "$dir/out" ] && [ ! -s "$dir/err" ]; echo $?)" "--quiet: nothing on stdout or stderr"

# (the EXR files themselves differ: the image adapter stamps a DateTime)
"$tool" $small --threads 1 --stats "$scene" -o "$dir/one.exr" >"$dir/out"
ok "$([ "$(value rays "$dir/out")" -gt 0 ] 2>/dev/null; echo $?)" "--stats prints the rays traced"
"$tool" $small --threads 2 "$scene" -o "$dir/two.exr"
"$imgdiff" "$dir/one.exr" "$dir/two.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ] && [ "$(value psnr "$dir/same")" = inf ]; echo $?)" \
    "the same pixels on 1 and 2 threads"
"$tool" $small --threads 2 --seed 9 "$scene" -o "$dir/seed.exr"
"$imgdiff" "$dir/one.exr" "$dir/seed.exr" >"$dir/diff"
ok "$([ "$(value max_error "$dir/diff")" != 0 ]; echo $?)" "another seed, another image"

"$tool" $small --mode indirect1-unshadowed --camera 0 "$scene" -o "$dir/u.exr"
ok $? "indirect1-unshadowed mode runs"

expect_failure "a missing scene" 1 "^reference: .*missing.scene" \
    --quiet "$dir/missing.scene" -o "$dir/missing.exr"
ok "$([ ! -e "$dir/missing.exr" ]; echo $?)" "a failed run writes no image"
expect_failure "an unknown mode" 2 "unknown mode \"indirect2\"" \
    --mode indirect2 "$scene" -o "$dir/x.exr"
expect_failure "vpl mode without a VPL file" 2 "^reference: --vpl FILE goes with --mode vpl" \
    --mode vpl "$scene" -o "$dir/x.exr"
expect_failure "a camera the scene lacks" 1 "^reference: .*no camera 3" \
    --quiet --camera 3 "$scene" -o "$dir/x.exr"
expect_failure "a VPL file that is not one" 1 "^reference: .*direct.png" \
    --quiet --vpl "$dir/direct.png" "$scene" -o "$dir/x.exr"
expect_failure "a bad resolution" 2 "^reference: --resolution: '0x5' is not WxH with each side in 1\.\.16384$" \
    --resolution 0x5 "$scene" -o "$dir/x.exr"

# --tile I/N and --merge: three parts of a 100x70 render (7x5 tiles, so the
# last row and column are part tiles) joined byte for byte into the whole one.
"$tool" -q --spp 2 -r 100x70 --seed 5 "$scene" -o "$dir/whole.exr"
parts=
for i in 0 1 2; do
    "$tool" -q --spp 2 -r 100x70 --seed 5 --tile $i/3 "$scene" -o "$dir/part$i.exr"
    parts="$parts $dir/part$i.exr"
done
"$tool" --merge $parts -o "$dir/merged.exr"
ok "$([ $? = 0 ] && cmp -s "$dir/whole.exr" "$dir/merged.exr"; echo $?)" \
    "--merge of --tile 0/3, 1/3, 2/3: the bytes of the whole render"
"$imgdiff" "$dir/part1.exr" "$dir/whole.exr" >"$dir/out"
ok "$(below 0.01 "$(value relative_mse "$dir/out")"; echo $?)" \
    "and a part alone is not the whole (relative MSE $(value relative_mse "$dir/out"))"
expect_failure "--merge of two of the three parts" 1 "not part 0 of 2" \
    --merge "$dir/part0.exr" "$dir/part1.exr" -o "$dir/x.exr"
expect_failure "--merge of the parts out of order" 1 "part1.exr: .*not part 0 of 3" \
    --merge "$dir/part1.exr" "$dir/part0.exr" "$dir/part2.exr" -o "$dir/x.exr"
expect_failure "--tile 3/3" 2 "'3/3' is not I/N" --tile 3/3 "$scene" -o "$dir/x.exr"

"$tool" --help >"$dir/out"
ok "$([ $? = 0 ] && grep -q "^usage: reference" "$dir/out"; echo $?)" "--help on stdout, status 0"
"$tool" --version >"$dir/out"
ok "$([ $? = 0 ] && grep -q "reference (gibake)" "$dir/out"; echo $?)" "--version"

tap_done
