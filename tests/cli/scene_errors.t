#!/bin/sh
# scene_errors.t — every bad scene input makes scene-info fail as a Unix tool
# should: exit status 1, one message "scene-info: FILE:LINE: what" on stderr
# (LINE where the input has lines), nothing on stdout. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/scene-info

# expect_error WHAT FILE MESSAGE: scene-info FILE exits 1, prints exactly
# "scene-info: MESSAGE" on stderr and nothing on stdout.
expect_error() {
    "$tool" "$2" >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ $status = 1 ]; echo $?)" "$1: exit status 1 (got $status)"
    expected="scene-info: $3"
    got=$(cat "$dir/err")
    [ "$got" = "$expected" ]
    result=$?
    ok $result "$1: message '$expected'"
    [ $result = 0 ] || echo "#   got '$got'"
    ok "$([ ! -s "$dir/out" ]; echo $?)" "$1: nothing on stdout"
}

# A triangle; the caller adds or changes lines.
triangle='v 0 0 0
v 1 0 0
v 0 1 0'

needs scene-info

printf '%s\nv 0 nan 0\nf 1 2 3\n' "$triangle" >"$dir/nan.obj"
expect_error "NaN coordinate" "$dir/nan.obj" "$dir/nan.obj:4: vertex y 'nan' is not finite"

printf '%s\nf 1 2 3\nv -inf 0 0\n' "$triangle" >"$dir/inf.obj"
expect_error "Inf coordinate" "$dir/inf.obj" "$dir/inf.obj:5: vertex x '-inf' is not finite"

printf '%s\nf 1 2 9\n' "$triangle" >"$dir/index.obj"
expect_error "index out of range" "$dir/index.obj" \
    "$dir/index.obj:4: vertex index 9 out of range (3 vertices)"

printf '%s\nf 1 2 3\nf 1 2 -4\n' "$triangle" >"$dir/negative.obj"
expect_error "negative index out of range" "$dir/negative.obj" \
    "$dir/negative.obj:5: vertex index -4 out of range (3 vertices)"

printf '# no MTL beside me\nmtllib gone.mtl\n%s\nf 1 2 3\n' "$triangle" >"$dir/nomtl.obj"
expect_error "missing MTL" "$dir/nomtl.obj" \
    "$dir/nomtl.obj:2: mtllib $dir/gone.mtl: No such file or directory"

printf 'newmtl wood\nKd 0.5 0.4 0.3\nmap_Kd textures/wood.png\n' >"$dir/notex.mtl"
printf 'mtllib notex.mtl\n%s\nusemtl wood\nf 1 2 3\n' "$triangle" >"$dir/notex.obj"
expect_error "missing texture" "$dir/notex.obj" \
    "$dir/notex.mtl:3: texture $dir/textures/wood.png: No such file or directory"

printf '# only comments\no nothing\n' >"$dir/empty.obj"
expect_error "empty mesh" "$dir/empty.obj" "$dir/empty.obj: no triangles (empty mesh)"

printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n' >"$dir/flat.obj"
expect_error "only degenerate triangles" "$dir/flat.obj" \
    "$dir/flat.obj: no triangles (empty mesh, all degenerate)"

printf '%s\nf 1 2 3\n' "$triangle" >"$dir/good.obj"
printf 'gibake-scene 1\nmesh good.obj\nlight point position 0 1 intensity 1 1 1\n' \
    >"$dir/number.scene"
expect_error "missing number in a .scene line" "$dir/number.scene" \
    "$dir/number.scene:3: position value 3 'intensity' is not a number"

printf 'gibake-scene 1\r\nmesh good.obj\r\nlamp 0 1 2\r\n' >"$dir/keyword.scene"
expect_error "unknown keyword in a .scene line" "$dir/keyword.scene" \
    "$dir/keyword.scene:3: unknown keyword 'lamp'"

printf 'gibake-scene 1\nmesh good.obj\nenvironment 0 NaN 0\n' >"$dir/nan.scene"
expect_error "NaN in a .scene line" "$dir/nan.scene" \
    "$dir/nan.scene:3: environment y 'NaN' is not finite"

printf 'gibake-scene 1\n# the mesh is elsewhere\nmesh missing.obj\n' >"$dir/nomesh.scene"
expect_error "missing mesh file" "$dir/nomesh.scene" \
    "$dir/nomesh.scene:3: mesh $dir/missing.obj: No such file or directory"

expect_error "missing scene file" "$dir/absent.scene" \
    "$dir/absent.scene: No such file or directory"

{
    printf 'ply\nformat ascii 1.0\nelement vertex 3\n'
    printf 'property float x\nproperty float y\nproperty float z\n'
    printf 'element face 1\nproperty list uchar int vertex_indices\nend_header\n'
    printf '0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n'
} >"$dir/index.ply"
expect_error "PLY index out of range" "$dir/index.ply" \
    "$dir/index.ply:13: face 0: vertex index 7 out of range (3 vertices)"

# A good scene still works and warns about what it dropped.
printf '%s\nf 1 2 3\nf 1 1 2\n' "$triangle" >"$dir/dropped.obj"
"$tool" "$dir/dropped.obj" >"$dir/out" 2>"$dir/err"
ok $? "a scene with a degenerate triangle loads"
ok "$(grep -q '^triangles  *1$' "$dir/out"; echo $?)" "summary counts 1 triangle"
grep -qxF "scene-info: $dir/dropped.obj: warning: 1 degenerate triangle dropped" "$dir/err"
ok $? "warning on stderr: 1 degenerate triangle dropped"
"$tool" --quiet "$dir/dropped.obj" >"$dir/out" 2>"$dir/err"
ok "$([ ! -s "$dir/err" ]; echo $?)" "--quiet silences the warning"

tap_done
