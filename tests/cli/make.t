#!/bin/sh
# make.t — make bake reruns exactly the steps whose inputs changed
# (bake.mk): on a copy of the Cornell box with a texture, `make -f bake.mk`
# is run again after each edit and the tools it ran are read from its
# output; the baked files it did not rerun keep their bytes and times.
# Also: tools' --depfile rules, a mesh as SCENE, a second scene of the same
# name refused, and two scenes baked with -j4 byte-identical to -j1.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
needs scene-info voxelize thin segment photons cluster atlas lightmap reference gbview

# The environment of the make running this suite (its jobserver) is not ours.
unset MAKEFLAGS MFLAGS MAKELEVEL
flags_v="-r 16" flags_p="-n 3000" flags_c="--depth 3" flags_a="--size 128"

# bake [VAR=VALUE...]: make bake of $dir/scene/box.scene into $dir/bake;
# $ran is the tools it ran, in order ("voxelize thin ..."), $dir/make.out its output.
bake() {
    make --no-print-directory -f "$GB_ROOT/bake.mk" BIN="$GB_BIN" BAKE="$dir/bake" \
        SCENE="$dir/scene/box.scene" VOXELIZE_FLAGS="$flags_v" PHOTONS_FLAGS="$flags_p" \
        CLUSTER_FLAGS="$flags_c" ATLAS_FLAGS="$flags_a" "$@" bake >"$dir/make.out" 2>&1
    status=$?
    ran=$(grep -o "^$GB_BIN/[a-z-]* " "$dir/make.out" | sed "s|^$GB_BIN/||" | tr -d ' ' |
          grep -v '^scene-info$' | tr '\n' ' ' | sed 's/ $//')
    return $status
}

# expect WHAT TOOLS...: the last bake succeeded and ran exactly TOOLS.
expect() {
    what=$1
    shift
    ok "$([ "$status" = 0 ] && [ "$ran" = "$*" ]; echo $?)" \
        "$what: reruns ${*:-nothing} (ran: ${ran:-nothing})"
}

# The scene: the project's box, its first material given a texture made here.
mkdir "$dir/scene"
cp "$GB_ROOT/scenes/cornell/cornell.obj" "$dir/scene/box.obj"
cp "$GB_ROOT/scenes/cornell/cornell.mtl" "$dir/scene/box.mtl"
sed -i 's/cornell\.mtl/box.mtl/' "$dir/scene/box.obj"
sed 's/cornell\.obj/box.obj/' "$GB_ROOT/scenes/cornell/cornell.scene" >"$dir/scene/box.scene"
"$GB_BIN/reference" -q --mode direct --spp 1 -r 8x8 "$dir/scene/box.scene" \
    -o "$dir/scene/wall.png"
first=$(sed -n 's/^newmtl //p' "$dir/scene/box.mtl" | head -1)
sed -i "0,/^newmtl $first\$/s//newmtl $first\nmap_Kd wall.png/" "$dir/scene/box.mtl"
ok "$(grep -q '^map_Kd wall.png' "$dir/scene/box.mtl"; echo $?)" "the box's $first has a texture"

