#!/usr/bin/env python3
"""subdivide_obj.py -- a large scene for bench/viewer.sh, made from a shared
one: each triangle of an OBJ split into 4 at its edges' midpoints, ROUNDS
times (4^ROUNDS triangles each), positions, texture coordinates and normals
interpolated, materials kept. The look is the source's; only the triangle
count grows (Sponza's 66 450, three rounds: 4.25 M).

usage: subdivide_obj.py SOURCE.obj ROUNDS OUT.obj
The output names the source's mtllib by its file name: link or copy the
source's .mtl and textures beside it (bench/viewer.sh links them).
"""
import sys


def parse_corner(token):
    parts = token.split("/")
    indices = [int(p) if p else 0 for p in parts] + [0, 0]
    return indices[0], indices[1], indices[2]


def resolve(index, count):
    """OBJ's 1-based or negative index, as 0-based."""
    return index - 1 if index > 0 else count + index


class Mesh:
    def __init__(self):
        self.lists = {"v": [], "vt": [], "vn": []}
        self.midpoints = {}

    def midpoint(self, kind, a, b):
        if a < 0 or b < 0:
            return -1
        key = (kind, min(a, b), max(a, b))
        found = self.midpoints.get(key)
        if found is None:
            values = self.lists[kind]
            values.append(tuple(0.5 * (x + y) for x, y in zip(values[a], values[b])))
            found = len(values) - 1
            self.midpoints[key] = found
        return found

    def split(self, triangle):
        """The four triangles of one: corners (v, vt, vn) 0-based, -1 absent."""
        a, b, c = triangle
        mids = []
        for p, q in ((a, b), (b, c), (c, a)):
            mids.append(tuple(self.midpoint(k, p[i], q[i]) for i, k in enumerate(("v", "vt", "vn"))))
        ab, bc, ca = mids
        return [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]


def corner_text(corner):
    """v, v/vt, v//vn or v/vt/vn, 1-based."""
    v, vt, vn = (i + 1 for i in corner)
    if vn > 0:
        return "%d/%s/%d" % (v, vt if vt > 0 else "", vn)
    return "%d/%d" % (v, vt) if vt > 0 else "%d" % v


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    source, rounds, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    mesh = Mesh()
    groups = []          # (usemtl or None, [triangles])
    mtllibs = []
    current = None
    with open(source, errors="replace") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            key = words[0]
            if key in mesh.lists:
                mesh.lists[key].append(tuple(float(x) for x in words[1:4 if key != "vt" else 3]))
            elif key == "mtllib":
                mtllibs.append(" ".join(words[1:]).split("/")[-1])
            elif key == "usemtl" or current is None:
                current = (words[1] if key == "usemtl" and len(words) > 1 else None, [])
                groups.append(current)
            if key == "f":
                counts = [len(mesh.lists[k]) for k in ("v", "vt", "vn")]
                corners = []
                for token in words[1:]:
                    raw = parse_corner(token)
                    corners.append(tuple(resolve(i, n) if i else -1 for i, n in zip(raw, counts)))
                for i in range(1, len(corners) - 1):
                    current[1].append((corners[0], corners[i], corners[i + 1]))
    for _ in range(rounds):
        for g, (name, triangles) in enumerate(groups):
            groups[g] = (name, [t for old in triangles for t in mesh.split(old)])
    with open(out, "w") as f:
        f.write("# %s, each triangle split in 4 %d times (bench/subdivide_obj.py)\n" % (source, rounds))
        for lib in mtllibs:
            f.write("mtllib %s\n" % lib)
        for key, fmt in (("v", "v %.6g %.6g %.6g\n"), ("vt", "vt %.6g %.6g\n"), ("vn", "vn %.6g %.6g %.6g\n")):
            f.writelines(fmt % value for value in mesh.lists[key])
        triangles = 0
        for name, group in groups:
            if name:
                f.write("usemtl %s\n" % name)
            for t in group:
                f.write("f %s\n" % " ".join(corner_text(c) for c in t))
            triangles += len(group)
    print("%s: %d triangles" % (out, triangles))


main()
