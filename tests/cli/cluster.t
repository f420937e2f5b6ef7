#!/bin/sh
# cluster.t — the light octree tool as a user types it, on the Cornell box
# with a few thousand photons: a valid octree written, the same bytes
# whatever the threads, errors reported as a Unix tool should and nothing
# left behind. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/cluster
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs cluster photons

"$GB_BIN/photons" --count 5000 --quiet "$scene" -o "$dir/in.phot" 2>"$dir/err"
ok $? "photons for the Cornell box"

small="--depth 4 --knn 50 --quiet"
"$tool" $small --threads 1 "$scene" "$dir/in.phot" -o "$dir/one.lot" >"$dir/out" 2>"$dir/err"
ok $? "cluster: exit status 0"
[ -s "$dir/one.lot" ] && [ ! -s "$dir/err" ]
ok $? "... writes the octree, nothing on stderr"
head -c 16 "$dir/one.lot" | tr -d '\000' | grep -a -q LOCT
ok $? "... a gibake container of kind LOCT"

"$tool" $small --threads 2 "$scene" "$dir/in.phot" -o "$dir/two.lot" 2>"$dir/err"
cmp -s "$dir/one.lot" "$dir/two.lot"
ok $? "the same bytes with 1 and 2 threads"

"$tool" $small --stats "$scene" "$dir/in.phot" -o "$dir/stats.lot" >"$dir/stats" 2>"$dir/err"
grep -q '^leaves [1-9]' "$dir/stats" && grep -q '^vdls [1-9]' "$dir/stats"
ok $? "--stats prints leaves and VDLs"

# the best of 4 k-means runs per leaf: its first run is the single run, so
# no leaf spreads more
spread_of() {
    sed -n 's/^mean_spread_degrees //p' "$1"
}
"$tool" $small --stats --vdls 4 --tolerance 0 "$scene" "$dir/in.phot" -o "$dir/r1.lot" \
    >"$dir/r1" 2>"$dir/err" &&
    "$tool" $small --stats --vdls 4 --tolerance 0 --restarts 4 "$scene" "$dir/in.phot" \
        -o "$dir/r4.lot" >"$dir/r4" 2>"$dir/err" &&
    awk -v one="$(spread_of "$dir/r1")" -v four="$(spread_of "$dir/r4")" \
        'BEGIN { exit !(one > 0 && four > 0 && four <= one) }'
ok $? "--restarts 4: mean spread $(spread_of "$dir/r4") <= $(spread_of "$dir/r1") of one run"
"$tool" $small --restarts 0 "$scene" "$dir/in.phot" -o "$dir/bad.lot" 2>"$dir/err"
[ $? = 2 ] && [ ! -e "$dir/bad.lot" ]
ok $? "--restarts 0: exit 2, nothing written"

"$tool" --help >"$dir/help"
[ $? = 0 ] && grep -q -- "--tolerance" "$dir/help" && grep -q -- '--restarts' "$dir/help"
ok $? "--help: exit 0, lists the options"
"$tool" --version >/dev/null
ok $? "--version: exit 0"

"$tool" $small "$scene" "$dir/in.phot" 2>"$dir/err"
[ $? = 2 ] && grep -q '^cluster: ' "$dir/err"
ok $? "no -o: exit 2 with a message"
"$tool" $small --depth 11 "$scene" "$dir/in.phot" -o "$dir/bad.lot" 2>"$dir/err"
[ $? = 2 ] && [ ! -e "$dir/bad.lot" ]
ok $? "--depth 11: exit 2, nothing written"

"$tool" $small "$scene" "$dir/missing.phot" -o "$dir/bad.lot" 2>"$dir/err"
[ $? = 1 ] && grep -q 'missing.phot' "$dir/err" && [ ! -e "$dir/bad.lot" ]
ok $? "a missing photon map: exit 1, names the file, nothing written"

head -c 200 "$dir/in.phot" >"$dir/cut.phot"
"$tool" $small "$scene" "$dir/cut.phot" -o "$dir/bad.lot" 2>"$dir/err"
[ $? = 1 ] && grep -q 'cut.phot' "$dir/err" && [ ! -e "$dir/bad.lot" ]
ok $? "a truncated photon map: exit 1, nothing written"

