#!/bin/sh
# output.t — how every tool writes its outputs (formats/output_file.h), as a
# user types it: -o written through to character devices, FIFOs, /dev/stdout,
# "-" and symlinks, which stay what they were; outputs of mode 0666 & ~umask
# under umask 022 and 027; an output folder missing or not writable, or an
# unknown image format, refused before any input is read; SIGINT and SIGKILL
# during a write; a file-size limit and a full tmpfs. Prints TAP.
#
# Nothing depends on timing. A signal is sent only when the tool is frozen
# (SIGSTOP, every thread stopped) with its temporary file present, so the
# signal is known to land before the rename; a tool that finished its write
# before that is checked as finished (its output the new complete file).
# Where strace works, each tool also gets the signal injected at its first
# fsync(2), which comes after the temporary is written and before the rename:
# the same checks, with certainty that the window was hit.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
scene=$GB_ROOT/scenes/cornell/cornell.scene
in=$dir/in
mounted=
cleanup() {
    [ -n "$mounted" ] && umount "$mounted" 2>/dev/null
    chmod -R u+w "$dir" 2>/dev/null
    rm -rf "$dir"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

tools="voxelize thin segment photons cluster reference gbview imgdiff"
needs $tools
root=0
[ "$(id -u)" = 0 ] && root=1

# ext TOOL: the extension of TOOL's output (thin: the skeleton's)
ext() {
    case $1 in
    voxelize) e=vdb ;; thin) e=skel ;; segment) e=seg ;; photons) e=phot ;;
    cluster) e=lot ;; reference) e=exr ;; gbview | imgdiff) e=png ;;
    esac
}

# Runs its arguments with SIGINT at its default action: a script's background
# jobs start with SIGINT ignored, and the writer leaves an ignored signal alone.
default_int='$SIG{INT} = "DEFAULT"; exec { $ARGV[0] } @ARGV or die "$ARGV[0]: $!\n"'

# run_job HOW SIZE TOOL OUT GRID: TOOL's small or big job writing OUT (thin:
# and GRID). HOW: fg (its status is returned), bg (started in the background
# with SIGINT at its default action, as in a terminal; $job is its pid), or
# INT / KILL (under strace, that signal injected at its first fsync).
# Output in $dir/job.out, messages in $dir/job.err.
run_job() {
    how=$1 o=$4 g=$5
    case $2-$3 in
    small-voxelize) set -- "$GB_BIN/voxelize" -q -r 16 "$scene" -o "$o" ;;
    big-voxelize) set -- "$GB_BIN/voxelize" -q -r 160 "$scene" -o "$o" ;;
    small-thin) set -- "$GB_BIN/thin" -q "$in/voxelize.vdb" -o "$o" --grid "$g" ;;
    big-thin) set -- "$GB_BIN/thin" -q "$in/big.vdb" -o "$o" --grid "$g" ;;
    small-segment) set -- "$GB_BIN/segment" "$in/thin.skel" -o "$o" ;;
    big-segment) set -- "$GB_BIN/segment" "$in/thin.skel" -o "$o" ;;   # its write is short anyway
    small-photons) set -- "$GB_BIN/photons" -q -n 10000 "$scene" -o "$o" ;;
    big-photons) set -- "$GB_BIN/photons" -q -n 500000 "$scene" -o "$o" ;;
    small-cluster) set -- "$GB_BIN/cluster" -q --depth 3 "$scene" "$in/photons.phot" -o "$o" ;;
    big-cluster) set -- "$GB_BIN/cluster" -q --depth 5 "$scene" "$in/photons.phot" -o "$o" ;;
    small-reference)
        set -- "$GB_BIN/reference" -q --mode direct --spp 1 --resolution 64x64 "$scene" -o "$o" ;;
    big-reference)
        set -- "$GB_BIN/reference" -q --mode direct --spp 1 --resolution 1024x1024 "$scene" \
            -o "$o" ;;
    small-gbview) set -- "$GB_BIN/gbview" "$scene" --headless --quiet --resolution 64x64 -o "$o" ;;
    big-gbview)
        set -- "$GB_BIN/gbview" "$scene" --headless --quiet --resolution 1024x1024 -o "$o" ;;
    small-imgdiff) set -- "$GB_BIN/imgdiff" --heatmap "$o" "$in/reference.exr" "$in/g.exr" ;;
    big-imgdiff) set -- "$GB_BIN/imgdiff" --heatmap "$o" "$in/big1.exr" "$in/big2.exr" ;;
    esac
    case $how in
    fg) "$@" >"$dir/job.out" 2>"$dir/job.err" ;;
    bg)
        # a simple command, so that $! is the tool itself once perl execs it
        perl -e "$default_int" "$@" >"$dir/job.out" 2>"$dir/job.err" &
        job=$!
        ;;
    *)
        MESA_SHADER_CACHE_DISABLE=true strace -o /dev/null -qq -f -e trace=fsync \
            -e inject=fsync:signal="$how":when=1 \
            perl -e "$default_int" "$@" >"$dir/job.out" 2>"$dir/job.err"
        ;;
    esac
}


