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

# The NAME line of each man page.
summary() {
    case $1 in
    scene-info) echo "print what gibake sees in a scene" ;;
    voxelize) echo "voxelize a scene into an OpenVDB file of surfaces, empty space and distances" ;;
    thin) echo "the curvilinear skeleton of a voxelized scene's empty space" ;;
    segment) echo "visibility clusters and gates of a skeleton" ;;
    photons) echo "trace the photon map of a scene with Embree" ;;
    cluster) echo "the light octree of a scene from its photon map" ;;
    reference) echo "render the ground truth of a scene with Embree" ;;
    imgdiff) echo "how far an image is from a reference" ;;
    gbview) echo "show a scene and its baked global illumination, or render it headless" ;;
    *) echo "a gibake tool" ;;
    esac
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
