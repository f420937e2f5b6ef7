#!/bin/sh
# gibake — runs the gibake tool named first, installed beside this script as
# gibake-TOOL (tools/install.sh): `gibake thin IN.vdb -o OUT.skel`.

here=$(dirname "$(readlink -f "$0")")
tools() {
    for t in "$here"/gibake-*; do [ -x "$t" ] && printf '  %s\n' "${t##*/gibake-}"; done
}
case $1 in
'' | -h | --help)
    if [ -z "$1" ]; then exec >&2; fi
    echo "usage: gibake TOOL [ARGS...]; gibake TOOL --help for its options. The tools:"
    tools
    [ -n "$1" ] && exit 0
    exit 2 ;;
esac
tool=$1
shift
if [ ! -x "$here/gibake-$tool" ]; then
    echo "gibake: '$tool' is not a gibake tool" >&2
    echo "Try 'gibake --help' for the list." >&2
    exit 2
fi
exec "$here/gibake-$tool" "$@"
