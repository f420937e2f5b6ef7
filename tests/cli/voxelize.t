#!/bin/sh
# voxelize.t — voxelize as a user types it: a box room written here as an
# OBJ, the OpenVDB file it gives (read back with vdb_print when installed),
# options, errors, atomic output, byte-identical output on 1 and 2 threads;
# -r auto on the two rooms keeps the door open (thin's skeleton: the outside
# and the joined rooms, where -r 8 closes the door and parts them).
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/voxelize

# active NAME FILE: the number of active voxels vdb_print reports for grid NAME
active() {
    vdb_print -l "$2" 2>/dev/null | awk -v name="$1" '
        /^Name:/ { grid = $2 }
        grid == name && /Number of active voxels/ { gsub(",", "", $NF); print $NF; exit }'
}

needs voxelize

# A closed box room 0..16 x 0..16 x 0..16 (6 quads): at resolution 16 its
# walls lie on voxel faces and each marks the two layers around it.
cat >"$dir/room.obj" <<'EOF'
v 0 0 0
v 16 0 0
v 16 16 0
v 0 16 0
v 0 0 16
v 16 0 16
v 16 16 16
v 0 16 16
f 1 2 3 4
f 5 8 7 6
f 1 5 6 2
f 2 6 7 3
f 3 7 8 4
f 4 8 5 1
EOF

"$tool" --help >"$dir/out" 2>"$dir/err"
ok "$([ $? = 0 ] && grep -q '^usage: voxelize' "$dir/out" && [ ! -s "$dir/err" ]; echo $?)" \
    "--help: usage on stdout, exit 0"
ok "$([ "$("$tool" --version)" = "voxelize (gibake) 0.1" ]; echo $?)" "--version"

"$tool" -r 16 "$dir/room.obj" -o "$dir/room.vdb" >"$dir/out" 2>"$dir/err"
ok $? "voxelize -r 16 room.obj -o room.vdb: exit 0"
ok "$([ -s "$dir/room.vdb" ] && [ ! -s "$dir/out" ] && [ ! -s "$dir/err" ]; echo $?)" \
    "the file is written, nothing printed (stderr is not a terminal)"
ok "$([ "$(ls "$dir" | grep -c tmp)" = 0 ]; echo $?)" "no temporary file left"
ok "$([ "$(head -c 4 "$dir/room.vdb" | od -An -tx1 | tr -d ' \n')" = 20424456 ]; echo $?)" \
    "it starts with the OpenVDB magic"

if command -v vdb_print >/dev/null 2>&1; then
    vdb_print -l -m "$dir/room.vdb" >"$dir/print" 2>&1
    ok $? "vdb_print reads it"
    ok "$(grep -q 'creator: gibake-voxelize 0.1' "$dir/print" &&
        grep -q 'resolution: 16' "$dir/print" && grep -q 'voxel_size: 1$' "$dir/print" &&
        grep -q 'grid_size: \[20, 20, 20\]' "$dir/print" &&
        grep -q 'world_origin: \[-2, -2, -2\]' "$dir/print" &&
        grep -Eq 'scene_hash: [0-9a-f]{16}$' "$dir/print"; echo $?)" \
        "metadata: creator, resolution, voxel size, grid size, origin, scene hash"
    # The shell [1,18]^3 minus [3,16]^3: 18^3 - 14^3 = 3088 surface voxels.
    ok "$([ "$(active surface "$dir/room.vdb")" = 3088 ]; echo $?)" \
        "surface: 3088 voxels, two layers per wall (got $(active surface "$dir/room.vdb"))"
    ok "$([ "$(active empty "$dir/room.vdb")" = $((8000 - 3088)) ]; echo $?)" \
        "empty: the other 4912 voxels"
    ok "$([ "$(grep -c '^Name: ' "$dir/print")" = 2 ] && ! grep -q 'Name: distance' "$dir/print"; echo $?)" \
        "two grids, surface and empty: no distance is stored"
    ok "$(grep -q 'gibake_format: 3$' "$dir/print"; echo $?)" "gibake_format 3"
else
    for i in 1 2 3 4 5 6; do missing "vdb_print not installed (package libopenvdb-tools)"; done
fi

"$tool" -q -r 16 -j 1 "$dir/room.obj" -o "$dir/one.vdb" &&
    "$tool" -q -r 16 -j 2 "$dir/room.obj" -o "$dir/two.vdb"
ok "$(cmp -s "$dir/one.vdb" "$dir/two.vdb" && cmp -s "$dir/one.vdb" "$dir/room.vdb"; echo $?)" \
    "byte-identical files on 1 and 2 threads and across runs"

"$tool" -r 8 --pad 0 "$dir/room.obj" -o "$dir/bare.vdb"
ok $? "--pad 0 is accepted"
if command -v vdb_print >/dev/null 2>&1; then
    ok "$(vdb_print -l -m "$dir/bare.vdb" | grep -q 'grid_size: \[8, 8, 8\]'; echo $?)" \
        "--pad 0 -r 8: an 8^3 grid"
fi

