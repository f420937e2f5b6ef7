#!/bin/sh
# shared_options.t — the options every tool shares (common/cli.h,
# gb_cli_shared): a tool whose --help lists one rejects a bad value of it
# the same way as every other tool, and a tool that does not list it
# refuses it as unknown. Asserted against cli.h's spec, not against a
# tool's own text:
#   -j, --threads N   1..HIGH (HIGH the tool's), "is not an integer in 1..HIGH"
#   --seed N          0..UINT64_MAX
#   -s, --stats       a flag: "option '--stats' takes no value"
#   --depfile FILE    "option '--depfile' needs a value"
#   -q, --quiet       in every tool; -h and -V the help's last two lines
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"

tools="voxelize thin segment photons cluster atlas lightmap reference imgdiff scene-info"
needs $tools

# refused WHAT TOOL PATTERN ARGS...: TOOL ARGS exits 2, its stderr is one
# line matching PATTERN (grep -E, anchored) and the Try line, no stdout.
refused() {
    what=$1 name=$2 pattern=$3
    shift 3
    "$GB_BIN/$name" "$@" >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ $status = 2 ]; echo $?)" "$name $what: exit status 2 (got $status)"
    ok "$([ "$(wc -l <"$dir/err")" = 2 ] && head -n 1 "$dir/err" | grep -Eqx "$name: $pattern" &&
          tail -n 1 "$dir/err" | grep -Fqx "Try '$name --help' for more information."; echo $?)" \
        "$name $what: '$name: $pattern' and the Try line (got '$(head -n 1 "$dir/err")')"
    ok "$([ ! -s "$dir/out" ]; echo $?)" "$name $what: nothing on stdout"
}

# lists TOOL LEFT: TOOL's --help has a line starting with LEFT then spaces.
lists() {
    "$GB_BIN/$1" --help | grep -Eq "^$2 +[^ ]"
}

for name in $tools; do
    if lists "$name" '  -j, --threads N'; then
        refused "--threads 0" "$name" "--threads: '0' is not an integer in 1\.\.[1-9][0-9]*" \
            --threads 0
        high=$(head -n 1 "$dir/err" | sed 's/.*1\.\.//')
        case $high in '' | *[!0-9]*) high=0 ;; esac    # refused above already failed
        refused "-j x" "$name" "--threads: 'x' is not an integer in 1\.\.$high" -j x
        refused "--threads HIGH+1" "$name" \
            "--threads: '$((high + 1))' is not an integer in 1\.\.$high" --threads $((high + 1))
    else
        refused "--threads (not listed)" "$name" "unknown option '--threads'" --threads 1
    fi
    if lists "$name" '      --seed [A-Z]+'; then
        refused "--seed -1" "$name" \
            "--seed: '-1' is not an integer in 0\.\.18446744073709551615" --seed -1
        refused "--seed 2^64" "$name" \
            "--seed: '18446744073709551616' is not an integer in 0\.\.18446744073709551615" \
            --seed 18446744073709551616
    else
        refused "--seed (not listed)" "$name" "unknown option '--seed'" --seed 1
    fi
    if lists "$name" '  -s, --stats'; then
        refused "--stats=1" "$name" "option '--stats' takes no value" --stats=1
    else
        refused "--stats (not listed)" "$name" "unknown option '--stats'" --stats
    fi
    if lists "$name" '      --depfile FILE'; then
        refused "--depfile alone" "$name" "option '--depfile' needs a value" --depfile
    else
        refused "--depfile (not listed)" "$name" "unknown option '--depfile'" --depfile x
    fi
    lists "$name" '  -q, --quiet'
    ok $? "$name --help lists -q, --quiet"
    "$GB_BIN/$name" --help | tail -n 2 | sed 's/  */ /g' >"$dir/last"
    printf ' -h, --help this help\n -V, --version the version\n' >"$dir/want"
    ok "$(cmp -s "$dir/want" "$dir/last"; echo $?)" "$name --help ends with -h and -V"
done

tap_done
