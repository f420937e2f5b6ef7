#!/bin/sh
# slurm_bake.sh — make slurm-bake (bake.mk): one scene's bake as Slurm jobs,
# each running the same bake.mk rule that make bake runs here:
#   voxelize → thin → segment          three jobs, each afterok the one before
#   photons, then cluster              each a job array of SHARDS tasks (--shard
#                                      I/N) and a merge job afterok the array
#   atlas, then lightmap               lightmap afterok atlas and cluster
# then waits (sbatch --wait) for a last job that needs all of them. A job
# that fails cancels what depends on it (--kill-on-invalid-dep), and this
# script then fails naming the logs: PREFIX.slurm-STEP.*.log.
#
# The environment gives what make bake takes (bake.mk passes it): BAKE_MK,
# BIN, BAKE, SCENE, SHARDS, VOXELIZE_FLAGS ... LIGHTMAP_FLAGS (each job gets
# this environment: sbatch's default --export=ALL), PREFIX the outputs'
# BAKE/NAME, and SBATCH_FLAGS (for instance -p PARTITION).

set -u
# The jobs' makes get the bake from the variables above, not from this make's
# jobserver or command line.
unset MAKEFLAGS MFLAGS MAKELEVEL
rule() {
    echo "make --no-print-directory -f $BAKE_MK $1"
}

# submit STEP SBATCH-OPTIONS... -- COMMAND: the job id of STEP.
submit() {
    step=$1
    shift
    sbatch --parsable --kill-on-invalid-dep=yes -J "gibake-$step" \
        -o "$PREFIX.slurm-$step.%A_%a.log" ${SBATCH_FLAGS:-} "$@" | cut -d';' -f1
}

voxelize=$(submit voxelize --wrap "$(rule "$PREFIX.vdb")") || exit 1
thin=$(submit thin -d "afterok:$voxelize" --wrap "$(rule "$PREFIX.skel")") || exit 1
segment=$(submit segment -d "afterok:$thin" --wrap "$(rule "$PREFIX.seg")") || exit 1
if [ "$SHARDS" -gt 1 ]; then
    shards=$(submit photons --array "0-$((SHARDS - 1))" \
        --wrap "$(rule "$PREFIX.phot.\$SLURM_ARRAY_TASK_ID-of-$SHARDS")") || exit 1
    photons=$(submit photons-merge -d "afterok:$shards" --wrap "$(rule "$PREFIX.phot")") || exit 1
else
    photons=$(submit photons --wrap "$(rule "$PREFIX.phot")") || exit 1
fi
if [ "$SHARDS" -gt 1 ]; then
    parts=$(submit cluster -d "afterok:$photons" --array "0-$((SHARDS - 1))" \
        --wrap "$(rule "$PREFIX.lot.\$SLURM_ARRAY_TASK_ID-of-$SHARDS")") || exit 1
    cluster=$(submit cluster-merge -d "afterok:$parts" --wrap "$(rule "$PREFIX.lot")") || exit 1
else
    cluster=$(submit cluster -d "afterok:$photons" --wrap "$(rule "$PREFIX.lot")") || exit 1
fi
atlas=$(submit atlas --wrap "$(rule "$PREFIX.atlas")") || exit 1
lightmap=$(submit lightmap -d "afterok:$atlas:$cluster" --wrap "$(rule "$PREFIX.lightmap.exr")") ||
    exit 1
echo "slurm-bake: jobs $voxelize $thin $segment ${shards:+$shards (array of $SHARDS) }$photons" \
    "${parts:+$parts (array of $SHARDS) }$cluster $atlas $lightmap; waiting"
sbatch --wait --kill-on-invalid-dep=yes -J gibake-done -o /dev/null ${SBATCH_FLAGS:-} \
    -d "afterok:$segment:$lightmap" --wrap true >/dev/null
# A job cancelled for a failed dependency never ran, and --wait does not say
# so: every job (every task of the array) must have completed.
for job in $voxelize $thin $segment ${shards:-} $photons ${parts:-} $cluster $atlas $lightmap; do
    states=$(scontrol -o show job "$job" | grep -o 'JobState=[A-Z_]*' | sort -u)
    if [ "$states" != JobState=COMPLETED ]; then
        echo "slurm-bake: a job failed: job $job:" $states "; see $PREFIX.slurm-*.log" >&2
        exit 1
    fi
done
echo "slurm-bake: done"
