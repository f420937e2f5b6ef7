#!/bin/sh
# slurm.t — make slurm-bake on a real Slurm: a single-node cluster started
# here (munged with a key made here and its own socket, slurmctld and slurmd
# from a slurm.conf made here on ports of their own), the Cornell box baked
# with photons and cluster in 4 shards (job arrays) and every step a job afterok the
# one before, and every baked file byte-identical to make bake on this
# machine. The daemons are stopped at the end. Needs root (slurmd does).
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
needs scene-info voxelize thin segment photons cluster atlas lightmap
unset MAKEFLAGS MFLAGS MAKELEVEL

for program in munged slurmctld slurmd sbatch sinfo; do
    command -v $program >/dev/null 2>&1 || missing "$program (Debian's munge and slurm-wlm)"
done
[ "$(id -u)" = 0 ] || missing "root, which slurmd needs"
if [ $failed != 0 ]; then
    tap_done
    exit
fi

cl=$dir/cluster
mkdir -p "$cl/munge" "$cl/state" "$cl/spool" "$cl/log"
chmod 700 "$cl/munge"
dd if=/dev/urandom of="$cl/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$cl/munge/munge.key"
stop_cluster() {
    for pid in "$cl/slurmd.pid" "$cl/slurmctld.pid"; do
        [ -s "$pid" ] && kill "$(cat "$pid")" 2>/dev/null
    done
    munged --stop --socket="$cl/munge/socket" >/dev/null 2>&1
    sleep 1
    [ -n "$GB_KEEP" ] || rm -rf "$dir"
}
trap stop_cluster EXIT

munged --key-file="$cl/munge/munge.key" --socket="$cl/munge/socket" \
    --pid-file="$cl/munge/pid" --log-file="$cl/munge/log" --seed-file="$cl/munge/seed" \
    --force >"$dir/err" 2>&1
ok $? "munged starts with a key of its own"

port=$((20000 + ($$ % 5000) * 2))
host=$(hostname -s)
cat >"$cl/slurm.conf" <<CONF
ClusterName=gibake
SlurmctldHost=$host(127.0.0.1)
AuthType=auth/munge
AuthInfo=socket=$cl/munge/socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$cl/state
SlurmdSpoolDir=$cl/spool
SlurmctldPidFile=$cl/slurmctld.pid
SlurmdPidFile=$cl/slurmd.pid
SlurmctldLogFile=$cl/log/slurmctld.log
SlurmdLogFile=$cl/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=gibake Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$cl/slurm.conf
slurmctld -f "$SLURM_CONF" && slurmd -f "$SLURM_CONF"
ok $? "slurmctld and slurmd start"
state=
for i in $(seq 180); do
    state=$(sinfo -h -o %T 2>/dev/null)
    [ "$state" = idle ] && break
    sleep 1
done
ok "$([ "$state" = idle ]; echo $?)" "the node is idle (${state:-no answer})"
if [ "$state" != idle ]; then
    sed 's/^/#   /' "$cl/log/slurmctld.log" "$cl/log/slurmd.log" 2>/dev/null | tail -20
    tap_done
    exit
fi

# The scene in a folder of its own: the jobs and this test bake one scene.
mkdir "$dir/scene"
cp "$GB_ROOT/scenes/cornell/cornell.scene" "$GB_ROOT/scenes/cornell/cornell.obj" \
    "$GB_ROOT/scenes/cornell/cornell.mtl" "$dir/scene/"
flags() {
    make --no-print-directory -f "$GB_ROOT/bake.mk" BIN="$GB_BIN" SCENE="$dir/scene/cornell.scene" \
        VOXELIZE_FLAGS="-q -r 24" THIN_FLAGS=-q SEGMENT_FLAGS=-q PHOTONS_FLAGS="-q -n 20000" \
        CLUSTER_FLAGS="-q --depth 4" ATLAS_FLAGS="-q --size 256" LIGHTMAP_FLAGS=-q "$@"
}
flags BAKE="$dir/here" bake >"$dir/here.out" 2>&1
ok $? "make bake on this machine"
flags BAKE="$dir/slurm" SHARDS=4 slurm-bake >"$dir/slurm.out" 2>&1
ok $? "make slurm-bake SHARDS=4"
sed 's/^/#   /' "$dir/slurm.out"
for step in photons cluster; do
    ok "$(ls "$dir"/slurm/cornell.slurm-$step.*_[0-3].log 2>/dev/null | wc -l | grep -qx 4
          echo $?)" "$step ran as 4 array tasks"
done
same=0
for f in vdb skel grid.vdb seg phot lot atlas lightmap.exr glb; do
    cmp -s "$dir/here/cornell.$f" "$dir/slurm/cornell.$f" || { same=1; echo "# cornell.$f differs"; }
done
ok $same "every baked file of slurm-bake is byte-identical to make bake's"

# A failing step fails slurm-bake, naming the logs.
flags BAKE="$dir/broken" SHARDS=2 CLUSTER_FLAGS="--depth 99" slurm-bake >"$dir/broken.out" 2>&1
ok "$([ $? != 0 ] && grep -q "a job failed" "$dir/broken.out"; echo $?)" \
    "a failing job (cluster --depth 99) fails slurm-bake and names the logs"

tap_done
