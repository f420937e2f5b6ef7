#!/bin/sh
# startup.sh — what a run of each tool costs before it does anything: the
# median wall and CPU milliseconds of `TOOL --version` over STARTUP_RUNS
# runs (default 21), beside OpenVDB's own `vdb_print -version`, the peer, in
# the same run (issue 24's goal: every tool at or below 50 ms). The CPU
# time is user + system of the process (GNU time). In a sweep of hundreds
# of runs, this is the part that does no work.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the
# repository.

GB_ROOT=${GB_ROOT:-.}
GB_BIN=${GB_BIN:-$GB_ROOT/build/bin}
STARTUP_RUNS=${STARTUP_RUNS:-21}

# median_ms COMMAND...: "wall cpu", the medians in ms of STARTUP_RUNS runs
# (perl: wall from a microsecond clock, CPU from times() of the child).
median_ms() {
    perl -MTime::HiRes=time -e '
        my $runs = shift; my (@wall, @cpu);
        open(my $results, ">&", \*STDOUT) or die;
        open(STDOUT, ">", "/dev/null") or die;
        open(STDERR, ">", "/dev/null") or die;
        for (1 .. $runs) {
            my @before = times; my $t = time;
            system(@ARGV) == 0 or die "startup.sh: @ARGV failed\n";
            push @wall, 1000 * (time - $t);
            my @after = times;
            push @cpu, 1000 * ($after[2] + $after[3] - $before[2] - $before[3]);
        }
        my $m = int(@wall / 2);
        printf $results "%.0f %.0f\n", (sort { $a <=> $b } @wall)[$m], (sort { $a <=> $b } @cpu)[$m];
    ' "$STARTUP_RUNS" "$@"
}

echo "start-up: median of $STARTUP_RUNS runs of --version; $(nproc) cores," \
    "load $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d)"
echo
peer=$(command -v vdb_print >/dev/null 2>&1 && median_ms vdb_print -version)
echo "| program | shared libraries | wall ms | cpu ms | wall / vdb_print's |"
echo "|---|---:|---:|---:|---:|"
if [ -n "$peer" ]; then
    set -- $peer
    echo "| vdb_print -version (peer) | $(ldd "$(command -v vdb_print)" | wc -l) | $1 | $2 | 1.00 |"
else
    echo "startup.sh: vdb_print (libopenvdb-tools) not found: no peer column" >&2
fi
for tool in "$GB_BIN"/*; do
    [ -x "$tool" ] || continue
    set -- $(median_ms "$tool" --version)
    ratio=-
    [ -n "$peer" ] && ratio=$(echo "$1 ${peer%% *}" | awk '{ printf "%.2f", ($2 > 0 ? $1 / $2 : 0) }')
    echo "| $(basename "$tool") | $(ldd "$tool" | wc -l) | $1 | $2 | $ratio |"
done
