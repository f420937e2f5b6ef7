# tap.sh — the TAP helpers every tests/cli/*.t shares; a .t sources it
# (`. "$(dirname "$0")/tap.sh"`) after setting $tool (the program under
# test) and $dir (its scratch folder), and ends with `tap_done`.
#
#   ok STATUS WHAT       one check, passed when STATUS is 0
#   missing WHAT         one failed check: a program or package the test needs
#                        is absent (make test installs them all, so in CI this
#                        never hides a result: it fails)
#   value KEY FILE       the value of the line "KEY value" of FILE
#   below A B            true when the number A is below B (either empty: false)
#   expect_failure WHAT STATUS PATTERN ARGS...
#                        runs $tool ARGS: two checks, exit status STATUS
#                        and PATTERN (grep) on stderr
#   tap_done             prints the plan; returns nonzero if a check failed

count=0
failed=0

ok() {
    count=$((count + 1))
    if [ "$1" = 0 ]; then
        echo "ok $count - $2"
    else
        failed=$((failed + 1))
        echo "not ok $count - $2"
    fi
}

missing() {
    ok 1 "missing: $1"
}

value() {
    sed -n "s/^$1 //p" "$2"
}

below() {
    awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && b != "" && a + 0 < b + 0) }'
}

expect_failure() {
    what=$1 want=$2 pattern=$3
    shift 3
    "$tool" "$@" >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ $status = "$want" ]; echo $?)" "$what: exit status $want (got $status)"
    ok "$(grep -q "$pattern" "$dir/err"; echo $?)" "$what: says '$pattern' on stderr"
}

tap_done() {
    echo "1..$count"
    [ $failed = 0 ]
}