# leftovers FOLDER: $left, the names of the temporaries (*.tmp.*) in FOLDER
leftovers() {
    left=
    for f in "$1"/*.tmp.*; do
        [ -e "$f" ] && left="$left ${f##*/}"
    done
}

# ---------------------------------------------------------------- inputs

mkdir "$in"
run_job fg small voxelize "$in/voxelize.vdb" &&
    run_job fg small thin "$in/thin.skel" "$in/thin.grid.vdb" &&
    run_job fg small segment "$in/segment.seg" &&
    run_job fg small photons "$in/photons.phot" &&
    run_job fg small cluster "$in/cluster.lot" &&
    run_job fg small reference "$in/reference.exr" &&
    run_job fg small gbview "$in/gbview.png" &&
    "$GB_BIN/gbview" "$scene" --headless --quiet --resolution 64x64 --method flc -o "$in/g.exr" &&
    run_job fg small imgdiff "$in/imgdiff.png"
if [ $? != 0 ]; then
    echo "Bail out! the small jobs failed: $(cat "$dir/job.err")"
    exit 1
fi
# the reference bytes of each tool's small job
for t in $tools; do
    ext $t
    cp "$in/$t.$e" "$in/$t.expected.$e"
done
cp "$in/thin.grid.vdb" "$in/thin.expected.grid.vdb"

# same TOOL FILE [GRID]: FILE (and GRID) hold TOOL's small-job bytes
same() {
    ext $1
    cmp -s "$2" "$in/$1.expected.$e" && { [ $1 != thin ] || cmp -s "$3" "$in/thin.expected.grid.vdb"; }
}

# ---------------------------------------------------------------- write through

mkdir "$dir/dev"
through_ok=1
if mknod "$dir/dev/null" c 1 3 2>/dev/null && mknod "$dir/dev/null.exr" c 1 3 &&
    mknod "$dir/dev/null.png" c 1 3 && mknod "$dir/dev/full" c 1 7 &&
    mknod "$dir/dev/full.png" c 1 7; then
    for t in $tools; do
        ext $t
        node=$dir/dev/null
        [ $e = exr ] || [ $e = png ] && node=$dir/dev/null.$e
        run_job fg small $t "$node" "$node"
        status=$?
        leftovers "$dir/dev"
        intact=$([ -c "$node" ] && [ "$(stat -c %t,%T "$node")" = 1,3 ] && [ -z "$left" ]; echo $?)
        [ $status = 0 ] && [ $intact = 0 ] || through_ok=0
        ok "$([ $status = 0 ] && [ $intact = 0 ]; echo $?)" \
            "$t -o a null device (mknod c 1 3): exit 0, still that device, nothing beside it"
    done
    "$GB_BIN/segment" "$in/thin.skel" -o "$dir/dev/full" 2>"$dir/err"
    ok "$([ $? = 1 ] && grep -qx "segment: $dir/dev/full: cannot write: No space left on device" \
        "$dir/err"; echo $?)" "segment -o a full device (mknod c 1 7): 'cannot write: No space left on device', exit 1"
    run_job fg small gbview "$dir/dev/full.png"
    ok "$([ $? = 1 ] && grep -qx "gbview: $dir/dev/full.png: cannot write: No space left on device" \
        "$dir/job.err" && [ -c "$dir/dev/full.png" ]; echo $?)" \
        "gbview -o a full device: the same error, exit 1, the device kept"
