#!/bin/sh
# bake_open.t — gbview reads each baked file once (runtime/bake.h): with a
# full bake of the Cornell box (voxelize -r 16, thin --grid, segment,
# photons and cluster), `gbview --headless --method topo` and
# `--method octree` run under strace: each opens the baked files it uses
# once and the others never. OpenVDB's own reader opens a .vdb twice for
# one read, so a .vdb or .grid.vdb may show two opens.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/gbview
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs voxelize thin segment photons cluster gbview
if ! strace -o /dev/null -qq -e trace=openat true 2>/dev/null; then
    missing "strace, or tracing here"
    tap_done
    exit
fi

bake=$dir/bake
mkdir "$bake"
"$GB_BIN/voxelize" -q -r 16 "$scene" -o "$bake/cornell.vdb" &&
    "$GB_BIN/thin" -q "$bake/cornell.vdb" -o "$bake/cornell.skel" \
        --grid "$bake/cornell.grid.vdb" &&
    "$GB_BIN/segment" -q "$bake/cornell.skel" -o "$bake/cornell.seg" &&
    "$GB_BIN/photons" -n 20000 --quiet "$scene" -o "$dir/cornell.phot" >/dev/null &&
    "$GB_BIN/cluster" --depth 4 --quiet "$scene" "$dir/cornell.phot" \
        -o "$bake/cornell.lot" >/dev/null
ok $? "bake: voxelize -r 16, thin --grid, segment, photons, cluster"

# opens EXT: how many times the trace $dir/trace opened $bake/cornell.EXT
opens() {
    grep -F "\"$bake/cornell.$1\"" "$dir/trace" | grep -c "openat("
}

# each method reads the files it uses, once, and never opens the others:
# topo the voxels, the nearest-node grid and the segmentation; octree the
# light octree alone
for method in topo octree; do
    case $method in
    topo) used="vdb grid.vdb seg" unused="skel lot" ;;
    octree) used="lot" unused="vdb grid.vdb skel seg" ;;
    esac
    # LeakSanitizer cannot run under a tracer: no leak check in this one run
    ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 \
        MESA_SHADER_CACHE_DISABLE=true strace -qq -f -e trace=openat -o "$dir/trace" \
            "$tool" --headless --method "$method" --bake "$bake" --resolution 16x16 \
            "$scene" -o "$dir/$method.png" >"$dir/out" 2>"$dir/err"
    ok $? "--method $method under strace: renders"
    ok "$([ ! -s "$dir/err" ]; echo $?)" "--method $method: nothing on stderr"
    sed 's/^/#   /' "$dir/err"
    for ext in $used; do
        n=$(opens "$ext")
        case $ext in
        *vdb) ok "$([ "$n" -ge 1 ] && [ "$n" -le 2 ]; echo $?)" \
            "--method $method: cornell.$ext read once ($n opens, OpenVDB's two for one read)" ;;
        *) ok "$([ "$n" = 1 ]; echo $?)" "--method $method: cornell.$ext opened once ($n)" ;;
        esac
    done
    for ext in $unused; do
        n=$(opens "$ext")
        ok "$([ "$n" = 0 ]; echo $?)" "--method $method: cornell.$ext never opened ($n)"
    done
done

# the same name, another scene (another environment): the files are stale,
# and the method that reads one says so by path
mkdir "$dir/other"
sed 's/^environment 0 0 0/environment 0.5 0.5 0.5/; s|^mesh |mesh '"$GB_ROOT"'/scenes/cornell/|' \
    "$scene" >"$dir/other/cornell.scene"
"$tool" --headless --method octree --bake "$bake" --resolution 16x16 "$dir/other/cornell.scene" \
    -o "$dir/stale.png" >"$dir/out" 2>"$dir/err"
ok "$([ $? = 1 ] && grep -q "cornell.lot: stale" "$dir/err" && [ ! -e "$dir/stale.png" ];
      echo $?)" "a bake of another scene: --method octree fails, 'cornell.lot: stale'"

tap_done