bake; expect "the first bake" voxelize thin segment photons cluster atlas lightmap
mode=$(printf '%o' $((0666 & ~$(umask))))
modes=$(stat -c '%a %n' "$dir"/bake/* | grep -v "^$mode " | sed "s|$dir/bake/||")
ok "$([ -z "$modes" ]; echo $?)" \
    "every file of the bake, stamps too, is mode $mode (0666 less the umask)${modes:+; not: $modes}"
for f in vdb skel grid.vdb seg lot atlas lightmap.exr glb; do cp "$dir/bake/box.$f" "$dir/box.$f.first"; done
"$GB_BIN/gbview" --headless -q --method topo -r 8x8 --bake "$dir/bake" "$dir/scene/box.scene" \
    -o "$dir/topo.png" 2>"$dir/err"
ok "$([ $? = 0 ] && [ ! -s "$dir/err" ]; echo $?)" "gbview takes every baked file"

bake; expect "nothing changed"
touch -d '+1 second' "$dir/scene/box.obj" "$dir/scene/box.mtl"
bake; expect "the mesh and .mtl touched, not changed"
sed -i 's/^camera position \([-0-9.]*\)/camera position 1\1/' "$dir/scene/box.scene"
bake; expect "a camera edited (in no hash)"
touch -d '+2 seconds' "$dir/scene/box.scene"
bake; expect "the .scene touched"
same=0
for f in vdb skel grid.vdb seg lot atlas lightmap.exr glb; do
    cmp -s "$dir/bake/box.$f" "$dir/box.$f.first" || same=1
done
ok $same "the baked files kept their bytes"

"$GB_BIN/reference" -q --mode direct --spp 2 -r 8x8 "$dir/scene/box.scene" \
    -o "$dir/scene/wall.png"
touch -d '+3 seconds' "$dir/scene/wall.png"
bake; expect "the texture changed" photons cluster lightmap
awk '/^Kd / && !done { $2 = $2 * 0.5; done = 1 } { print }' "$dir/scene/box.mtl" \
    >"$dir/box.mtl" && mv "$dir/box.mtl" "$dir/scene/box.mtl"
touch -d '+4 seconds' "$dir/scene/box.mtl"
bake; expect "a colour in the .mtl changed" voxelize thin segment photons cluster atlas lightmap
echo "light point position 278 400 278 intensity 9000 9000 9000" >>"$dir/scene/box.scene"
touch -d '+5 seconds' "$dir/scene/box.scene"
bake; expect "a light added to the .scene" voxelize thin segment photons cluster atlas lightmap
printf 'v 0 0 0\n' >>"$dir/scene/box.obj"
touch -d '+6 seconds' "$dir/scene/box.obj"
bake; expect "a vertex added to the mesh" voxelize thin segment photons cluster atlas lightmap
"$GB_BIN/gbview" --headless -q --method topo -r 8x8 --bake "$dir/bake" "$dir/scene/box.scene" \
    -o "$dir/topo.png" 2>"$dir/err"
ok "$([ $? = 0 ] && [ ! -s "$dir/err" ]; echo $?)" "gbview takes every baked file again"

flags_v="-r 20"
bake; expect "VOXELIZE_FLAGS changed" voxelize thin segment
flags_c="--depth 4"
bake; expect "CLUSTER_FLAGS changed" cluster lightmap
flags_a="--size 64"
bake; expect "ATLAS_FLAGS changed" atlas lightmap
bake THIN_FLAGS=--quiet; expect "THIN_FLAGS changed" thin segment
bake THIN_FLAGS=--quiet; expect "and kept"

# --depfile: each tool's rule names its output and every file it read.
"$GB_BIN/photons" -q -n 1000 --depfile "$dir/p.d" "$dir/scene/box.scene" -o "$dir/p.phot" \
    >/dev/null
for f in box.scene box.obj box.mtl wall.png; do
    ok "$(grep -q "^ $dir/scene/$f" "$dir/p.d" && grep -q "^$dir/scene/$f:\$" "$dir/p.d"
          echo $?)" "photons --depfile lists $f, with an empty rule of its own"
done
ok "$(head -1 "$dir/p.d" | grep -q "^$dir/p.phot: "; echo $?)" "photons --depfile: the target"
"$GB_BIN/voxelize" -q -r 8 --depfile "$dir/v.d" "$dir/scene/box.scene" -o "$dir/v.vdb"
ok "$(grep -q wall.png "$dir/v.d"; [ $? = 1 ] && grep -q box.mtl "$dir/v.d"; echo $?)" \
    "voxelize --depfile lists the .mtl, not the texture it does not read"
"$GB_BIN/cluster" -q --depth 3 --depfile "$dir/c.d" "$dir/scene/box.scene" "$dir/p.phot" \
    -o "$dir/c.lot" >/dev/null
ok "$(grep -q "^ $dir/p.phot" "$dir/c.d"; echo $?)" "cluster --depfile lists the photon map"
mkdir "$dir/odd folder"
cp "$dir/scene/box.scene" "$dir/scene/box.obj" "$dir/scene/box.mtl" "$dir/scene/wall.png" \
    "$dir/odd folder/"
"$GB_BIN/reference" -q --spp 1 -r 8x8 --depfile "$dir/r.d" "$dir/odd folder/box.scene" \
    -o "$dir/r.exr"
ok "$(grep -qF "odd\\ folder/box.obj" "$dir/r.d"; echo $?)" "a space in a path is escaped"
printf '%s/r.exr:\n\ttouch "$@"\n' "$dir" >"$dir/r.mk"
make --no-print-directory -q -f "$dir/r.mk" -f "$dir/r.d" "$dir/r.exr"
ok $? "make reads the rule: r.exr up to date"
touch -d '+7 seconds' "$dir/odd folder/box.obj"
make --no-print-directory -q -f "$dir/r.mk" -f "$dir/r.d" "$dir/r.exr"
ok "$([ $? = 1 ]; echo $?)" "and out of date once the mesh is newer"

# A mesh as SCENE, beside a .scene of the same name: the mesh is baked.
make --no-print-directory -f "$GB_ROOT/bake.mk" BIN="$GB_BIN" BAKE="$dir/mesh-bake" \
    SCENE="$dir/scene/box.obj" VOXELIZE_FLAGS="-r 16" PHOTONS_FLAGS="-n 3000" \
    CLUSTER_FLAGS="--depth 3" ATLAS_FLAGS="--size 128" bake >"$dir/make.out" 2>&1
ok "$([ $? = 0 ] && grep -q "voxelize -r 16 $dir/scene/box.obj " "$dir/make.out"; echo $?)" \
    "SCENE=box.obj bakes the mesh, not box.scene"

# The same name from another folder, into the same bake folder: refused.
cp "$dir/bake/box.vdb" "$dir/box.vdb.before"
mkdir "$dir/other"
cp "$dir/scene/box.scene" "$dir/scene/box.obj" "$dir/scene/box.mtl" "$dir/scene/wall.png" \
    "$dir/other/"
make --no-print-directory -f "$GB_ROOT/bake.mk" BIN="$GB_BIN" BAKE="$dir/bake" \
    SCENE="$dir/other/box.scene" bake >"$dir/make.out" 2>&1
ok "$([ $? != 0 ] && grep -q "baked from $dir/scene/box.scene.*same name" "$dir/make.out"
      echo $?)" "a second scene named box in one bake folder is refused, naming the first"
ok "$(cmp -s "$dir/bake/box.vdb" "$dir/box.vdb.before" && grep -q "$dir/scene/box.scene" \
      "$dir/bake/box.source"; echo $?)" "and the first bake is left as it was"

# Two scenes at once: -j4 gives the bytes of -j1.
cp "$GB_ROOT/scenes/cornell/cornell.scene" "$GB_ROOT/scenes/cornell/cornell.obj" \
    "$GB_ROOT/scenes/cornell/cornell.mtl" "$dir/other/"
for j in 1 4; do
    make --no-print-directory -j$j -f "$GB_ROOT/bake.mk" BIN="$GB_BIN" BAKE="$dir/j$j" \
        SCENES="$dir/scene/box.scene $dir/other/cornell.scene" VOXELIZE_FLAGS="-r 16" \
        PHOTONS_FLAGS="-n 3000" CLUSTER_FLAGS="--depth 3" ATLAS_FLAGS="--size 128" bake \
        >"$dir/make$j.out" 2>&1
    ok $? "make -j$j bake of two scenes"
done
same=0
for f in box.vdb box.skel box.grid.vdb box.seg box.phot box.lot box.atlas box.lightmap.exr \
         box.glb cornell.vdb cornell.skel cornell.grid.vdb cornell.seg cornell.phot cornell.lot \
         cornell.atlas cornell.lightmap.exr cornell.glb; do
    cmp -s "$dir/j1/$f" "$dir/j4/$f" || { same=1; echo "# $f differs"; }
done
ok $same "every baked file of -j4 is byte-identical to -j1's"
make --no-print-directory -f "$GB_ROOT/bake.mk" BIN="$GB_BIN" BAKE="$dir/j1" \
    SCENES="$dir/scene/box.scene $dir/other/box.scene" bake >"$dir/make.out" 2>&1
ok "$([ $? != 0 ] && grep -q "two scenes named box" "$dir/make.out"; echo $?)" \
    "two scenes of one name in SCENES are refused"

tap_done
