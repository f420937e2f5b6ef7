#!/bin/sh
# shards.sh — what splitting photons, cluster and reference costs (make
# slurm-bake, SHARDS=N; reference --tile I/N): for photons, one
# run of photons -n COUNT against the same photons as N shards run one after
# another (photons --shard I/N) plus photons --merge, same scene, same run;
# CPU seconds (user + sys, GNU time) and wall, the merged map checked
# byte-identical to the single run; the same for cluster on that map (each
# part indexing only its halo: peak memory too) and for one reference
# render against N parts and --merge. Then, on paper, from the measured rates:
# a 10^9-photon bake of the scene.
#
#   sh bench/shards.sh [SCENE]      SHARDS_COUNT (default 2000000), SHARDS_N (4),
#                                   SHARDS_SPP (16), SHARDS_SIZE (256x144)
#
# GB_BIN: the tools (default build/bin).

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
scene=${1:-$root/scenes/shared/sponza.scene}
count=${SHARDS_COUNT:-2000000}
n=${SHARDS_N:-4}
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-shards.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

# timed NAME COMMAND...: runs it; appends "NAME cpu_s wall_s peak_kB" to
# $dir/times and its standard output to $dir/NAME.out.
timed() {
    name=$1
    shift
    /usr/bin/time -f "$name %U %S %e %M" -a -o "$dir/times" "$@" >>"$dir/$name.out" || exit 1
}

timed single "$GB_BIN/photons" -q -n "$count" "$scene" -o "$dir/single.phot"
shards=
for i in $(seq 0 $((n - 1))); do
    timed shard "$GB_BIN/photons" -q -n "$count" --shard "$i/$n" "$scene" -o "$dir/$i.phot"
    shards="$shards $dir/$i.phot"
done
timed merge "$GB_BIN/photons" --merge $shards -o "$dir/merged.phot"
cmp -s "$dir/single.phot" "$dir/merged.phot" && same=yes || same=NO
bytes=$(stat -c %s "$dir/merged.phot")

# cluster: one run on the map against N parts (--shard I/N) and --merge.
timed cluster "$GB_BIN/cluster" -q --stats "$scene" "$dir/single.phot" -o "$dir/single.lot"
leaves=
for i in $(seq 0 $((n - 1))); do
    timed leaves "$GB_BIN/cluster" -q --stats --shard "$i/$n" "$scene" "$dir/single.phot" \
        -o "$dir/leaves$i.lot"
    leaves="$leaves $dir/leaves$i.lot"
done
timed octree-merge "$GB_BIN/cluster" --merge $leaves -o "$dir/merged.lot"
cmp -s "$dir/single.lot" "$dir/merged.lot" && octree_same=yes || octree_same=NO
indexed=$(sed -n 's/^indexed_photons //p' "$dir/leaves.out" | tr '\n' ' ')
map_photons=$(sed -n 's/^indexed_photons //p' "$dir/cluster.out")

# reference: one render against N parts (--tile I/N) and --merge, same scene.
spp=${SHARDS_SPP:-16}
size=${SHARDS_SIZE:-256x144}
timed reference "$GB_BIN/reference" -q --spp "$spp" -r "$size" "$scene" -o "$dir/whole.exr"
parts=
for i in $(seq 0 $((n - 1))); do
    timed part "$GB_BIN/reference" -q --spp "$spp" -r "$size" --tile "$i/$n" "$scene" \
        -o "$dir/part$i.exr"
    parts="$parts $dir/part$i.exr"
done
timed image-merge "$GB_BIN/reference" --merge $parts -o "$dir/merged.exr"
cmp -s "$dir/whole.exr" "$dir/merged.exr" && image_same=yes || image_same=NO

echo "photons in $n shards; $(basename "$scene"), $count photons; $(nproc) cores, load" \
    "$(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
awk -v n="$n" -v bytes="$bytes" -v same="$same" -v count="$count" -v spp="$spp" \
    -v size="$size" -v image_same="$image_same" -v octree_same="$octree_same" \
    -v indexed="$indexed" -v map_photons="$map_photons" '
    { cpu[$1] += $2 + $3; wall[$1] += $4; if ($5 > peak[$1]) peak[$1] = $5 }
    END {
        printf "| step | CPU s | wall s | peak MB |\n|---|---:|---:|---:|\n"
        row("photons, one run", "single")
        row(sprintf("photons, %d shards (--shard I/%d)", n, n), "shard")
        row("photons --merge", "merge")
        row("cluster, one run", "cluster")
        row(sprintf("cluster, %d parts (--shard I/%d)", n, n), "leaves")
        row("cluster --merge", "octree-merge")
        row(sprintf("reference %s, %d spp, one run", size, spp), "reference")
        row(sprintf("reference, %d parts (--tile I/%d)", n, n), "part")
        row("reference --merge", "image-merge")
        printf "\nphotons: shards and merge against one run: %.2fx the CPU; the merged map" \
            " (%d bytes) byte-identical to the one run: %s.\n",
            (cpu["shard"] + cpu["merge"]) / cpu["single"], bytes, same
        printf "cluster: parts and merge against one run: %.2fx the CPU, the largest part" \
            " %.2fx the peak memory; the merged octree byte-identical: %s.\n",
            (cpu["leaves"] + cpu["octree-merge"]) / cpu["cluster"],
            peak["leaves"] / peak["cluster"], octree_same
        parts = split(indexed, part_indexed, " ")
        printf "cluster: photons each part indexes (its halo), of the %d of the map:", map_photons
        for (i = 1; i <= parts; ++i)
            printf " %.0f %%", 100 * part_indexed[i] / map_photons
        printf ".\n"
        printf "reference: parts and merge against one run: %.2fx the CPU; the merged image" \
            " byte-identical: %s.\n", (cpu["part"] + cpu["image-merge"]) / cpu["reference"],
            image_same
        # a run = a fixed start (scene load, BVH) + tracing: two equations
        fixed = (cpu["shard"] - cpu["single"]) / (n - 1)
        trace = count / (cpu["single"] - fixed)
        rate = bytes / (wall["merge"] > 0.01 ? wall["merge"] : 0.01)
        total = 1e9 / count * bytes
        printf "A run costs a fixed %.2f CPU s (load, BVH) and traces %.0f photons per CPU s.\n",
            fixed, trace
        printf "10^9 photons of this scene, on paper: %.1f GB of photon map (as many stored" \
            " per photon traced as here); %.2f CPU h of tracing, plus %.2f CPU s a shard; on" \
            " 64 shards of one core, %.1f min each; the merge, at the %.0f MB/s measured" \
            " here, %.0f s.\n", total / 1e9, 1e9 / trace / 3600, fixed,
            (1e9 / trace / 64 + fixed) / 60, rate / 1e6, total / rate
    }
    # a table row: CPU and wall summed over the runs of a step, the largest peak
    function row(label, step) {
        printf "| %s | %.2f | %.2f | %.0f |\n", label, cpu[step], wall[step], peak[step] / 1024
    }' "$dir/times"