else
    echo "# mknod is not allowed here (not root): the device checks use /dev/null only"
    for t in $tools; do skip "mknod: not allowed here"; done
    skip "mknod: not allowed here"
    skip "mknod: not allowed here"
fi

# /dev/null itself: only once the tools are known to write through a device
# (as root, a tool that renames onto its output would replace /dev/null).
if [ $through_ok = 1 ]; then
    for t in voxelize segment photons; do
        run_job fg small $t /dev/null /dev/null
        ok "$([ $? = 0 ] && [ -c /dev/null ] && [ "$(stat -c %t,%T /dev/null)" = 1,3 ]; echo $?)" \
            "$t -o /dev/null: exit 0, /dev/null still the null device"
    done
else
    for t in voxelize segment photons; do skip "a tool replaced a device: /dev/null not tried"; done
fi

# FIFOs, read by cat in the background
mkdir "$dir/fifo"
for t in $tools; do
    ext $t
    fifo=$dir/fifo/out.$e grid=$dir/fifo/out.grid.vdb
    mkfifo "$fifo"
    cat "$fifo" >"$dir/fifo.got" &
    reader=$!
    if [ $t = thin ]; then
        mkfifo "$grid"
        cat "$grid" >"$dir/fifo.grid.got" &
        grid_reader=$!
    fi
    run_job fg small $t "$fifo" "$grid"
    status=$?
    # a writer end of our own, so that a reader still waiting gets its EOF
    exec 9<>"$fifo"
    exec 9>&-
    wait $reader
    if [ $t = thin ]; then
        exec 9<>"$grid"
        exec 9>&-
        wait $grid_reader
    fi
    ok "$([ $status = 0 ] && same $t "$dir/fifo.got" "$dir/fifo.grid.got" && [ -p "$fifo" ] &&
        { [ $t != thin ] || [ -p "$grid" ]; }; echo $?)" \
        "$t -o a FIFO: exit 0, the reader gets the bytes of a regular -o, the FIFO stays"
    rm -f "$fifo" "$grid"
done

# standard output: "-" and /dev/stdout (containers and OpenVDB files)
for t in voxelize segment photons cluster; do
    ext $t
    run_job fg small $t - && cp "$dir/job.out" "$dir/dash.$e"
    ok "$([ $? = 0 ] && same $t "$dir/dash.$e"; echo $?)" "$t -o - writes the file to standard output"
done
if [ $through_ok = 1 ]; then
    for t in thin segment; do
        ext $t
        run_job fg small $t /dev/stdout "$dir/stdout.grid.vdb" && cp "$dir/job.out" "$dir/stdout.$e"
        ok "$([ $? = 0 ] && same $t "$dir/stdout.$e" "$dir/stdout.grid.vdb"; echo $?)" \
            "$t -o /dev/stdout (a regular file here) writes standard output"
    done
    ok "$([ -L /dev/stdout ] || [ ! -e /dev/stdout ]; echo $?)" "/dev/stdout is still a symlink"
    "$GB_BIN/segment" "$in/thin.skel" -o /dev/stdout | cat >"$dir/piped.seg"
    ok "$(same segment "$dir/piped.seg"; echo $?)" "segment -o /dev/stdout into a pipe"
else
    for i in 1 2 3 4; do skip "a tool replaced a device: /dev/stdout not tried"; done
fi
for t in reference gbview; do
    run_job fg small $t -
    ok "$([ $? = 1 ] && grep -qx "$t: -: unknown image format .*" "$dir/job.err" &&
        [ ! -s "$dir/job.out" ]; echo $?)" \
        "$t -o -: refused (an image's format comes from its name), nothing written"
done

# symlinks: followed, the link stays a link, the temporary beside the target
mkdir "$dir/links" "$dir/links/target"
for t in $tools; do
    ext $t
    rm -f "$dir/links/target/"*
    echo previous >"$dir/links/target/out.$e"
    ln -s "target/out.$e" "$dir/links/link.$e"
    ln -s "target/new.grid.vdb" "$dir/links/link.grid.vdb"   # dangling: created
    run_job fg small $t "$dir/links/link.$e" "$dir/links/link.grid.vdb"
    status=$?
    leftovers "$dir/links"
    left_links=$left
    leftovers "$dir/links/target"
    ok "$([ $status = 0 ] && [ -L "$dir/links/link.$e" ] &&
        same $t "$dir/links/target/out.$e" "$dir/links/target/new.grid.vdb" &&
        { [ $t != thin ] || [ -L "$dir/links/link.grid.vdb" ]; } &&
        [ -z "$left$left_links" ]; echo $?)" \
        "$t -o link.$e: the link stays a link, its target gets the bytes, no temporary left"
    rm -f "$dir/links/link.$e" "$dir/links/link.grid.vdb"
