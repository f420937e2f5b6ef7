#!/bin/sh
# segment.t — the segment tool as a user runs it: voxelize the Cornell box at
# 48 voxels, thin it, segment the skeleton (with the voxels, the gates fitted,
# as make bake does, and without), evaluate the segmentation; exit codes,
# same bytes twice, precision and recall in [0, 1], and bad input refused
# with "segment: ..." and no output left behind. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
scene=$GB_ROOT/scenes/cornell/cornell.scene

# expect_status WHAT STATUS COMMAND...: the command exits with STATUS.
expect_status() {
    what=$1
    want=$2
    shift 2
    "$@" >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ "$status" = "$want" ]; echo $?)" "$what: exit status $want (got $status)"
    [ "$status" = "$want" ] || sed 's/^/#   /' "$dir/err"
}

# in_unit_interval X: 0 when 0 <= X <= 1.
in_unit_interval() {
    awk -v x="$1" 'BEGIN { exit !(x != "" && x + 0 >= 0 && x + 0 <= 1) }'
}

for tool in voxelize thin segment; do
    if [ ! -x "$GB_BIN/$tool" ]; then
        echo "1..0 # SKIP $GB_BIN/$tool not built"
        exit 0
    fi
done

expect_status "voxelize" 0 "$GB_BIN/voxelize" -q -r 48 "$scene" -o "$dir/c.vdb"
"$GB_BIN/voxelize" -q -r 32 "$scene" -o "$dir/c32.vdb"
expect_status "thin" 0 "$GB_BIN/thin" -q "$dir/c.vdb" -o "$dir/c.skel" --grid "$dir/c.grid.vdb"
expect_status "segment" 0 "$GB_BIN/segment" -q "$dir/c.skel" -o "$dir/c.seg"
ok "$([ -s "$dir/c.seg" ]; echo $?)" "segment: writes the .seg file"
ok "$([ ! -s "$dir/out" ] && [ ! -s "$dir/err" ]; echo $?)" "segment: silent without --stats"
expect_status "segment --alpha 0 --stats" 0 "$GB_BIN/segment" --alpha 0 --stats "$dir/c.skel" \
    -o "$dir/c0.seg"
grep -q '^clusters  *[0-9][0-9]* (alpha 0 %)' "$dir/out"
ok $? "segment --stats: prints the clusters and alpha"
"$GB_BIN/segment" -q "$dir/c.skel" -o "$dir/again.seg"
cmp -s "$dir/c.seg" "$dir/again.seg"
ok $? "segment: the same skeleton gives the same bytes"

# the gates fitted to the voxels (make bake's way)
fit="--voxels $dir/c.vdb --grid $dir/c.grid.vdb"
expect_status "segment --voxels --grid --stats" 0 "$GB_BIN/segment" --stats "$dir/c.skel" $fit \
    -o "$dir/fitted.seg"
fitted=$(awk '$1 == "fitted" && $2 == "gates" { print $3 }' "$dir/out")
opening=$(awk '$1 == "opening" && $2 == "gates" { print $3 }' "$dir/out")
gates=$(awk '$1 == "gates" { print $2 }' "$dir/out")
echo "# fitted: $gates gates, $opening opening gates, $fitted fitted"
ok "$([ "${fitted:-0}" -gt 0 ] && [ "${opening:-0}" -gt 0 ] &&
    [ "$gates" -ge "$fitted" ]; echo $?)" \
    "segment --voxels --grid: gates fitted ($fitted of $gates) and opening gates added ($opening)"
ok "$(! cmp -s "$dir/c.seg" "$dir/fitted.seg"; echo $?)" \
    "segment --voxels --grid: other gates than the paper's"
"$GB_BIN/segment" -q "$dir/c.skel" $fit -o "$dir/fitted2.seg"
cmp -s "$dir/fitted.seg" "$dir/fitted2.seg"
ok $? "segment --voxels --grid: the same inputs give the same bytes"
expect_status "evaluate the fitted gates" 0 "$GB_BIN/segment" --evaluate -q "$scene" \
    "$dir/fitted.seg" "$dir/c.grid.vdb" --pairs 2000
grep -q "^gates  *$gates\$" "$dir/out"
ok $? "evaluate: the fitted file's $gates gates"

expect_status "evaluate" 0 "$GB_BIN/segment" --evaluate -q "$scene" "$dir/c.seg" \
    "$dir/c.grid.vdb" --pairs 2000 --seed 7
cp "$dir/out" "$dir/table"
for predictor in same-cluster one-gate; do
    precision=$(awk -v p="$predictor" '$1 == p { print $2 }' "$dir/table")
    recall=$(awk -v p="$predictor" '$1 == p { print $3 }' "$dir/table")
    in_unit_interval "$precision"
    ok $? "evaluate: $predictor precision $precision in [0, 1]"
    in_unit_interval "$recall"
    ok $? "evaluate: $predictor recall $recall in [0, 1]"
