# x_session.sh — a virtual X display with a window manager, for what drives
# gbview's window as a user would (tests/cli/window.t, bench/viewer.sh).
# Sourced; needs Debian's xvfb, openbox and xdotool (make deps).
#
#   x_start              starts Xvfb on a free display and openbox on it,
#                        and waits for openbox; exports DISPLAY; x_stop
#                        (also at exit) ends both
#   wait_for PATTERN FILE [SECONDS]
#                        waits until a line of FILE matches PATTERN (grep -E);
#                        false after SECONDS (default 120): a limit against a
#                        hang, never a measure
#   count_lines PATTERN FILE
#                        how many lines of FILE match PATTERN
#   gbview_window        the window id of gbview, waiting for it to map
#   wait_for_title WINDOW PATTERN [SECONDS]
#                        waits until WINDOW's title matches PATTERN (grep -E)

x_pids=

x_start() {
    x_fd_file=$(mktemp)
    Xvfb -displayfd 1 -screen 0 1280x800x24 -nolisten tcp >"$x_fd_file" 2>/dev/null &
    x_pids="$!"
    wait_for '^[0-9]+$' "$x_fd_file" 30 || return 1
    DISPLAY=:$(head -1 "$x_fd_file")
    export DISPLAY
    rm -f "$x_fd_file"
    # A window made while the window manager starts can wait for events
    # that never come: go on once openbox says it is up.
    x_wm_ready=$(mktemp -u)
    openbox --startup "touch $x_wm_ready" >/dev/null 2>&1 &
    x_pids="$x_pids $!"
    trap 'x_stop' EXIT
    waited=0
    until [ -e "$x_wm_ready" ]; do
        [ "$waited" -ge 300 ] && return 1
        sleep 0.1
        waited=$((waited + 1))
    done
    rm -f "$x_wm_ready"
}

x_stop() {
    [ -n "$x_pids" ] && kill $x_pids 2>/dev/null
    x_pids=
    [ -z "$dir" ] || [ -n "$GB_KEEP" ] || rm -rf "$dir"
}

wait_for() {
    waited=0
    while ! grep -Eq "$1" "$2" 2>/dev/null; do
        [ "$waited" -ge "$((${3:-120} * 10))" ] && return 1
        sleep 0.1
        waited=$((waited + 1))
    done
}

wait_for_title() {
    waited=0
    until xdotool getwindowname "$1" 2>/dev/null | grep -Eq "$2"; do
        [ "$waited" -ge "$((${3:-120} * 10))" ] && return 1
        sleep 0.1
        waited=$((waited + 1))
    done
}

count_lines() {
    grep -Ec "$1" "$2" 2>/dev/null
}

gbview_window() {
    timeout 300 xdotool search --sync --onlyvisible --name '^gbview ' 2>/dev/null | head -1
}
