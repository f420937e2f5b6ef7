# common.sh — the helpers the bench/*.sh share. A bench script sources it
# first (`. "$(dirname "$0")/common.sh"`). Sourcing sets
#   root                 the repository (bench/..), absolute
#   GB_BIN               the tools (default $root/build/bin)
#   BENCH_BIN            the bench programs, bench/*.c built by the Makefile
#                        (default build/bench beside GB_BIN)
#   dir                  a scratch folder, gibake-bench-NAME.XXXXXX for
#                        NAME.sh, removed at exit
#
#   needs TOOL...        exits unless each TOOL is built in $GB_BIN
#   bench_program NAME   prints $BENCH_BIN/NAME; fails unless it is built
#   value KEY FILE       the value of the line "KEY value" of FILE (--stats,
#                        imgdiff, the bench programs)
#   relative_mse A B     imgdiff's relative MSE of image A against image B
#   scene_entry ENTRY    splits ENTRY, PATH:EMITTED:ERROR-SIZE:SPP (PATH under
#                        scenes/), into path, emitted, error_size and spp; sets
#                        scene (the file), name (its base name) and bake
#                        ($dir/NAME, made)
#
# make bench runs every bench/*.sh: run on its own, this file does nothing.

case $0 in
common.sh | */common.sh) exit 0 ;;
esac

root=$(cd "$(dirname "$0")/.." && pwd)
GB_BIN=${GB_BIN:-$root/build/bin}
BENCH_BIN=${BENCH_BIN:-$(dirname "$GB_BIN")/bench}
dir=$(mktemp -d "${TMPDIR:-/tmp}/gibake-bench-$(basename "$0" .sh).XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM

needs() {
    for needed in "$@"; do
        if [ ! -x "$GB_BIN/$needed" ]; then
            echo "$(basename "$0"): $GB_BIN/$needed not built"
            exit 1
        fi
    done
}

bench_program() {
    if [ ! -x "$BENCH_BIN/$1" ]; then
        echo "$(basename "$0"): $BENCH_BIN/$1 not built: run make bench" >&2
        return 1
    fi
    echo "$BENCH_BIN/$1"
}

value() {
    sed -n "s/^$1 //p" "$2"
}

relative_mse() {
    "$GB_BIN/imgdiff" "$1" "$2" | value relative_mse -
}

scene_entry() {
    path=${1%%:*}
    rest=${1#*:}
    emitted=${rest%%:*}
    rest=${rest#*:}
    error_size=${rest%%:*}
    spp=${rest#*:}
    scene=$root/scenes/$path
    name=$(basename "$scene" .scene)
    bake=$dir/$name
    mkdir -p "$bake"
}