done
grep -q '^pairs  *2000 (seed 7)$' "$dir/table"
ok $? "evaluate: 2000 pairs, seed 7"
"$GB_BIN/segment" --evaluate -q "$scene" "$dir/c.seg" "$dir/c.grid.vdb" --pairs 2000 \
    --seed 7 >"$dir/table2" 2>/dev/null
grep -v '^seconds' "$dir/table" >"$dir/t1"
grep -v '^seconds' "$dir/table2" >"$dir/t2"
cmp -s "$dir/t1" "$dir/t2"
ok $? "evaluate: the same seed gives the same table"

# errors
expect_status "--help" 0 "$GB_BIN/segment" --help
grep -q '^usage: segment' "$dir/out"
ok $? "--help: prints the usage on stdout"
expect_status "--version" 0 "$GB_BIN/segment" --version
expect_status "no output" 2 "$GB_BIN/segment" "$dir/c.skel"
expect_status "alpha 101" 2 "$GB_BIN/segment" --alpha 101 "$dir/c.skel" -o "$dir/x.seg"
expect_status "pairs 0" 2 "$GB_BIN/segment" --evaluate "$scene" "$dir/c.seg" "$dir/c.grid.vdb" \
    --pairs 0
expect_status "--voxels without --grid" 2 "$GB_BIN/segment" "$dir/c.skel" --voxels "$dir/c.vdb" \
    -o "$dir/x.seg"
grep -q "^segment: --voxels and --grid go together" "$dir/err"
ok $? "--voxels without --grid: says they go together"
expect_status "--evaluate with --grid" 2 "$GB_BIN/segment" --evaluate "$scene" "$dir/c.seg" \
    "$dir/c.grid.vdb" --grid "$dir/c.grid.vdb"
expect_status "--voxels of another resolution" 1 "$GB_BIN/segment" "$dir/c.skel" \
    --voxels "$dir/c32.vdb" --grid "$dir/c.grid.vdb" -o "$dir/x.seg"
grep -q "^segment: $dir/c32.vdb: its voxel frame is not the segmentation's" "$dir/err"
ok $? "--voxels of another resolution: refused as stale, naming the file"
ok "$([ ! -e "$dir/x.seg" ]; echo $?)" "--voxels of another resolution: no output left"
expect_status "--grid of another file kind" 1 "$GB_BIN/segment" "$dir/c.skel" --voxels "$dir/c.vdb" \
    --grid "$dir/c.vdb" -o "$dir/x.seg"
grep -q "^segment: $dir/c.vdb: " "$dir/err"
ok $? "--grid of a voxel file without nearest_node: the message names the file"
expect_status "missing skeleton" 1 "$GB_BIN/segment" "$dir/missing.skel" -o "$dir/x.seg"
grep -q "^segment: $dir/missing.skel: " "$dir/err"
ok $? "missing skeleton: the message names the file"
ok "$([ ! -e "$dir/x.seg" ]; echo $?)" "missing skeleton: no output left"

head -c 100 "$dir/c.skel" >"$dir/short.skel"
expect_status "truncated skeleton" 1 "$GB_BIN/segment" "$dir/short.skel" -o "$dir/x.seg"
ok "$([ ! -e "$dir/x.seg" ]; echo $?)" "truncated skeleton: no output left"
cp "$dir/c.seg" "$dir/bad.seg"
printf 'X' | dd of="$dir/bad.seg" bs=1 seek=200 conv=notrunc 2>/dev/null
expect_status "corrupt .seg" 1 "$GB_BIN/segment" --evaluate "$scene" "$dir/bad.seg" \
    "$dir/c.grid.vdb" --pairs 10
expect_status "a .skel as .seg" 1 "$GB_BIN/segment" --evaluate "$scene" "$dir/c.skel" \
    "$dir/c.grid.vdb" --pairs 10
grep -q "expected SEGM" "$dir/err"
ok $? "a .skel as .seg: says which kind it expected"

printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$dir/other.obj"
expect_status "another scene" 1 "$GB_BIN/segment" --evaluate "$dir/other.obj" "$dir/c.seg" \
    "$dir/c.grid.vdb" --pairs 10
grep -q "another scene" "$dir/err"
ok $? "another scene: refused as stale"
"$GB_BIN/voxelize" -q -r 48 "$dir/other.obj" -o "$dir/other.vdb"
expect_status "--voxels of another scene" 1 "$GB_BIN/segment" "$dir/c.skel" \
    --voxels "$dir/other.vdb" --grid "$dir/c.grid.vdb" -o "$dir/x.seg"
grep -q "^segment: $dir/other.vdb: made from another scene" "$dir/err"
ok $? "--voxels of another scene: refused as stale, naming the file"

tap_done