done
ln -s "$dir/links/chain2.seg" "$dir/links/chain1.seg"
ln -s "target/chained.seg" "$dir/links/chain2.seg"
"$GB_BIN/segment" "$in/thin.skel" -o "$dir/links/chain1.seg"
ok "$([ -L "$dir/links/chain1.seg" ] && [ -L "$dir/links/chain2.seg" ] &&
    same segment "$dir/links/target/chained.seg"; echo $?)" \
    "segment -o a chain of two links (absolute, then relative): both stay, the end gets the bytes"

# ---------------------------------------------------------------- modes

for mask in 022 027; do
    mkdir "$dir/mode$mask"
    want=$(printf '%o' $((0666 & ~0$mask)))
    for t in $tools; do
        ext $t
        out=$dir/mode$mask/out.$e
        (umask $mask && run_job fg small $t "$out" "$dir/mode$mask/out.grid.vdb")
        modes=$(stat -c %a "$out" 2>&1)
        [ $t = thin ] && modes="$modes $(stat -c %a "$dir/mode$mask/out.grid.vdb" 2>&1)"
        ok "$([ "$modes" = "$want" ] || [ "$modes" = "$want $want" ]; echo $?)" \
            "umask $mask: $t's output has mode $want (got $modes)"
    done
    (umask $mask && "$GB_BIN/reference" -q --mode direct --spp 1 --resolution 16x16 --png \
        "$scene" -o "$dir/mode$mask/both.exr")
    modes="$(stat -c %a "$dir/mode$mask/both.exr") $(stat -c %a "$dir/mode$mask/both.png")"
    ok "$([ "$modes" = "$want $want" ]; echo $?)" \
        "umask $mask: reference --png, both images mode $want (got $modes)"
done

# ---------------------------------------------------------------- checked first

# Every input here is missing: the message names the output, so the output
# was checked before any input was read, let alone any work done.
none=$dir/none
missing=$dir/missing
# refused TOOL WHAT OUTPUT MESSAGE ARGS...: two checks, exit 1 and the one line
refused() {
    tool=$GB_BIN/$1 what=$2 output=$3 message=$4
    shift 4
    "$tool" "$@" >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ $status = 1 ]; echo $?)" "$what: exit status 1 (got $status)"
    ok "$([ "$(cat "$dir/err")" = "${tool##*/}: $output: $message" ] && [ ! -s "$dir/out" ]; echo $?)" \
        "$what: '${tool##*/}: $output: $message' before reading any input"
}
gone="cannot write in folder '$missing': No such file or directory"
refused voxelize "voxelize -o missing/x.vdb" "$missing/x.vdb" "$gone" "$none.obj" -o "$missing/x.vdb"
refused thin "thin -o missing/x.skel" "$missing/x.skel" "$gone" "$none.vdb" -o "$missing/x.skel"
refused thin "thin --grid missing/x.grid.vdb" "$missing/x.grid.vdb" "$gone" \
    "$none.vdb" -o "$dir/x.skel" --grid "$missing/x.grid.vdb"
refused segment "segment -o missing/x.seg" "$missing/x.seg" "$gone" "$none.skel" -o "$missing/x.seg"
refused photons "photons -n 2000000 -o missing/x.phot" "$missing/x.phot" "$gone" \
    -n 2000000 "$none.obj" -o "$missing/x.phot"
refused photons "photons --merge -o missing/x.phot" "$missing/x.phot" "$gone" \
    --merge "$none.phot" -o "$missing/x.phot"
refused cluster "cluster -o missing/x.lot" "$missing/x.lot" "$gone" "$none.obj" "$none.phot" \
    -o "$missing/x.lot"
refused reference "reference -o missing/x.exr" "$missing/x.exr" "$gone" "$none.obj" \
    -o "$missing/x.exr"
