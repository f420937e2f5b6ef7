#!/bin/sh
# gbview.t — the runtime as a user types it, headless on llvmpipe (and in a
# window under Xvfb when xvfb-run is there): images written, direct light
# close to `reference --mode direct` (and not without shadows), the same
# image twice, sizes and cameras, a bad baked file ignored by a method that
# does not read it and named by one that does, errors as a Unix tool
# reports them.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/gbview
reference=$GB_BIN/reference
imgdiff=$GB_BIN/imgdiff
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs gbview imgdiff

small="--headless --resolution 64x64 --quiet"

"$tool" $small "$scene" -o "$dir/a.exr" >"$dir/out" 2>"$dir/err"
ok $? "headless render of the Cornell box: exit status 0"
ok "$([ -s "$dir/a.exr" ] && [ ! -s "$dir/out" ] && [ ! -s "$dir/err" ]; echo $?)" \
    "writes OUT.exr, --quiet prints nothing"
"$tool" $small "$scene" -o "$dir/a.png"
ok "$([ -s "$dir/a.png" ]; echo $?)" "writes OUT.png"

"$tool" $small "$scene" -o "$dir/b.exr"
"$imgdiff" "$dir/a.exr" "$dir/b.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" "rendering twice: identical images"

"$tool" --headless --resolution 40x30 "$scene" -o "$dir/c.exr" &&
    "$tool" --headless --resolution 40x30 --frames 3 "$scene" -o "$dir/d.exr"
"$imgdiff" "$dir/c.exr" "$dir/d.exr" >"$dir/same" 2>&1
ok "$([ "$(value pixels "$dir/same")" = 1200 ]; echo $?)" "--resolution 40x30 gives 40x30 pixels"
ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" "--frames 3: the same last frame"

# A second camera (the first one moved) in a copy of the scene file.
sed "s|^mesh .*|mesh $(cd "$GB_ROOT/scenes/cornell" && pwd)/cornell.obj|" "$scene" >"$dir/two.scene"
echo "camera position 400 273 -800 target 278 273 0 up 0 1 0 fov 39.3077 resolution 64 64" \
    >>"$dir/two.scene"
"$tool" $small --camera 1 "$dir/two.scene" -o "$dir/camera1.exr"
ok $? "--camera 1 of a scene with two cameras"
"$tool" $small --camera 0 "$dir/two.scene" -o "$dir/camera0.exr"
"$imgdiff" "$dir/camera0.exr" "$dir/a.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" "camera 0 is the Cornell box's camera"
"$imgdiff" "$dir/camera0.exr" "$dir/camera1.exr" >"$dir/diff"
ok "$([ "$(value max_error "$dir/diff")" != 0 ]; echo $?)" "camera 1 sees another image"

"$tool" $small --timings "$scene" --frames 2 >"$dir/out"
ok "$(grep -q "^g-buffer" "$dir/out" && grep -q "^direct light" "$dir/out" &&
    grep -q "^frame (gpu)" "$dir/out"; echo $?)" "--timings prints the passes' times"

# Direct light against the reference (the unit test states the figures).
if [ -x "$reference" ]; then
    "$reference" --mode direct --resolution 128x128 --quiet "$scene" -o "$dir/ref.exr"
    "$tool" --headless --resolution 128x128 --supersample 4 --quiet "$scene" -o "$dir/direct.exr"
    "$tool" --headless --resolution 128x128 --supersample 4 --no-shadows --quiet "$scene" \
        -o "$dir/unshadowed.exr"
    "$imgdiff" "$dir/direct.exr" "$dir/ref.exr" >"$dir/error"
    "$imgdiff" "$dir/unshadowed.exr" "$dir/ref.exr" >"$dir/error-unshadowed"
    shadowed=$(value relative_mse "$dir/error")
    unshadowed=$(value relative_mse "$dir/error-unshadowed")
    echo "# relative MSE to reference --mode direct: $shadowed; without shadows: $unshadowed"
    ok "$(below "$shadowed" 0.004; echo $?)" "direct light: relative MSE below 0.004"
    ok "$(below "$unshadowed" 0.004 && echo 1 || echo 0)" "--no-shadows: not below 0.004"
else
    missing "$reference not built"
    missing "$reference not built"
fi

# Baked files are read when a method needs them: a method that uses none
# ignores a bad bake folder; one that needs a corrupt file fails naming it.
mkdir "$dir/bake"
echo "not a skeleton" >"$dir/bake/cornell.skel"
echo "not a light octree" >"$dir/bake/cornell.lot"
"$tool" --headless --resolution 16x16 --bake "$dir/bake" "$scene" -o "$dir/bake.png" \
    >"$dir/out" 2>"$dir/err"
