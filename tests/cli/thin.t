#!/bin/sh
# thin.t — thin as a user types it: the Cornell box voxelized at a low
# resolution, thinned into a skeleton and a nearest-node grid; the same bytes
# on a second run; options, errors, and no output left by a failed run.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/thin

# status_of COMMAND...: its exit status, output in $dir/out and $dir/err.
status_of() {
    "$@" >"$dir/out" 2>"$dir/err"
    echo $?
}

needs thin voxelize

scene=$GB_ROOT/scenes/cornell/cornell.scene
"$GB_BIN/voxelize" -q -r 40 "$scene" -o "$dir/box.vdb" 2>"$dir/err"
ok $? "voxelize the Cornell box at 40"

# ---- a run ----
ok "$(status_of "$tool" -q --stats "$dir/box.vdb" -o "$dir/box.skel" --grid "$dir/box.grid.vdb")" \
    "thin writes a skeleton and a grid"
ok "$([ -s "$dir/box.skel" ] && [ -s "$dir/box.grid.vdb" ]; echo $?)" "both files are there"
nodes=$(sed -n 's/^nodes  *//p' "$dir/out")
ok "$([ "${nodes:-0}" -gt 0 ]; echo $?)" "--stats reports nodes ($nodes)"
ok "$(grep -q '^squares left    0$' "$dir/out"; echo $?)" "the skeleton is thin (no square left)"
ok "$([ ! -s "$dir/err" ]; echo $?)" "--quiet: nothing on stderr"

"$tool" -q "$dir/box.vdb" -o "$dir/again.skel" --grid "$dir/again.grid.vdb"
ok "$(cmp -s "$dir/box.skel" "$dir/again.skel"; echo $?)" "a second run gives the same skeleton bytes"
ok "$(cmp -s "$dir/box.grid.vdb" "$dir/again.grid.vdb"; echo $?)" "and the same grid bytes"

ok "$(status_of "$tool" -q "$dir/box.vdb" -o "$dir/only.skel")" "the grid is optional"
ok "$([ -s "$dir/only.skel" ] && [ ! -e "$dir/only.grid.vdb" ]; echo $?)" "only the skeleton is written"

ok "$(status_of "$tool" -q -p 3 -l 2 "$dir/box.vdb" -o "$dir/p.skel")" "--persistence and --min-lifespan"
ok "$(cmp -s "$dir/box.skel" "$dir/p.skel" && echo 1 || echo 0)" "other parameters, other skeleton"

# ---- help and version ----
ok "$(status_of "$tool" --help)" "--help exits 0"
ok "$(grep -q '^usage: thin' "$dir/out"; echo $?)" "--help prints the usage on stdout"
ok "$(status_of "$tool" --version)" "--version exits 0"

# ---- errors ----
ok "$([ "$(status_of "$tool" "$dir/missing.vdb" -o "$dir/m.skel")" = 1 ]; echo $?)" \
    "a missing input exits 1"
ok "$(grep -q "^thin: .*missing.vdb" "$dir/err"; echo $?)" "the message names the file"
ok "$([ ! -e "$dir/m.skel" ]; echo $?)" "no output after a failure"

printf 'not a vdb\n' >"$dir/bad.vdb"
ok "$([ "$(status_of "$tool" "$dir/bad.vdb" -o "$dir/b.skel" --grid "$dir/b.grid.vdb")" = 1 ]; echo $?)" \
    "a corrupt input exits 1"
ok "$([ ! -e "$dir/b.skel" ] && [ ! -e "$dir/b.grid.vdb" ]; echo $?)" "and leaves nothing"

ok "$([ "$(status_of "$tool" "$dir/box.vdb")" = 2 ]; echo $?)" "no -o is a usage error (2)"
ok "$([ "$(status_of "$tool" -p -1 "$dir/box.vdb" -o "$dir/x.skel")" = 2 ]; echo $?)" \
    "a negative persistence is refused"
ok "$(grep -q '^thin: --persistence' "$dir/err"; echo $?)" "with a message naming the option"
ok "$([ "$(status_of "$tool" -q "$dir/box.vdb" -o "$dir/no/such/dir.skel")" = 1 ]; echo $?)" \
    "an unwritable output exits 1"

tap_done
