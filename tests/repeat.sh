#!/bin/sh
# repeat.sh — runs each test many times and counts its failures, to show the
# suite does not flake (make test-repeat N=1000; not part of make test).
#
#   sh tests/repeat.sh N TEST...
#
# A test that runs in under a second is run N times; a slower one, and each
# CLI script (tests/cli/*.t), N/20 times (at least once). A run fails when
# the program exits non-zero or prints "not ok". The log of each failed run
# is kept as repeat-failures/NAME.RUN.log. Exits 1 if any run failed.
# GB_BIN and GB_ROOT are passed on to the tests as make check sets them.

n=${1:?usage: repeat.sh N TEST...}
shift
mkdir -p repeat-failures
total_failed=0

# Whole seconds taken by one run of the test (0 when under a second).
seconds_of_one_run() {
    start=$(date +%s.%N)
    "$1" >/dev/null 2>&1
    end=$(date +%s.%N)
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%d\n", b - a }'
}

for t in "$@"; do
    runs=$n
    case "$t" in
    *.t) runs=$((n / 20)) ;;
    *) [ "$(seconds_of_one_run "$t")" -ge 1 ] && runs=$((n / 20)) ;;
    esac
    [ "$runs" -ge 1 ] || runs=1
    failed=0
    i=1
    while [ $i -le $runs ]; do
        log=repeat-failures/$(basename "$t").$i.log
        if "$t" >"$log" 2>&1 && ! grep -q '^not ok' "$log"; then
            rm -f "$log"
        else
            failed=$((failed + 1))
        fi
        i=$((i + 1))
    done
    echo "$(basename "$t"): $failed failed of $runs runs"
    total_failed=$((total_failed + failed))
done
rmdir repeat-failures 2>/dev/null
[ $total_failed = 0 ]
