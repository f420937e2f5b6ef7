#!/bin/sh
# implicit.t — gbview --method implicit (Dong 2007) on the Cornell box as a
# user types it: it runs headless, twice the same image, and its indirect
# term is close to `reference --mode indirect1`; --bins and --bounces are
# checked. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
tool=$GB_BIN/gbview
reference=$GB_BIN/reference
imgdiff=$GB_BIN/imgdiff
scene=$GB_ROOT/scenes/cornell/cornell.scene
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-implicit.XXXXXX") || exit 1
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

if [ ! -x "$tool" ] || [ ! -x "$imgdiff" ]; then
    echo "Bail out! $tool or $imgdiff not built"
    exit 1
fi

small="--headless --method implicit --bins 8 --resolution 64x64 --quiet"

"$tool" $small --terms indirect "$scene" -o "$dir/a.exr" >"$dir/out" 2>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
ok $status "--method implicit renders the Cornell box headless"
"$tool" $small --terms indirect "$scene" -o "$dir/b.exr"
"$imgdiff" "$dir/a.exr" "$dir/b.exr" >"$dir/same"
ok "$([ "$(value max_error "$dir/same")" = 0 ]; echo $?)" "rendering twice: identical images"

"$tool" $small --terms indirect --bounces 2 "$scene" -o "$dir/two.exr"
"$imgdiff" "$dir/two.exr" "$dir/a.exr" >"$dir/diff"
ok "$([ "$(value max_error "$dir/diff")" != 0 ]; echo $?)" "--bounces 2 adds light"
"$tool" $small --bins 0 "$scene" >"$dir/out" 2>"$dir/err"
ok "$([ $? = 2 ] && grep -q 'bad value "0"' "$dir/err"; echo $?)" "--bins 0: a usage error"

# The indirect term against the reference's one-bounce indirect light.
# Measured at 128x128, 6x12x12 bins, 1 bounce: 0.0036 (a black image: 0.040);
# the threshold leaves room for the reference's noise at 64 spp.
if [ -x "$reference" ]; then
    "$reference" --mode indirect1 --spp 64 --resolution 128x128 --quiet "$scene" \
        -o "$dir/ref.exr"
    "$tool" --headless --method implicit --terms indirect --resolution 128x128 --quiet \
        "$scene" -o "$dir/implicit.exr"
    "$imgdiff" "$dir/implicit.exr" "$dir/ref.exr" >"$dir/error"
    error=$(value relative_mse "$dir/error")
    echo "# relative MSE of the indirect term to reference --mode indirect1: $error"
    ok "$(below "$error" 0.01; echo $?)" "indirect term: relative MSE below 0.01"
else
    skip "$reference not built"
fi

echo "1..$count"
[ $failed = 0 ]