# the same box with another environment: another scene hash
sed 's/^environment 0 0 0/environment 0.5 0.5 0.5/; s|^mesh |mesh '"$GB_ROOT"'/scenes/cornell/|' \
    "$scene" >"$dir/other.scene"
"$tool" $small "$dir/other.scene" "$dir/in.phot" -o "$dir/bad.lot" 2>"$dir/err"
status=$?
[ $status = 1 ] && grep -q 'another scene' "$dir/err" && [ ! -e "$dir/bad.lot" ]
ok $? "photons of another scene: exit 1, stale, nothing written"

# --shard I/N and --merge: three parts of the leaves joined into the bytes of
# the whole run; a part left out, or the parts out of order, refused.
parts=
for i in 0 1 2; do
    "$tool" $small --shard $i/3 "$scene" "$dir/in.phot" -o "$dir/part$i.lot" 2>"$dir/err"
    parts="$parts $dir/part$i.lot"
done
"$tool" --merge $parts -o "$dir/merged.lot" 2>"$dir/err"
ok "$([ $? = 0 ] && cmp -s "$dir/one.lot" "$dir/merged.lot"; echo $?)" \
    "--merge of --shard 0/3, 1/3, 2/3: the bytes of the whole run"
ok "$(cmp -s "$dir/one.lot" "$dir/part1.lot"; [ $? = 1 ]; echo $?)" "and a part alone is not it"
# eight parts of a deeper octree: each indexes only the photons its leaves
# can reach (its halo), fewer than the map's, and they still join into the
# whole run's bytes
"$tool" --depth 5 --knn 400 --quiet --stats "$scene" "$dir/in.phot" -o "$dir/deep.lot" \
    >"$dir/deep.stats" 2>"$dir/err"
whole=$(sed -n 's/^indexed_photons //p' "$dir/deep.stats")
parts=
fewer=0
for i in 0 1 2 3 4 5 6 7; do
    "$tool" --depth 5 --knn 400 --quiet --stats --shard $i/8 "$scene" "$dir/in.phot" \
        -o "$dir/deep$i.lot" >"$dir/deep$i.stats" 2>"$dir/err"
    indexed=$(sed -n 's/^indexed_photons //p' "$dir/deep$i.stats")
    [ "${indexed:-0}" -gt 0 ] && [ "$indexed" -lt "${whole:-0}" ] && fewer=$((fewer + 1))
    parts="$parts $dir/deep$i.lot"
done
"$tool" --merge $parts -o "$dir/deep-merged.lot" 2>"$dir/err"
ok "$([ $? = 0 ] && cmp -s "$dir/deep.lot" "$dir/deep-merged.lot"; echo $?)" \
    "--merge of 8 parts of a depth-5 octree: the bytes of the whole run"
ok "$([ $fewer = 8 ]; echo $?)" "each of the 8 parts indexes fewer than the $whole photons"
expect_failure "--merge of two of the three parts" 1 "not part 0 of 2\|not part 1 of 2" \
    --merge "$dir/part0.lot" "$dir/part1.lot" -o "$dir/x.lot"
expect_failure "--merge of the parts out of order" 1 "part1.lot: .*not part 0 of 3" \
    --merge "$dir/part1.lot" "$dir/part0.lot" "$dir/part2.lot" -o "$dir/x.lot"
"$tool" --depth 4 --shard 0/2 "$scene" "$dir/in.phot" -o "$dir/other.lot" 2>"$dir/err"
expect_failure "--merge of parts of two octrees" 1 "not a part of the octree" \
    --merge "$dir/part0.lot" "$dir/other.lot" -o "$dir/x.lot"
old="$GB_ROOT/tests/fuzz/corpus/fuzz_light_octree/cornell-depth2-v2.lot"
expect_failure "a version-2 octree (32-byte leaves) is refused, naming its version" 1 \
    "format version 2, from an older cluster" --merge "$old" "$old" -o "$dir/x.lot"

tap_done
