#!/bin/sh
# install.sh — installs gibake as git installs its commands (make install):
#   PREFIX/bin/gibake-TOOL          each program of BIN, gbview included
#   PREFIX/bin/gibake               the dispatcher: `gibake thin IN.vdb -o OUT.skel`
#   PREFIX/lib/gibake/*.so          the adapters (formats/adapter.h), found
#                                   from bin/ as ../lib/gibake/
#   PREFIX/share/man/man1/gibake-TOOL.1   from TOOL --help and --version (help2man)
#   PREFIX/share/doc/gibake/FORMATS.md    every file format, byte for byte
# The bare names (thin, segment, cluster, photons, reference) would clash
# with other software in PREFIX/bin.
#
#   sh tools/install.sh BIN DEST     (DEST: $(DESTDIR)$(PREFIX))

bin=${1:?usage: install.sh BIN DEST}
dest=${2:?usage: install.sh BIN DEST}
root=$(cd "$(dirname "$0")/.." && pwd)

# The NAME line of each man page: its line of tools/tools.txt.
summary() {
    awk -v name="$1" '!/^#/ && $1 == name { sub(/^[^ ]+ +[^ ]+ +/, ""); print; found = 1 }
        END { if (!found) print "a gibake tool" }' "$root/tools/tools.txt"
}

if ! command -v help2man >/dev/null 2>&1; then
    echo "install.sh: help2man not found (Debian package help2man; make deps installs it)" >&2
    exit 1
fi
set -e
install -d "$dest/bin" "$dest/lib/gibake" "$dest/share/man/man1" "$dest/share/doc/gibake"
for program in "$bin"/*; do
    [ -x "$program" ] || continue
    name=$(basename "$program")
    install -m 755 "$program" "$dest/bin/gibake-$name"
    help2man -N --name "$(summary "$name")" --output "$dest/share/man/man1/gibake-$name.1" \
        "$program"
done
install -m 755 "$root/tools/gibake.sh" "$dest/bin/gibake"
install -m 644 "$bin"/../lib/gibake/*.so "$dest/lib/gibake"
install -m 644 "$root/formats/FORMATS.md" "$dest/share/doc/gibake"