refused gbview "gbview --headless -o missing/x.png" "$missing/x.png" "$gone" \
    "$none.obj" --headless -o "$missing/x.png"
refused gbview "gbview --write-vpls missing/x.vpl" "$missing/x.vpl" "$gone" \
    "$none.obj" --headless --method topo --write-vpls "$missing/x.vpl"
refused imgdiff "imgdiff --heatmap missing/x.png" "$missing/x.png" "$gone" \
    --heatmap "$missing/x.png" "$none.exr" "$none.exr"
unknown="unknown image format (the extension names it: .exr, .png, .jpg, .tif, .hdr, ...)"
refused reference "reference -o x.txt" "$dir/x.txt" "$unknown" "$none.obj" -o "$dir/x.txt"
refused gbview "gbview --headless -o x.txt" "$dir/x.txt" "$unknown" "$none.obj" --headless \
    -o "$dir/x.txt"
refused imgdiff "imgdiff --heatmap x.txt" "$dir/x.txt" "$unknown" --heatmap "$dir/x.txt" \
    "$none.exr" "$none.exr"
refused segment "segment -o a folder" "$in" "is a folder" "$none.skel" -o "$in"
echo plain >"$dir/plain"
refused voxelize "voxelize -o plain/x.vdb (a file, not a folder)" "$dir/plain/x.vdb" \
    "cannot write in folder '$dir/plain': Not a directory" "$none.obj" -o "$dir/plain/x.vdb"
ok "$([ ! -e "$missing" ] && [ ! -e "$dir/x.txt" ] && [ ! -e "$dir/x.skel" ]; echo $?)" \
    "the refused runs wrote nothing"

# A folder that is not writable: as root, the tools run as nobody (setpriv).
mkdir "$dir/ro"
chmod 555 "$dir/ro"
as_user=
if [ $root = 1 ] && command -v setpriv >/dev/null 2>&1; then
    as_user="setpriv --reuid=65534 --regid=65534 --clear-groups --"
    # nobody must be able to run the tools from where they are
    $as_user "$GB_BIN/voxelize" --version >/dev/null 2>&1 || as_user=
fi
if [ $root = 0 ] || [ -n "$as_user" ]; then
    chmod 711 "$dir"
    for t in $tools; do
        ext $t
        case $t in
        thin | segment) set -- "$none.in" -o "$dir/ro/x.$e" ;;
        cluster) set -- "$none.obj" "$none.phot" -o "$dir/ro/x.$e" ;;
        gbview) set -- "$none.obj" --headless -o "$dir/ro/x.$e" ;;
        imgdiff) set -- --heatmap "$dir/ro/x.$e" "$none.exr" "$none.exr" ;;
        *) set -- "$none.obj" -o "$dir/ro/x.$e" ;;
        esac
        $as_user "$GB_BIN/$t" "$@" >"$dir/out" 2>"$dir/err"
        status=$?
        ok "$([ $status = 1 ] && [ "$(cat "$dir/err")" = \
            "$t: $dir/ro/x.$e: cannot write in folder '$dir/ro': Permission denied" ]; echo $?)" \
            "$t into a folder it cannot write: '...: Permission denied', exit 1 (got $status)"
    done
    chmod 700 "$dir"
else
    for t in $tools; do skip "root, and no setpriv to run the tools as nobody"; done
fi

# ---------------------------------------------------------------- full disk

# ulimit -f 1 (512 or 1024 bytes, by the shell): each output is larger. The
# writer ignores SIGXFSZ, so the write fails with EFBIG.
mkdir "$dir/limit"
for t in $tools; do
    ext $t
    (ulimit -f 1 && run_job fg small $t "$dir/limit/out.$e" "$dir/limit/out.grid.vdb")
    status=$?
    [ $t = thin ] && short=$dir/limit/out.grid.vdb || short=$dir/limit/out.$e
    ok "$([ $status = 1 ] && [ "$(cat "$dir/job.err")" = \
        "$t: $short: cannot write: File too large" ]; echo $?)" \
        "$t past ulimit -f: '...: cannot write: File too large', exit 1 (got $status)"
    ok "$([ -z "$(ls -A "$dir/limit")" ]; echo $?)" "$t past ulimit -f: nothing left behind"
done

