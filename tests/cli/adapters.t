#!/bin/sh
# adapters.t — the adapters to heavy libraries (formats/adapter.h): no
# program links OpenImageIO or OpenVDB (they load gibake-openimageio.so and
# gibake-openvdb.so from BIN/../lib/gibake/ on the first image or voxel
# file), `--version` maps neither, a run that reads an image or a .vdb maps
# its adapter, and a program moved away from its adapters fails as a tool
# should, naming the file it could not load.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"

adapters=$GB_BIN/../lib/gibake
needs imgdiff reference voxelize thin gbview

[ -f "$adapters/gibake-openimageio.so" ] &&
    ldd "$adapters/gibake-openimageio.so" | grep -q 'libOpenImageIO\.so'
ok $? "gibake-openimageio.so is built beside bin/ and links OpenImageIO"
[ -f "$adapters/gibake-openvdb.so" ] && ldd "$adapters/gibake-openvdb.so" | grep -q 'libopenvdb\.so'
ok $? "gibake-openvdb.so is built beside bin/ and links OpenVDB"

for tool in "$GB_BIN"/*; do
    [ -x "$tool" ] || continue
    ! ldd "$tool" | grep -q 'OpenImageIO\|libopenvdb'
    ok $? "$(basename "$tool") links neither OpenImageIO nor OpenVDB"
done

# The libraries a run maps, as the dynamic loader reports them.
LD_DEBUG=files "$GB_BIN/voxelize" --version >/dev/null 2>"$dir/version.files"
status=$?
[ $status = 0 ] && ! grep -q 'OpenImageIO\|libopenvdb\|gibake-' "$dir/version.files"
ok $? "voxelize --version: the loader maps no adapter, OpenVDB or OpenImageIO"

printf 'P3\n2 1\n255\n100 100 100 0 0 0\n' >"$dir/a.ppm"
LD_DEBUG=files "$GB_BIN/imgdiff" "$dir/a.ppm" "$dir/a.ppm" >"$dir/out" 2>"$dir/read.files"
status=$?
[ $status = 0 ] && grep -q "file=.*gibake-openimageio.so" "$dir/read.files" &&
    grep -q 'file=libOpenImageIO' "$dir/read.files" && grep -q '^pixels 2$' "$dir/out"
ok $? "imgdiff on two images loads the OpenImageIO adapter, compares 2 pixels"

"$GB_BIN/voxelize" -q -r 16 "$GB_ROOT/scenes/cornell/cornell.scene" -o "$dir/box.vdb"
LD_DEBUG=files "$GB_BIN/thin" -q "$dir/box.vdb" -o "$dir/box.skel" >/dev/null 2>"$dir/thin.files"
status=$?
[ $status = 0 ] && [ -s "$dir/box.skel" ] && grep -q "file=.*gibake-openvdb.so" "$dir/thin.files" &&
    grep -q 'file=libopenvdb' "$dir/thin.files" && ! grep -q 'OpenImageIO' "$dir/thin.files"
ok $? "thin on a .vdb loads the OpenVDB adapter (and not OpenImageIO), writes the skeleton"

# Copies of imgdiff and thin with no lib/gibake/ beside their folder.
mkdir -p "$dir/alone/bin"
cp "$GB_BIN/imgdiff" "$GB_BIN/thin" "$dir/alone/bin/"
"$dir/alone/bin/imgdiff" "$dir/a.ppm" "$dir/a.ppm" >"$dir/out" 2>"$dir/err"
status=$?
[ $status = 1 ] &&
    grep -q "^imgdiff: .*cannot load the openimageio adapter $dir/alone/bin/../lib/gibake/gibake-openimageio.so: " "$dir/err"
ok $? "imgdiff without its adapter: exit 1, 'cannot load the openimageio adapter PATH: why' (status $status: $(head -1 "$dir/err"))"
"$dir/alone/bin/thin" -q "$dir/box.vdb" -o "$dir/alone.skel" >"$dir/out" 2>"$dir/err"
status=$?
[ $status = 1 ] && [ ! -e "$dir/alone.skel" ] &&
    grep -q "^thin: .*cannot load the openvdb adapter $dir/alone/bin/../lib/gibake/gibake-openvdb.so: " "$dir/err"
ok $? "thin without its adapter: exit 1, nothing written, 'cannot load the openvdb adapter PATH: why' (status $status: $(head -1 "$dir/err"))"

tap_done