ok $? "--bake with corrupt and missing files, direct light: exit status 0"
ok "$([ ! -s "$dir/err" ] && [ -s "$dir/bake.png" ]; echo $?)" \
    "... nothing on stderr (direct light reads no baked file), the image rendered"
expect_failure "--method octree with a corrupt .lot" 1 "cornell\.lot" \
    --headless --resolution 16x16 --method octree --bake "$dir/bake" "$scene" \
    -o "$dir/bad-octree.png"
ok "$([ ! -e "$dir/bad-octree.png" ]; echo $?)" "... and writes no image"
expect_failure "--method topo with the nearest-node grid missing" 1 "cornell\.grid\.vdb" \
    --headless --resolution 16x16 --method topo --bake "$dir/bake" "$scene" \
    -o "$dir/bad-topo.png"

expect_failure "a missing scene" 1 "^gbview: .*missing.scene" \
    --headless "$dir/missing.scene" -o "$dir/missing.png"
ok "$([ ! -e "$dir/missing.png" ]; echo $?)" "a failed run writes no image"
expect_failure "an unknown method" 2 "unknown method 'radiosity'" \
    --headless --method radiosity "$scene"
expect_failure "octree without a bake folder" 1 "octree: needs a light octree" \
    --headless --method octree "$scene" -o "$dir/octree.png"
expect_failure "a camera the scene lacks" 1 "^gbview: camera 3" \
    --headless --camera 3 "$scene" -o "$dir/camera3.png"
expect_failure "--headless with nothing to write" 2 "writes nothing without -o" \
    --headless "$scene"
expect_failure "a bad resolution" 2 "^gbview: --resolution: '0x5' is not WxH with each side in 1\.\.16384$" \
    --headless --resolution 0x5 "$scene"

"$tool" --help >"$dir/out"
ok "$([ $? = 0 ] && grep -q "^usage: gbview" "$dir/out"; echo $?)" "--help on stdout, status 0"
# The methods' options, declared in their folders (runtime/*/..._options.c),
# each once in the help and parsed as common/cli.h says.
for option in vpls write-vpls topo-visibility atlas navg mu levels epsilon tiling \
    no-decimation bins bounces paper-rules bin-filter; do
    listed=$(grep -c "^      --$option[ =]" "$dir/out")
    ok "$([ "$listed" = 1 ]; echo $?)" "--help lists --$option once (got $listed)"
done
expect_failure "implicit's --bins out of range" 2 \
    "^gbview: --bins: '0' is not an integer in 1\.\.64$" $small --bins 0 "$scene" -o "$dir/x.png"
expect_failure "flc's --levels out of range" 2 \
    "^gbview: --levels: '17' is not an integer in 1\.\.16$" $small --levels 17 "$scene" -o "$dir/x.png"
expect_failure "topo's --topo-visibility not a choice" 2 \
    "^gbview: --topo-visibility: 'some' is not one of full, clusters, none$" \
    $small --topo-visibility some "$scene" -o "$dir/x.png"
expect_failure "flc-iv's --bin-filter not a choice" 2 \
    "^gbview: --bin-filter: 'cubic' is not one of bilinear, nearest$" \
    $small --bin-filter cubic "$scene" -o "$dir/x.png"
expect_failure "implicit's flag --paper-rules given a value" 2 \
    "option '--paper-rules' takes no value" $small --paper-rules=1 "$scene" -o "$dir/x.png"
"$tool" --version >"$dir/out"
ok "$([ $? = 0 ] && grep -q "gbview (gibake)" "$dir/out"; echo $?)" "--version"

# The window, on a virtual X server.
# Mesa's GLX driver is unloaded at exit still holding a few hundred bytes;
# preloaded, it stays mapped and LeakSanitizer can name (and waive) it.
glx_driver=$(ls /usr/lib/*/dri/swrast_dri.so 2>/dev/null | head -1)
if command -v xvfb-run >/dev/null 2>&1; then
    xvfb-run -a env ${glx_driver:+LD_PRELOAD=$glx_driver} "$tool" --frames 3 --resolution 64x64 --timings "$scene" \
        -o "$dir/window.exr" >"$dir/out" 2>"$dir/err"
    status=$?
    [ $status = 0 ] || sed 's/^/# /' "$dir/err"
    ok $status "window mode under Xvfb: draws --frames 3 and exits 0"
    ok "$(grep -q "^present" "$dir/out"; echo $?)" "the window presents its frames"
    "$imgdiff" "$dir/window.exr" "$dir/a.exr" >"$dir/same" 2>&1
    ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" \
        "with -o, its last frame is saved: the headless image"
else
    for i in 1 2 3; do missing "xvfb-run not installed (Debian package xvfb)"; done
fi

tap_done