# A 32 KiB tmpfs, when this machine lets us mount one.
mkdir "$dir/small-disk"
if [ $root = 1 ] && mount -t tmpfs -o size=32k gibake-test "$dir/small-disk" 2>/dev/null; then
    mounted=$dir/small-disk
    for t in voxelize photons cluster reference; do
        ext $t
        if [ $t = reference ]; then
            "$GB_BIN/reference" -q --mode direct --spp 1 --resolution 128x128 "$scene" \
                -o "$mounted/out.$e" >"$dir/job.out" 2>"$dir/job.err"
        elif [ $t = cluster ] || [ $t = voxelize ]; then
            run_job fg big $t "$mounted/out.$e"     # the small ones fit in 32 KiB
        else
            run_job fg small $t "$mounted/out.$e"
        fi
        status=$?
        ok "$([ $status = 1 ] && [ "$(cat "$dir/job.err")" = \
            "$t: $mounted/out.$e: cannot write: No space left on device" ]; echo $?)" \
            "$t onto a full 32 KiB tmpfs: 'No space left on device', exit 1 (got $status)"
        ok "$([ -z "$(ls -A "$mounted")" ]; echo $?)" "$t onto a full tmpfs: nothing left behind"
    done
    umount "$mounted" && mounted=
else
    echo "# mount -t tmpfs is not allowed here: the full disk is only the ulimit -f one"
    for i in 1 2 3 4 5 6 7 8; do skip "mount -t tmpfs not allowed here"; done
fi

# ---------------------------------------------------------------- interrupted

# present GLOB: some file matches GLOB (builtins only: no process started)
present() {
    for candidate in $1; do
        [ -e "$candidate" ] && return 0
    done
    return 1
}