# Errors: nothing written, the older file kept.
cp "$dir/room.vdb" "$dir/kept.vdb"
"$tool" "$dir/missing.obj" -o "$dir/kept.vdb" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ] && grep -q "^voxelize: .*missing.obj" "$dir/err"; echo $?)" \
    "missing scene: exit 1, 'voxelize: FILE: ...' (got $status: $(head -1 "$dir/err"))"
ok "$(cmp -s "$dir/room.vdb" "$dir/kept.vdb"; echo $?)" "... and the older output is kept"

"$tool" "$dir/room.obj" -o "$dir/no/such/folder/x.vdb" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ] && grep -q "^voxelize: .*x.vdb" "$dir/err" &&
    [ ! -e "$dir/no" ]; echo $?)" "output in a missing folder: exit 1, message names it"

printf 'this is not a mesh\n' >"$dir/bad.obj"
"$tool" "$dir/bad.obj" -o "$dir/bad.vdb" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ] && grep -q "^voxelize: .*bad.obj" "$dir/err" && [ ! -e "$dir/bad.vdb" ]; echo $?)" \
    "a file with no triangles: exit 1, no output (got $status: $(head -1 "$dir/err"))"

for arguments in "-r 0" "-r 2049" "-r 12x" "--pad 65" "--pad -1" "-j 0"; do
    # shellcheck disable=SC2086
    "$tool" $arguments "$dir/room.obj" -o "$dir/arg.vdb" 2>"$dir/err"
    status=$?
    ok "$([ $status = 2 ] && grep -q "^voxelize: " "$dir/err" && [ ! -e "$dir/arg.vdb" ]; echo $?)" \
        "bad option '$arguments': exit 2 with a message, no output"
done
"$tool" "$dir/room.obj" 2>"$dir/err"
ok "$([ $? = 2 ] && grep -q "no output file" "$dir/err"; echo $?)" "no -o: exit 2"
"$tool" -o "$dir/x.vdb" 2>"$dir/err"
ok "$([ $? = 2 ] && grep -q "expected one SCENE" "$dir/err"; echo $?)" "no SCENE: exit 2"

# -r auto (tools/voxelize/auto_resolution.h) on the two rooms, 4 m long with
# a door 0.6 m wide: the skeleton's graph is a forest here, so nodes - edges
# counts its parts: 2 with the door open (the outside, the two rooms
# joined), 3 with it closed (-r 8: 0.5 m voxels, both door jambs marked).
rooms=$GB_ROOT/scenes/two-rooms/two-rooms.scene
if [ -x "$GB_BIN/thin" ]; then
    parts() {
        "$GB_BIN/thin" -q -s "$1" -o "$1.skel" | awk '$1 == "nodes" { n = $2 } $1 == "edges" { e = $2 } END { print n - e }'
    }
    "$tool" -r auto "$rooms" -o "$dir/auto.vdb" 2>"$dir/auto.err"
    ok "$([ $? = 0 ] && [ -s "$dir/auto.vdb" ]; echo $?)" "-r auto: exit 0, an output"
    chosen=$(sed -n 's/^voxelize: -r auto: \([0-9]*\) (the same at three resolutions.*/\1/p' "$dir/auto.err")
    echo "# -r auto chose ${chosen:-nothing}: $(cat "$dir/auto.err")"
    ok "$([ -n "$chosen" ] && [ "$chosen" -ge 16 ] && [ "$chosen" -le 512 ]; echo $?)" \
        "-r auto: says the resolution it chose, settled, in 16..512"
    "$tool" -q -r "${chosen:-1}" "$rooms" -o "$dir/chosen.vdb"
    ok "$(cmp -s "$dir/auto.vdb" "$dir/chosen.vdb"; echo $?)" "-r auto: the bytes of -r $chosen"
    "$tool" -q -j 1 -r auto "$rooms" -o "$dir/auto1.vdb"
    ok "$(cmp -s "$dir/auto.vdb" "$dir/auto1.vdb"; echo $?)" "-r auto: the same bytes on 1 thread"
    "$tool" -q -r 8 "$rooms" -o "$dir/coarse.vdb"
    open=$(parts "$dir/auto.vdb")
    closed=$(parts "$dir/coarse.vdb")
    echo "# skeleton parts (nodes - edges): -r auto $open, -r 8 $closed"
    ok "$([ "$open" = 2 ]; echo $?)" "-r auto: the door open (2 parts: outside, the rooms joined)"
    ok "$([ "$closed" = 3 ]; echo $?)" "-r 8: the door closed (3 parts)"
    "$tool" -q -r auto "$rooms" -o "$dir/quiet.vdb" 2>"$dir/quiet.err"
    ok "$([ ! -s "$dir/quiet.err" ]; echo $?)" "-r auto -q: nothing on stderr"
else
    missing "$GB_BIN/thin not built"
fi
"$tool" -r automatic "$rooms" -o "$dir/x.vdb" 2>"$dir/err"
ok "$([ $? = 2 ] && grep -q "resolution" "$dir/err"; echo $?)" "-r automatic: exit 2, names --resolution"

tap_done
