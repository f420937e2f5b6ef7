#!/bin/sh
# install.t — make install's layout (tools/install.sh) into a scratch
# folder: gibake-TOOL for every program, the gibake dispatcher, the adapters
# found from the installed bin/, a man page per program made from its
# --help, FORMATS.md. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"

if ! command -v help2man >/dev/null 2>&1; then
    missing "help2man (Debian help2man): the man pages"
    tap_done
    exit 1
fi
dest=$dir/usr
sh "$GB_ROOT/tools/install.sh" "$GB_BIN" "$dest" >"$dir/out" 2>"$dir/err"
ok $? "tools/install.sh BIN DEST: exit 0 ($(head -1 "$dir/err"))"

programs=0
for program in "$GB_BIN"/*; do
    [ -x "$program" ] || continue
    name=$(basename "$program")
    programs=$((programs + 1))
    cmp -s "$program" "$dest/bin/gibake-$name" && [ -x "$dest/bin/gibake-$name" ] &&
        [ ! -e "$dest/bin/$name" ]
    ok $? "$name installed as bin/gibake-$name, not under its bare name"
    page=$dest/share/man/man1/gibake-$name.1
    upper=$(echo "$name" | tr a-z A-Z)
    grep -q "^\.TH $upper \"1\"" "$page" && grep -q '^\.SH NAME' "$page" &&
        grep -qF '\-\-help' "$page" && grep -qF '\-\-version' "$page"
    ok $? "man page gibake-$name.1: its NAME and the --help and --version options"
done
[ "$programs" -ge 9 ]
ok $? "9 programs or more installed ($programs)"

"$dest/bin/gibake" thin --version >"$dir/out" 2>&1
[ $? = 0 ] && grep -qx 'thin (gibake) [0-9.]*' "$dir/out"
ok $? "gibake thin --version runs gibake-thin ($(cat "$dir/out"))"
"$dest/bin/gibake" --help >"$dir/out" 2>&1
[ $? = 0 ] && [ "$(grep -c '^  ' "$dir/out")" = "$programs" ]
ok $? "gibake --help: exit 0, lists the $programs tools"
"$dest/bin/gibake" nosuch >"$dir/out" 2>"$dir/err"
status=$?
[ $status = 2 ] && grep -qx "gibake: 'nosuch' is not a gibake tool" "$dir/err" && [ ! -s "$dir/out" ]
ok $? "gibake nosuch: exit 2 and one line naming it (status $status)"
"$dest/bin/gibake" >"$dir/out" 2>"$dir/err"
[ $? = 2 ] && grep -q '^usage: gibake TOOL' "$dir/err"
ok $? "gibake alone: the usage on stderr, exit 2"

# The adapters, found from the installed bin/ as ../lib/gibake/.
printf 'P3\n2 1\n255\n100 100 100 0 0 0\n' >"$dir/a.ppm"
"$dest/bin/gibake" imgdiff "$dir/a.ppm" "$dir/a.ppm" >"$dir/out" 2>"$dir/err"
[ $? = 0 ] && grep -q '^pixels 2$' "$dir/out"
ok $? "the installed imgdiff loads its adapter from lib/gibake/ ($(head -1 "$dir/err"))"
"$dest/bin/gibake" voxelize -q -r 8 "$GB_ROOT/scenes/cornell/cornell.scene" -o "$dir/box.vdb" &&
    "$dest/bin/gibake-thin" -q "$dir/box.vdb" -o "$dir/box.skel" && [ -s "$dir/box.skel" ]
ok $? "the installed voxelize and thin write and read a .vdb"
cmp -s "$GB_ROOT/formats/FORMATS.md" "$dest/share/doc/gibake/FORMATS.md"
ok $? "FORMATS.md in share/doc/gibake"

tap_done
