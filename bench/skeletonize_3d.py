#!/usr/bin/python3
"""skeletonize_3d.py — the peer bench/thin.sh measures thin against:
scikit-image's skeletonize_3d (Lee et al. 1994) on the empty space of a
voxelize .vdb (formats/FORMATS.md, "Voxel file").

Usage: skeletonize_3d.py FILE.vdb

Prints one line:
    empty E skeleton S wall_s W cpu_s C
E: empty voxels of the grid; S: voxels of the skeleton skeletonize_3d
leaves; W and C: seconds of the skeletonize_3d call alone, wall
(time.perf_counter) and CPU of the process (time.process_time, user +
system). Reading the file and building the array are not counted.

The array is dense, of exactly grid_size (metadata of the grids), index
(i, j, k) = OpenVDB coordinate (i, j, k), True on the empty voxels: the
voxels thin thins (thin reads the dense "surface" array and makes a cube of
every voxel that is not surface; tools/thin/cubical_complex.c). pyopenvdb 10
cannot read mask grids, so the grid "empty" (Tree_mask_5_4_3) is not read:
the empty voxels are taken as the complement of "surface" inside grid_size,
which is what the format defines "empty" to be (and what gibake's reader
checks); the count is checked against the active voxels of "distance",
which the format makes active exactly on the empty voxels.

Needs the Debian packages python3-skimage and python3-openvdb, which serve
Debian's /usr/bin/python3 (not a pyenv or venv python). Exit status 1 on
any error, with the reason on stderr.
"""

import sys
import time


def fail(message):
    sys.stderr.write("skeletonize_3d.py: %s\n" % message)
    sys.exit(1)


def main(argv):
    if len(argv) != 2 or argv[1].startswith("-"):
        sys.stderr.write("usage: skeletonize_3d.py FILE.vdb\n")
        return 1
    path = argv[1]
    missing = []
    try:
        import numpy
    except ImportError:
        missing.append("numpy")
    try:
        import pyopenvdb
    except ImportError:
        missing.append("pyopenvdb")
    try:
        from skimage.morphology import skeletonize_3d
    except ImportError:
        missing.append("skimage")
    if missing:
        fail("no module %s in %s: install python3-skimage python3-openvdb "
             "(apt-get install -y python3-skimage python3-openvdb) and run "
             "with /usr/bin/python3" % (", ".join(missing), sys.executable))

    try:
        surface = pyopenvdb.read(path, "surface")
        distance = pyopenvdb.read(path, "distance")
    except Exception as error:  # pyopenvdb raises KeyError, IOError, TypeError ...
        fail("%s: %s" % (path, error))
    if not isinstance(surface, pyopenvdb.BoolGrid):
        fail("%s: grid 'surface' is not a bool grid" % path)
    size = surface.metadata.get("grid_size")
    if (size is None or len(size) != 3 or any(int(n) < 1 for n in size)
            or distance.metadata.get("grid_size") != size):
        fail("%s: no grid_size, or not the same on 'surface' and 'distance'" % path)
    size = tuple(int(n) for n in size)

    is_surface = numpy.zeros(size, dtype=bool)
    surface.copyToArray(is_surface, ijk=(0, 0, 0))
    if int(is_surface.sum()) != surface.activeVoxelCount():
        fail("%s: grid 'surface' has active voxels outside grid_size "
             "or inactive true voxels" % path)
    empty = numpy.logical_not(is_surface)
    del is_surface
    empty_count = int(empty.sum())
    if empty_count != distance.activeVoxelCount():
        fail("%s: %d voxels are not surface but 'distance' has %d active voxels"
             % (path, empty_count, distance.activeVoxelCount()))
    del surface, distance

    wall = time.perf_counter()
    cpu = time.process_time()
    skeleton = skeletonize_3d(empty)
    cpu = time.process_time() - cpu
    wall = time.perf_counter() - wall

    print("empty %d skeleton %d wall_s %.3f cpu_s %.3f"
          % (empty_count, int(numpy.count_nonzero(skeleton)), wall, cpu))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
