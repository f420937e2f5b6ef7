#!/bin/sh
# cli.t — the command line every tool shares (common/cli.h), as a user types
# it: a bad value is one line in one format and the Try line, exit 2; an
# unknown option is one line naming it and the Try line (no help dumped, no
# path of the binary), exit 2; --help and --version on stdout, exit 0; a
# short letter means the same option in every tool.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=

tools="voxelize thin segment photons cluster reference imgdiff scene-info gbview"
needs $tools atlas lightmap

# usage_error WHAT TOOL LINE ARGS...: TOOL ARGS exits 2 with exactly LINE and
# the Try line on stderr, nothing on stdout.
usage_error() {
    what=$1 name=$2 line=$3
    shift 3
    "$GB_BIN/$name" "$@" >"$dir/out" 2>"$dir/err"
    status=$?
    printf '%s\nTry '\''%s --help'\'' for more information.\n' "$line" "$name" >"$dir/want"
    ok "$([ $status = 2 ]; echo $?)" "$name $what: exit status 2 (got $status)"
    ok "$(cmp -s "$dir/want" "$dir/err"; echo $?)" \
        "$name $what: stderr is '$line' and the Try line (got '$(head -n 1 "$dir/err")')"
    ok "$([ ! -s "$dir/out" ]; echo $?)" "$name $what: nothing on stdout"
}

# A bad integer value: the one format, whatever the tool (imgdiff takes
# numbers only, scene-info no value at all).
usage_error "--resolution abc" voxelize \
    "voxelize: --resolution: 'abc' is not an integer in 1..2048" --resolution abc x.obj
usage_error "--threads 0" thin "thin: --threads: '0' is not an integer in 1..64" \
    --threads 0 x.vdb -o x.skel
usage_error "--pairs 0" segment "segment: --pairs: '0' is not an integer in 1..4294967295" \
    --evaluate --pairs 0 x.scene x.seg x.vdb
usage_error "--bounces 0" photons "photons: --bounces: '0' is not an integer in 1..255" \
    --bounces 0 x.obj -o x.phot
usage_error "--depth 11" cluster "cluster: --depth: '11' is not an integer in 1..10" \
    --depth 11 x.obj x.phot -o x.lot
usage_error "--spp 1.5" reference \
    "reference: --spp: '1.5' is not an integer in 1..1073741824" --spp 1.5 x.obj -o x.exr
usage_error "--bins 0" gbview "gbview: --bins: '0' is not an integer in 1..64" --bins 0 x.obj
usage_error "--fail-above -1" imgdiff \
    "imgdiff: --fail-above: '-1' is not a number in [0, 1e+30]" --fail-above -1 a.png b.png

# Strict decimal integers: no sign but '-', no space, no overflow.
usage_error "-r +5" voxelize "voxelize: --resolution: '+5' is not an integer in 1..2048" \
    -r +5 x.obj
usage_error "-r ' 5'" voxelize "voxelize: --resolution: ' 5' is not an integer in 1..2048" \
    -r " 5" x.obj
usage_error "--seed 2^64" segment \
    "segment: --seed: '18446744073709551616' is not an integer in 0..18446744073709551615" \
    --seed 18446744073709551616 x.skel -o x.seg
usage_error "--camera 99999999999999999999" gbview \
    "gbview: --camera: '99999999999999999999' is not an integer in 0..1073741824" \
    --camera 99999999999999999999 x.obj
# Numbers: finite and in range.
usage_error "--persistence nan" thin "thin: --persistence: 'nan' is not a number in [0, 1e+06]" \
    --persistence nan x.vdb -o x.skel
usage_error "--heatmap-scale inf" imgdiff \
    "imgdiff: --heatmap-scale: 'inf' is not a number in [1e-30, 1e+30]" \
    --heatmap-scale inf a.png b.png
usage_error "--alpha 101" segment "segment: --alpha: '101' is not a number in [0, 100]" \
    --alpha 101 x.skel -o x.seg
# One --resolution WxH, one largest side, in reference and gbview.
usage_error "--resolution 0x5" reference \
    "reference: --resolution: '0x5' is not WxH with each side in 1..16384" \
    --resolution 0x5 x.obj -o x.exr
usage_error "--resolution 16385x16" reference \
    "reference: --resolution: '16385x16' is not WxH with each side in 1..16384" \
    --resolution 16385x16 x.obj -o x.exr
