#!/bin/sh
# photons.t — the photon tracer as a user types it, on the Cornell box with a
# few thousand photons: a map written, the same bytes whatever the threads,
# shards merged into the very file of a whole run, errors reported as a Unix
# tool should. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/photons
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs photons

small="--count 3000 --quiet"

"$tool" $small "$scene" -o "$dir/one.phot" >"$dir/out" 2>"$dir/err"
ok $? "the Cornell box: exit status 0"
ok "$([ -s "$dir/one.phot" ]; echo $?)" "writes OUT.phot"
ok "$([ ! -s "$dir/out" ] && [ ! -s "$dir/err" ]; echo $?)" "--quiet: nothing on stdout or stderr"

"$tool" $small --stats --threads 1 "$scene" -o "$dir/t1.phot" >"$dir/stats"
"$tool" $small --threads 2 "$scene" -o "$dir/t2.phot"
"$tool" $small --threads 3 "$scene" -o "$dir/t3.phot"
ok "$(cmp -s "$dir/t1.phot" "$dir/t2.phot" && cmp -s "$dir/t1.phot" "$dir/t3.phot"; echo $?)" \
    "the same bytes on 1, 2 and 3 threads"
ok "$(cmp -s "$dir/one.phot" "$dir/t1.phot"; echo $?)" "the same bytes run after run"
stored=$(value stored "$dir/stats")
ok "$([ "$(value photons "$dir/stats")" = 3000 ] && [ "$stored" -gt 0 ] 2>/dev/null; echo $?)" \
    "--stats prints the photons emitted and stored"
size=$(wc -c <"$dir/t1.phot")
ok "$([ "$size" -le $((32 * stored + 464)) ]; echo $?)" "32 bytes per stored photon ($size bytes)"
"$tool" $small --seed 9 "$scene" -o "$dir/seed.phot"
ok "$(! cmp -s "$dir/one.phot" "$dir/seed.phot"; echo $?)" "another seed, other photons"

for i in 0 1 2 3; do
    "$tool" $small --shard $i/4 "$scene" -o "$dir/shard$i.phot" || echo "shard $i failed"
done
"$tool" --merge "$dir/shard2.phot" "$dir/shard0.phot" "$dir/shard3.phot" "$dir/shard1.phot" \
    -o "$dir/merged.phot"
ok $? "--merge of 4 shards: exit status 0"
ok "$(cmp -s "$dir/one.phot" "$dir/merged.phot"; echo $?)" \
    "the merged shards are byte for byte the single run"

expect_failure "a missing scene" 1 "^photons: .*missing.scene" \
    --quiet "$dir/missing.scene" -o "$dir/missing.phot"
ok "$([ ! -e "$dir/missing.phot" ]; echo $?)" "a failed run writes no map"

printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$dir/dark.obj"
printf 'gibake-scene 1\nmesh dark.obj\n' >"$dir/dark.scene"
# No light: valid, its right answer is dark (tests/cli/hard_cases.t has more).
"$tool" --count 3000 --stats "$dir/dark.scene" -o "$dir/dark.phot" >"$dir/out" 2>"$dir/err"
ok $? "a scene with no light: exit status 0"
ok "$(grep -q "^photons: .*dark.scene: warning: no light" "$dir/err"; echo $?)" \
    "... a warning naming it"
ok "$([ -s "$dir/dark.phot" ] && [ "$(value stored "$dir/out")" = 0 ]; echo $?)" \
    "... and an empty map"

expect_failure "a bad store mode" 2 "^photons: --store: 'some' is not one of indirect, all$" \
    --store some "$scene" -o "$dir/x.phot"
expect_failure "shard 4 of 4" 2 "^photons: --shard: '4/4' is not I/N with I in 0\.\.N-1$" \
    --shard 4/4 "$scene" -o "$dir/x.phot"
expect_failure "zero photons" 2 "^photons: --count: '0' is not an integer in 1\.\.1099511627776$" \
    --count 0 "$scene" -o "$dir/x.phot"
expect_failure "256 bounces" 2 "^photons: --bounces: '256' is not an integer in 1\.\.255$" \
    --bounces 256 "$scene" -o "$dir/x.phot"