# alive PID: PID has not exited (a zombie has)
alive() {
    pline=
    read -r pline 2>/dev/null <"/proc/$1/stat" || return 1
    pline=${pline##*) }
    [ "${pline%% *}" != Z ]
}

# frozen PID: every thread of PID is stopped; gives up after many looks
frozen() {
    looks=0
    while [ $looks -lt 100000 ]; do
        running=0
        for task in /proc/"$1"/task/*; do
            tline=
            read -r tline 2>/dev/null <"$task/stat" || continue
            tline=${tline##*) }
            case ${tline%% *} in T | t | Z | X) ;; *) running=1 ;; esac
        done
        [ $running = 0 ] && return 0
        looks=$((looks + 1))
    done
    return 1
}

# to_main_thread PID: SIGINT to the main thread of PID (which writes every
# tool's outputs), as a terminal's Ctrl-C reaches a running process: the
# kernel gives a process's signal to its main thread when that thread can
# take it. Sent to a stopped process with kill, the signal would go to
# whichever thread resumes first, a worker as well, and the writer would
# run on towards its rename while that thread passes the signal on.
to_main_thread() {
    perl -e 'require "syscall.ph"; my $pid = $ARGV[0] + 0;
        syscall(&SYS_tgkill, $pid, $pid, 2) == 0 or die "tgkill: $!\n"' "$1"
}

# freeze_and_signal SIGNAL GLOB: $job is running; polls (a bounded number
# of times) until a file matches GLOB, freezes the job, and sends SIGNAL
# only if the file is still there once every thread is stopped; then
# resumes it and waits. Sets caught (1: signalled with the temporary there)
# and status.
freeze_and_signal() {
    caught=0 polls=0
    while [ $polls -lt 20000 ] && alive $job && ! present "$2"; do
        sleep 0.005
        polls=$((polls + 1))
    done
    if present "$2" && kill -STOP $job 2>/dev/null; then
        if frozen $job && present "$2"; then
            if [ "$1" = INT ]; then
                to_main_thread $job
            else
                kill -"$1" $job
            fi
            caught=1
        fi
        kill -CONT $job 2>/dev/null
    fi
    wait $job 2>/dev/null   # (the shell's "Killed" notice)
    status=$?
}

# previous TOOL: $out (and $grid) in an empty $dir/int, holding a previous
# output that no job writes
previous() {
    ext $1
    rm -rf "$dir/int"
    mkdir "$dir/int"
    out=$dir/int/out.$e grid=$dir/int/out.grid.vdb
    echo "previous $1 output" >"$out"
    echo "previous thin grid" >"$grid"
}

intact() {
    [ "$(cat "$out")" = "previous $1 output" ] &&
        { [ $1 != thin ] || [ "$(cat "$grid")" = "previous thin grid" ]; }
}

# stale_only: what a SIGKILL may leave: at most one temporary, of the output
# being written
stale_only() {
    leftovers "$dir/int"
    set -- $left
    [ $# -le 1 ] && case "${1-}" in "" | out.$e.tmp.?????? | out.grid.vdb.tmp.??????) true ;; *) false ;; esac
}

signal_status() { case $1 in INT) echo 130 ;; KILL) echo 137 ;; esac; }

# interrupted TOOL SIGNAL: the big job, frozen and signalled during its write
interrupted() {
    previous $1
    glob="$out.tmp.??????"
    [ $1 = thin ] && glob="$grid.tmp.??????"
    run_job bg big $1 "$out" "$grid"
    freeze_and_signal $2 "$glob"
    if [ $caught = 1 ]; then
        [ $status = "$(signal_status $2)" ]
        right=$?
        ok $right "$1: SIG$2 while frozen with its temporary there: dies by it (status $status)"
        [ $right = 0 ] || sed 's/^/#   /' "$dir/job.err"
        ok "$(intact $1; echo $?)" "$1: SIG$2: the previous output is byte-identical"
    else
        echo "# $1 finished its write before SIG$2 could be sent: checked as finished"
        mkdir "$dir/int/expected"
        run_job fg big $1 "$dir/int/expected/out.$e" "$dir/int/expected/out.grid.vdb"
        [ $status = 0 ]
        right=$?
        ok $right "$1: finished before SIG$2: exit 0 (status $status)"
        [ $right = 0 ] || sed 's/^/#   /' "$dir/job.err"
        ok "$(cmp -s "$out" "$dir/int/expected/out.$e" && { [ $1 != thin ] ||
            cmp -s "$grid" "$dir/int/expected/out.grid.vdb"; }; echo $?)" \
            "$1: finished before SIG$2: its output is the new complete file"
        rm -rf "$dir/int/expected"
    fi
    leftovers "$dir/int"
    if [ $2 = KILL ] && [ $caught = 1 ]; then
        ok "$(stale_only; echo $?)" \
            "$1: SIGKILL: at most one stale temporary, named after the output (left:$left)"
    else
        ok "$([ -z "$left" ]; echo $?)" "$1: SIG$2: no temporary file left (left:$left)"
    fi
}

# injected TOOL SIGNAL: the small job under strace, SIGNAL at its first
# fsync, which is the temporary's, before the rename
injected() {
    previous $1
    run_job $2 small $1 "$out" "$grid"
    status=$?
    ok "$([ $status = "$(signal_status $2)" ]; echo $?)" \
        "$1: SIG$2 at the fsync of its temporary (strace): dies by it (status $status)"
    ok "$(intact $1; echo $?)" "$1: SIG$2 at the fsync: the previous output is byte-identical"
    leftovers "$dir/int"
    if [ $2 = KILL ]; then
        ok "$(set -- $left; [ $# = 1 ] && stale_only; echo $?)" \
            "$1: SIGKILL at the fsync: exactly one stale temporary (left:$left)"
    else
        ok "$([ -z "$left" ]; echo $?)" "$1: SIGINT at the fsync: no temporary file left (left:$left)"
    fi
}

# the big jobs' inputs
"$GB_BIN/voxelize" -q -r 96 "$scene" -o "$in/big.vdb" &&
    "$GB_BIN/reference" -q --mode direct --spp 1 --resolution 1024x1024 "$scene" \
        -o "$in/big1.exr" &&
    "$GB_BIN/reference" -q --mode direct --spp 1 --seed 1 --resolution 1024x1024 "$scene" \
        -o "$in/big2.exr" ||
    echo "# the big jobs' inputs failed: the checks below will say so"

for t in $tools; do
    for signal in INT KILL; do
        interrupted $t $signal
    done
done

if command -v strace >/dev/null 2>&1 && strace -o /dev/null -qq true 2>/dev/null; then
    for t in $tools; do
        for signal in INT KILL; do
            injected $t $signal
        done
    done
else
    echo "# strace is missing or cannot trace here: the injected signals are skipped"
    for t in $tools; do
        for i in 1 2 3 4 5 6; do skip "strace cannot run here"; done
    done
fi

tap_done