usage_error "--resolution 16x16385" gbview \
    "gbview: --resolution: '16x16385' is not WxH with each side in 1..16384" \
    --resolution 16x16385 x.obj
"$GB_BIN/reference" --resolution 16384x1 "$dir/missing.obj" -o "$dir/x.exr" 2>"$dir/err"
ok "$([ $? = 1 ]; echo $?)" "reference --resolution 16384x1: accepted (fails later on the scene)"
# I/N and choices.
usage_error "--shard 4/4" photons "photons: --shard: '4/4' is not I/N with I in 0..N-1" \
    --shard 4/4 x.obj -o x.phot
usage_error "--shard 1/" photons "photons: --shard: '1/' is not I/N with I in 0..N-1" \
    --shard 1/ x.obj -o x.phot
usage_error "--store some" photons "photons: --store: 'some' is not one of indirect, all" \
    --store some x.obj -o x.phot
usage_error "--terms half" gbview "gbview: --terms: 'half' is not one of both, direct, indirect" \
    --terms half x.obj

# Unknown options, missing values: one line naming the option, the Try line.
for name in $tools; do
    usage_error "--no-such-option" "$name" "$name: unknown option '--no-such-option'" \
        --no-such-option
    usage_error "-Z" "$name" "$name: unknown option '-Z'" -Z
    ok "$(! grep -q -e "$GB_BIN" -e "^usage:" "$dir/err"; echo $?)" \
        "$name -Z: neither the binary's path nor the help on stderr"
    usage_error "--quiet=1" "$name" "$name: option '--quiet' takes no value" --quiet=1
done
usage_error "--output" voxelize "voxelize: option '--output' needs a value" x.obj --output
usage_error "-o" thin "thin: option '-o' needs a value" x.vdb -o
usage_error "--s" reference "reference: option '--s' is ambiguous" --s 4 x.obj -o x.exr
usage_error "-qx" photons "photons: unknown option '-x'" -qx x.obj -o x.phot

# A missing argument is a usage error in every tool (thin and segment too).
usage_error "with no -o" thin "thin: expected one IN.vdb and -o OUT.skel" x.vdb
usage_error "with no -o" segment "segment: expected one IN.skel and -o OUT.seg" x.skel
usage_error "with no SCENE" scene-info "scene-info: expected one SCENE"
usage_error "with one image" imgdiff "imgdiff: expected IMAGE and REFERENCE" a.png

# --help and --version: stdout, exit 0, nothing on stderr.
for name in $tools; do
    "$GB_BIN/$name" --help >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ $status = 0 ] && grep -q "^usage: $name " "$dir/out" && [ ! -s "$dir/err" ]; echo $?)" \
        "$name --help: the usage on stdout, exit 0 (got $status)"
    "$GB_BIN/$name" --version >"$dir/out" 2>"$dir/err"
    status=$?
    ok "$([ $status = 0 ] && [ "$(cat "$dir/out")" = "$name (gibake) 0.1" ] &&
        [ ! -s "$dir/err" ]; echo $?)" "$name --version: '$name (gibake) 0.1', exit 0 (got $status)"
done

# One letter, one option, across the toolchain: every "-X, --long" line of
# every tool's --help, the letters gathered over all of them; a letter
# naming two long options in two tools is a failure (threads were -j in
# some and -t in others, -s was --stats here and --spp there).
for name in $tools atlas lightmap; do
    "$GB_BIN/$name" --help | sed -n "s/^ *-\([A-Za-z]\), --\([a-z-]*\).*/\1 \2 $name/p"
done >"$dir/letters"
clashes=$(sort -u -k1,2 "$dir/letters" | awk '{ if ($1 == last) print $1; last = $1 }' | sort -u |
    tr '\n' ' ')
ok "$([ -s "$dir/letters" ] && [ -z "$clashes" ]; echo $?)" \
    "each short letter names one long option in every tool${clashes:+ (not: $clashes)}"
ok "$(grep -q '^j threads photons$' "$dir/letters" && grep -q '^j threads thin$' "$dir/letters" &&
    grep -q '^s stats reference$' "$dir/letters"; echo $?)" \
    "threads are -j and --stats is -s (photons, thin, reference)"

tap_done