expect_failure "no output" 2 "expected one SCENE and -o OUT" "$scene"

expect_failure "merging 3 of 4 shards" 1 "shard.*of 4, but 3 files" \
    --merge "$dir/shard0.phot" "$dir/shard1.phot" "$dir/shard2.phot" -o "$dir/x.phot"
expect_failure "merging a shard twice" 1 "is also" \
    --merge "$dir/shard0.phot" "$dir/shard1.phot" "$dir/shard2.phot" "$dir/shard1.phot" \
    -o "$dir/x.phot"
"$tool" $small --seed 5 --shard 3/4 "$scene" -o "$dir/other3.phot"
expect_failure "merging shards of two seeds" 1 "not a shard of the run" \
    --merge "$dir/shard0.phot" "$dir/shard1.phot" "$dir/shard2.phot" "$dir/other3.phot" \
    -o "$dir/x.phot"

# a flipped byte in the middle of the photons
cp "$dir/one.phot" "$dir/bad.phot"
middle=$(($(wc -c <"$dir/bad.phot") / 2))
printf '\377' | dd of="$dir/bad.phot" bs=1 seek=$middle conv=notrunc 2>/dev/null
expect_failure "a corrupt map" 1 "^photons: .*bad.phot: .*checksum" \
    --merge "$dir/bad.phot" -o "$dir/x.phot"
expect_failure "a file that is no photon map" 1 "^photons: .*dark.obj" \
    --merge "$dir/dark.obj" -o "$dir/x.phot"
ok "$([ ! -e "$dir/x.phot" ]; echo $?)" "failed merges write nothing"

"$tool" --help >"$dir/out"
ok "$([ $? = 0 ] && grep -q "^usage: photons" "$dir/out"; echo $?)" "--help on stdout, status 0"
"$tool" --version >"$dir/out"
ok "$([ $? = 0 ] && grep -q "photons (gibake)" "$dir/out"; echo $?)" "--version"

# -n auto: the count doubles until the map's power in a grid of cells
# settles. Monte Carlo noise falls as 1/sqrt(N), so half the tolerance takes
# about four times the photons; the map is the fixed-count run's, at any
# thread count.
chosen() {
    sed -n 's/^photons //p' "$1"
}
"$tool" -q -n auto --tolerance 0.1 --stats -j 1 "$scene" -o "$dir/auto1.phot" >"$dir/auto1"
ok $? "-n auto --tolerance 0.1: exit status 0"
"$tool" -q -n auto --tolerance 0.1 -j 2 "$scene" -o "$dir/auto2.phot"
ok "$(cmp -s "$dir/auto1.phot" "$dir/auto2.phot"; echo $?)" "... the same bytes on 1 and 2 threads"
"$tool" -q -n "$(chosen "$dir/auto1")" "$scene" -o "$dir/fixed.phot"
ok "$(cmp -s "$dir/auto1.phot" "$dir/fixed.phot"; echo $?)" \
    "... the bytes of -n $(chosen "$dir/auto1"), the count it chose"
"$tool" -n auto --tolerance 0.05 --stats "$scene" -o "$dir/auto3.phot" >"$dir/auto3" \
    2>"$dir/err"
ratio=$(awk -v a="$(chosen "$dir/auto1")" -v b="$(chosen "$dir/auto3")" \
    'BEGIN { print (a > 0 ? b / a : 0) }')
ok "$(awk -v r="$ratio" 'BEGIN { exit !(r >= 2 && r <= 8) }'; echo $?)" \
    "--tolerance 0.05 takes about 4x the photons of 0.1: $(chosen "$dir/auto3") / $(chosen "$dir/auto1") = $ratio"
ok "$(grep -q "^photons: -n auto: $(chosen "$dir/auto3") photons" "$dir/err"; echo $?)" \
    "-n auto says the count it chose on stderr"
expect_failure "--tolerance without -n auto" 2 "is for -n auto" \
    -n 1000 --tolerance 0.1 "$scene" -o "$dir/x.phot"
expect_failure "-n auto with --shard" 1 "cannot be sharded" \
    -n auto --shard 0/2 "$scene" -o "$dir/x.phot"
expect_failure "-n autom" 2 "count" -n autom "$scene" -o "$dir/x.phot"

tap_done
