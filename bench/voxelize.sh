#!/bin/sh
# voxelize.sh — wall time and peak memory of voxelize against OpenVDB's own
# meshToVolume (unsigned distance, 1-voxel band) on the same triangles with
# the same voxel size, in the same run, for the benchmark scenes at
# resolutions 64, 128, 256, 512. Prints a Markdown table on stdout.
#
# Run by `make bench` (GB_BIN: the tools folder, build/bin by default).
# GB_SCENES: the scenes folder (default ../shared/scenes beside the repo);
# VOXELIZE_RESOLUTIONS, VOXELIZE_SCENES: override the lists.
#
# Columns: surface and write are voxelize's steps timed inside one
# process (bench/voxelize_bench.cpp) on 2 threads; "voxelize" is their sum,
# the work the target compares with meshToVolume, with its peak memory (the
# process after loading the scene); "tool" is `voxelize` run as a user runs
# it (process start, scene load and all); "ratio" is voxelize / meshToVolume;
# "file KiB" the size of the .vdb written.

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
GB_SCENES=${GB_SCENES:-$root/../shared/scenes}
resolutions=${VOXELIZE_RESOLUTIONS:-64 128 256 512}
scenes=${VOXELIZE_SCENES:-"cornell-box/CornellBox-Original.obj stanford-bunny/bun_zipper.obj
sponza-dabrovic/sponza.obj bitterli-staircase/staircase.obj.gz"}
build=$(dirname "$GB_BIN")
helper=$build/bench/voxelize_bench
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-voxelize.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

# The helper is bench code that `make bench` builds into build/bench/.
if [ ! -x "$helper" ]; then
    echo "voxelize.sh: $helper not built: run make bench" >&2
    exit 1
fi
if [ ! -x /usr/bin/time ]; then
    echo "voxelize.sh: /usr/bin/time is needed for peak memory (package time)" >&2
    exit 1
fi

# field KEY FILE: the value of KEY=value in the one-line output in FILE
field() {
    tr ' ' '\n' <"$2" | sed -n "s/^$1=//p"
}

# peak FILE: peak resident memory in MiB from /usr/bin/time -f %M in FILE
peak() {
    awk '{ printf "%.0f", $1 / 1024 }' "$1"
}

echo "voxelize against OpenVDB meshToVolume (unsigned, 1-voxel band); $(nproc) cores; $(date -u +%Y-%m-%d)"
echo
echo "| scene | res | grid | surface voxels | surface s | write s | voxelize s | peak MiB | meshToVolume s | peak MiB | ratio | file KiB | tool s | tool peak MiB |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in $scenes; do
    path=$GB_SCENES/$scene
    if [ ! -f "$path" ]; then
        echo "| $scene | missing: $path |"
        continue
    fi
    for r in $resolutions; do
        /usr/bin/time -f %M -o "$dir/v.mem" "$helper" voxelize "$path" "$r" "$dir/out.vdb" \
            >"$dir/v.out" || exit 1
        /usr/bin/time -f %M -o "$dir/m.mem" "$helper" mesh_to_volume "$path" "$r" \
            >"$dir/m.out" || exit 1
        start=$(date +%s.%N)
        /usr/bin/time -f %M -o "$dir/t.mem" "$GB_BIN/voxelize" -q -r "$r" "$path" \
            -o "$dir/tool.vdb" || exit 1
        tool=$(echo "$(date +%s.%N) - $start" | bc)
        surface=$(field surface "$dir/v.out")
        write=$(field write "$dir/v.out")
        total=$(echo "$surface + $write" | bc)
        mtv=$(field mesh_to_volume "$dir/m.out")
        ratio=$(echo "scale=2; $total / $mtv" | bc)
        kib=$(( $(wc -c <"$dir/tool.vdb") / 1024 ))
        printf '| %s | %s | %s | %s | %s | %s | %.3f | %s | %s | %s | %.2f | %s | %.2f | %s |\n' \
            "$(basename "$scene")" "$r" "$(field size "$dir/v.out")" \
            "$(field surface_voxels "$dir/v.out")" "$surface" "$write" \
            "$total" "$(peak "$dir/v.mem")" "$mtv" "$(peak "$dir/m.mem")" "$ratio" \
            "$kib" "$tool" "$(peak "$dir/t.mem")"
    done
done
