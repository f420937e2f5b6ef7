#!/bin/sh
# adapters.t — the adapters to heavy libraries (formats/adapter.h): no
# program links OpenImageIO (they load gibake-openimageio.so from
# BIN/../lib/gibake/ on the first image), `--version` maps none of its
# libraries, an image run maps it, and a program moved away from the
# adapter fails as a tool should, naming the file it could not load.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-adapters.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM
. "$(dirname "$0")/tap.sh"

adapter=$GB_BIN/../lib/gibake/gibake-openimageio.so
for t in imgdiff reference voxelize gbview; do
    if [ ! -x "$GB_BIN/$t" ]; then
        echo "Bail out! $GB_BIN/$t not built"
        exit 1
    fi
done

[ -f "$adapter" ] && ldd "$adapter" | grep -q 'libOpenImageIO\.so'
ok $? "the adapter $(basename "$adapter") is built beside bin/ and links OpenImageIO"

for tool in "$GB_BIN"/*; do
    [ -x "$tool" ] || continue
    ! ldd "$tool" | grep -q OpenImageIO
    ok $? "$(basename "$tool") does not link OpenImageIO"
done

# The libraries a run maps, as the dynamic loader reports them.
LD_DEBUG=files "$GB_BIN/voxelize" --version >/dev/null 2>"$dir/version.files"
! grep -q 'OpenImageIO' "$dir/version.files" && grep -q 'file=libopenvdb' "$dir/version.files"
ok $? "voxelize --version: the loader maps OpenVDB, no OpenImageIO"

printf 'P3\n2 1\n255\n100 100 100 0 0 0\n' >"$dir/a.ppm"
LD_DEBUG=files "$GB_BIN/imgdiff" "$dir/a.ppm" "$dir/a.ppm" >"$dir/out" 2>"$dir/read.files"
status=$?
[ $status = 0 ] && grep -q "file=.*gibake-openimageio.so" "$dir/read.files" &&
    grep -q 'file=libOpenImageIO' "$dir/read.files" && grep -q '^pixels 2$' "$dir/out"
ok $? "imgdiff on two images loads the adapter and OpenImageIO, compares 2 pixels"

# A copy of imgdiff with no lib/gibake/ beside its folder.
mkdir -p "$dir/alone/bin"
cp "$GB_BIN/imgdiff" "$dir/alone/bin/"
"$dir/alone/bin/imgdiff" "$dir/a.ppm" "$dir/a.ppm" >"$dir/out" 2>"$dir/err"
status=$?
[ $status = 1 ] &&
    grep -q "^imgdiff: .*cannot load the openimageio adapter $dir/alone/bin/../lib/gibake/gibake-openimageio.so: " "$dir/err"
ok $? "without the adapter: exit 1 and 'cannot load the openimageio adapter PATH: why' (status $status: $(head -1 "$dir/err"))"

tap_done
