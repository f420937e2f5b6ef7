# tap.sh — the TAP helpers every tests/cli/*.t shares. A .t sources it first
# (`. "$(dirname "$0")/tap.sh"`) and ends with `tap_done`. Sourcing sets
#   GB_ROOT              the repository (default .), made absolute
#   GB_BIN               the tools (default $GB_ROOT/build/bin)
#   dir                  a scratch folder, gibake-NAME.XXXXXX for NAME.t,
#                        removed at exit unless GB_KEEP is set
#
#   needs TOOL...        bails out unless each TOOL is built in $GB_BIN
#   ok STATUS WHAT       one check, passed when STATUS is 0
#   missing WHAT         one failed check: a program or package the test needs
#                        is absent (make test installs them all, so in CI this
#                        never hides a result: it fails)
#   ok_run WHAT          one check, passed when the command just before exited
#                        0; else its stderr, $dir/err, as comments (sets status)
#   value KEY FILE       the value of the line "KEY value" of FILE
#   image_diff KEY A B   imgdiff's KEY (max_error, relative_mse...) of image A
#                        against image B
#   below A B            true when the number A is below B (either empty: false)
#   close_to WHAT TO LIMIT IMAGE REF
#                        one check "WHAT: relative MSE below LIMIT" on the
#                        relative MSE of IMAGE against REF (the image of TO),
#                        which goes in a comment and in $error
#   expect_failure WHAT STATUS PATTERN ARGS...
#                        runs $tool ARGS: two checks, exit status STATUS
#                        and PATTERN (grep) on stderr
#   topo_bake FOLDER SCENE VOXELS
#                        voxelize -r VOXELS, thin --grid, segment --voxels
#                        --grid, as make bake: what gbview --method topo
#                        reads, in FOLDER (made) as NAME.*, NAME the
#                        scene file's name; false if a step failed
#   floor_obj FILE       writes a lone 4 x 4 floor at y = 0 (two triangles, no
#                        material: Kd 0.8, the OBJ default) to FILE
#   box_under_sky FOLDER writes FOLDER/box.scene (.obj, .mtl): a 1 x 1 x 1 box
#                        (Kd 0.6 0.3 0.2) on a 4 x 4 ground (Kd 0.5) under
#                        a white sky, no light, a 64 x 64 camera
#   tap_done             prints the plan; returns nonzero if a check failed

GB_ROOT=$(cd "${GB_ROOT:-.}" && pwd) || exit 1
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-$(basename "$0" .t).XXXXXX") || exit 1
[ -n "$GB_KEEP" ] || trap 'rm -rf "$dir"' EXIT
# Interrupted, a test stops (and the EXIT trap cleans up), rather than going on.
trap 'exit 130' INT
trap 'exit 143' TERM

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

needs() {
    for needed in "$@"; do
        if [ ! -x "$GB_BIN/$needed" ]; then
            echo "Bail out! $GB_BIN/$needed not built"
            exit 1
        fi
    done
}

ok_run() {
    status=$?
    [ $status = 0 ] || sed 's/^/# /' "$dir/err"
    ok $status "$1"
}

missing() {
    ok 1 "missing: $1"
}

value() {
    sed -n "s/^$1 //p" "$2"
}

image_diff() {
    "$GB_BIN/imgdiff" "$2" "$3" | value "$1" -
}

below() {
    awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && b != "" && a + 0 < b + 0) }'
}

close_to() {
    error=$(image_diff relative_mse "$4" "$5")
    echo "# $1: relative MSE to $2: $error"
    ok "$(below "$error" "$3"; echo $?)" "$1: relative MSE below $3"
}

expect_failure() {
    what=$1 want=$2 pattern=$3
    shift 3
    "$tool" "$@" >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ $status = "$want" ]; echo $?)" "$what: exit status $want (got $status)"
    ok "$(grep -q "$pattern" "$dir/err"; echo $?)" "$what: says '$pattern' on stderr"
}

topo_bake() {
    topo_name=$(basename "$2")
    topo_name=$1/${topo_name%.*}
    mkdir -p "$1" &&
        "$GB_BIN/voxelize" -q -r "$3" "$2" -o "$topo_name.vdb" &&
        "$GB_BIN/thin" -q "$topo_name.vdb" -o "$topo_name.skel" --grid "$topo_name.grid.vdb" &&
        "$GB_BIN/segment" -q "$topo_name.skel" --voxels "$topo_name.vdb" \
            --grid "$topo_name.grid.vdb" -o "$topo_name.seg"
}

box_under_sky() {
    cat >"$1/box.obj" <<'EOF'
mtllib box.mtl
v -2 0 -2
v 2 0 -2
v 2 0 2
v -2 0 2
v -0.5 0 -0.5
v 0.5 0 -0.5
v 0.5 0 0.5
v -0.5 0 0.5
v -0.5 1 -0.5
v 0.5 1 -0.5
v 0.5 1 0.5
v -0.5 1 0.5
usemtl ground
f 1 4 3 2
usemtl box
f 9 12 11 10
f 9 10 6 5
f 10 11 7 6
f 11 12 8 7
f 12 9 5 8
EOF
    cat >"$1/box.mtl" <<'EOF'
newmtl ground
Kd 0.5 0.5 0.5
newmtl box
Kd 0.6 0.3 0.2
EOF
    cat >"$1/box.scene" <<'EOF'
gibake-scene 1
mesh box.obj
environment 1 1 1
camera position 2.5 2.5 3.5 target 0 0.3 0 up 0 1 0 fov 45 resolution 64 64
EOF
}
floor_obj() {
    cat >"$1" <<'EOF'
v -2 0 -2
v 2 0 -2
v 2 0 2
v -2 0 2
f 1 3 2
f 1 4 3
EOF
}

tap_done() {
    echo "1..$count"
    [ $failed = 0 ]
}
