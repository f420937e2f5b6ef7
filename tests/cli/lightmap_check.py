#!/usr/bin/env python3
"""lightmap_check.py — readers written apart from gibake's C, for
tests/cli/lightmap.t: the .glb (JSON and BIN chunks), its PNG (zlib and the
PNG filters), the light octree (.lot, formats/FORMATS.md "Container" and
"Light octree") and the octree's irradiance (octree.h's convention, in
double, each of the 8 leaves found from the root).

    lightmap_check.py OUT.glb NAME.lot DUMP [SCENE]

DUMP: `oiiotool --dumpdata OUT.exr`; SCENE: the .scene file, whose camera
line the glTF camera is checked against. Prints, one per line:
  texels               covered texels checked (centres well inside a triangle)
  octree_max_relative  largest |EXR - irradiance| / max(irradiance, 1e-3 scale),
                       the irradiance of the brighter side (lightmap.h)
  png_relative_mse     the PNG decoded (scale x sRGB decode) against the EXR,
                       every texel: mean (a - b)^2 / (b^2 + 0.01)
  samples              triangles sampled at their centroid's TEXCOORD_1
  sample_relative_mse  the PNG against the EXR, bilinear at those points
  sample_max_relative  the largest of those |a - b| / max(b, 0.05 scale)
  camera_degrees       (with SCENE) the angle between the camera node's -Z
                       and the scene camera's view, and between their ups
  camera_offset        the distance from the node to the camera's position
  camera_fov_degrees   the glTF camera's yfov in degrees
"""
import json
import math
import struct
import sys
import zlib


def glb_chunks(path):
    data = open(path, 'rb').read()
    magic, version, length = struct.unpack_from('<III', data, 0)
    assert magic == 0x46546C67 and version == 2 and length == len(data), 'bad GLB header'
    size, kind = struct.unpack_from('<II', data, 12)
    assert kind == 0x4E4F534A, 'first chunk is not JSON'
    document = json.loads(data[20:20 + size])
    rest = 20 + size
    bin_chunk = b''
    if rest < len(data):
        bsize, bkind = struct.unpack_from('<II', data, rest)
        assert bkind == 0x004E4942, 'second chunk is not BIN'
        bin_chunk = data[rest + 8:rest + 8 + bsize]
    return document, bin_chunk


def view_bytes(document, binary, index):
    view = document['bufferViews'][index]
    start = view.get('byteOffset', 0)
    return binary[start:start + view['byteLength']]


def accessor(document, binary, index):
    a = document['accessors'][index]
    width = {'SCALAR': 1, 'VEC2': 2, 'VEC3': 3, 'VEC4': 4}[a['type']]
    code = {5126: 'f', 5125: 'I'}[a['componentType']]
    raw = view_bytes(document, binary, a['bufferView'])[a.get('byteOffset', 0):]
    values = struct.unpack_from('<%d%s' % (a['count'] * width, code), raw)
    return [values[i * width:(i + 1) * width] for i in range(a['count'])]


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else b if pb <= pc else c


def decode_png(data):
    """8-bit RGB or RGBA, not interlaced: rows of [r, g, b] bytes."""
    assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
    at, idat = 8, b''
    while at < len(data):
        size, kind = struct.unpack_from('>I4s', data, at)
        body = data[at + 8:at + 8 + size]
        if kind == b'IHDR':
            width, height, depth, colour, _, _, interlace = struct.unpack('>IIBBBBB', body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, 'unexpected PNG kind'
        elif kind == b'IDAT':
            idat += body
        at += 12 + size
    channels = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up, corner = previous[i], previous[i - channels] if i >= channels else 0
            line[i] = (line[i] + [0, left, up, (left + up) // 2, paeth(left, up, corner)][kind]) & 255
        rows.append([line[x * channels:x * channels + 3] for x in range(width)])
        previous = line
    return rows


def srgb_decode(byte):
    c = byte / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def read_dump(path):
    pixels, width, height = {}, 0, 0
    for line in open(path):
        if 'Pixel (' in line:
            head, values = line.split(':', 1)
            x, y = head.split('(')[1].rstrip(') ').split(',')
            pixels[(int(x), int(y))] = [float(v) for v in values.split()[:3]]
        elif ' x ' in line and ':' in line:
            size = line.split(':', 1)[1].split(',')[0].split(' x ')
            width, height = int(size[0]), int(size[1])
    return pixels, width, height


def container_sections(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\xabGBK\r\n\x1a\n', 'not a gibake file'
    count = struct.unpack_from('<I', data, 24)[0]
    sections = {}
    for i in range(count):
        name, offset, size = struct.unpack_from('<24sQQ', data, 32 + 48 * i)
        sections[name.rstrip(b'\0').decode()] = data[offset:offset + size]
    return sections


SURFACE_REACH = 0.25   # cell edges: light_octree_shading.h


class Octree:
    def __init__(self, path):
        s = container_sections(path)
        h = s['header']
        self.depth, nodes, leaves, vdls = struct.unpack_from('<4I', h, 0)
        self.origin = struct.unpack_from('<3f', h, 16)
        self.size = struct.unpack_from('<f', h, 28)[0]
        self.surface = struct.unpack_from('<I', h, 84)[0] == 1
        self.nodes = [struct.unpack_from('<8I', s['nodes'], 32 * i) for i in range(nodes)]
        # a leaf (format 3): packed normal, first VDL, VDL count (16 bits) and
        # plane (16, signed), packed cell
        self.leaves = [struct.unpack_from('<4I', s['leaves'], 16 * i) for i in range(leaves)]
        self.vdls = [struct.unpack_from('<3fI', s['vdls'], 16 * i) for i in range(vdls)]

    def find(self, cell):
        if any(c < 0 or c >= (1 << self.depth) for c in cell):
            return None
        index = 0
        for level in range(self.depth):
            shift = self.depth - 1 - level
            child = sum(((cell[k] >> shift) & 1) << k for k in range(3))
            index = self.nodes[index][child]
            if index == 0xFFFFFFFF:
                return None
        return index

    def leaf_light(self, leaf, n, ng):
        packed_normal, first, count_plane = self.leaves[leaf][:3]
        normal = direction(packed_normal)
        total = [0.0, 0.0, 0.0]
        for e0, e1, e2, packed in self.vdls[first:first + (count_plane & 0xFFFF)]:
            d = direction(packed)
            factor = dot(n, d) / max(abs(dot(normal, d)), 0.25)
            if factor > 0 and dot(ng, d) > 0:
                for k, e in enumerate((e0, e1, e2)):
                    total[k] += e * factor
        return total

    def surface_distance(self, leaf, offset, ng):
        packed_normal, _, count_plane = self.leaves[leaf][:3]
        normal = direction(packed_normal)
        plane = ((count_plane >> 16) ^ 0x8000) - 0x8000
        return abs(dot(normal, offset) - plane / 32767.0) + 1.0 - abs(dot(normal, ng))

    def irradiance(self, x, n, ng):
        cell = self.size / (1 << self.depth)
        g = [(x[k] - self.origin[k]) / cell - 0.5 for k in range(3)]
        base = [math.floor(v) for v in g]
        f = [g[k] - base[k] for k in range(3)]
        lit = []   # (trilinear weight, surface distance, sum) of the lit leaves
        for c in range(8):
            o = [(c >> k) & 1 for k in range(3)]
            w = max(math.prod(f[k] if o[k] else 1 - f[k] for k in range(3)), 1e-6)
            leaf = self.find([base[k] + o[k] for k in range(3)])
            if leaf is None or self.leaves[leaf][2] & 0xFFFF == 0:
                continue
            s = self.surface_distance(leaf, [f[k] - o[k] for k in range(3)], ng) \
                if self.surface else 0.0
            lit.append((w, s, self.leaf_light(leaf, n, ng)))
        nearest = min((s for _, s, _ in lit), default=0.0)
        # where no leaf holds x (nearest from half a reach to one), trilinear
        trust = min(max(2.0 - 2.0 * nearest / SURFACE_REACH, 0.0), 1.0)
        total, weight = [0.0, 0.0, 0.0], 0.0
        for w, s, light in lit:
            w *= 1.0 - trust * (1.0 - max(1.0 - (s - nearest) / SURFACE_REACH, 1e-3))
            for k in range(3):
                total[k] += w * light[k]
            weight += w
        return [t / weight if weight > 0 else 0.0 for t in total]


def dot(a, b):
    return sum(p * q for p, q in zip(a, b))


def unit(v):
    length = math.sqrt(dot(v, v))
    return [c / length for c in v] if length > 0 else list(v)


def direction(packed):
    x = ((packed & 0xFFFF) - 32768) / 32767.0
    y = ((packed >> 16) - 32768) / 32767.0
    z = 1.0 - abs(x) - abs(y)
    if z < 0:
        x, y = (1 - abs(y)) * math.copysign(1, x), (1 - abs(x)) * math.copysign(1, y)
    return unit([x, y, z])


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def triangles(document, binary):
    """Each triangle: 3 corners of (position, normal, texcoord 1)."""
    for primitive in document['meshes'][0]['primitives']:
        attributes = primitive['attributes']
        p = accessor(document, binary, attributes['POSITION'])
        n = accessor(document, binary, attributes['NORMAL'])
        t = accessor(document, binary, attributes['TEXCOORD_1'])
        indices = [i[0] for i in accessor(document, binary, primitive['indices'])]
        for k in range(0, len(indices), 3):
            yield [(p[i], n[i], t[i]) for i in indices[k:k + 3]]


def bilinear(get, width, height, u, v):
    x, y = u * width - 0.5, v * height - 0.5
    x0, y0 = math.floor(x), math.floor(y)
    ax, ay = x - x0, y - y0
    def at(i, j):
        return get(min(max(i, 0), width - 1), min(max(j, 0), height - 1))
    return [(1 - ay) * ((1 - ax) * at(x0, y0)[c] + ax * at(x0 + 1, y0)[c]) +
            ay * ((1 - ax) * at(x0, y0 + 1)[c] + ax * at(x0 + 1, y0 + 1)[c]) for c in range(3)]


def inside_texels(corners, width, height, most):
    """Up to `most` texel centres at least 0.05 texel inside, with barycentrics."""
    q = [(c[2][0] * width, c[2][1] * height) for c in corners]
    area = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0])
    found = []
    for j in range(int(min(p[1] for p in q)), int(max(p[1] for p in q)) + 1):
        for i in range(int(min(p[0] for p in q)), int(max(p[0] for p in q)) + 1):
            cx, cy = i + 0.5, j + 0.5
            w = []
            for e in range(3):
                a, b = q[(e + 1) % 3], q[(e + 2) % 3]
                w.append(((b[0] - a[0]) * (cy - a[1]) - (b[1] - a[1]) * (cx - a[0])) / area)
            edges = [math.dist(q[(e + 1) % 3], q[(e + 2) % 3]) for e in range(3)]
            if all(w[e] * abs(area) / edges[e] > 0.05 for e in range(3)):
                found.append((i, j, w))
    step = max(1, len(found) // most)
    return found[::step][:most]


def rotate(q, v):
    """v rotated by the unit quaternion q = (x, y, z, w)."""
    u, w = q[:3], q[3]
    t = [2 * c for c in cross(u, v)]
    return [v[k] + w * t[k] + cross(u, t)[k] for k in range(3)]


def check_camera(document, scene):
    words = next(line.split() for line in open(scene) if line.startswith('camera '))
    field = {words[i]: words[i + 1:i + 4] for i in range(1, len(words)) if words[i].isalpha()}
    position = [float(v) for v in field['position']]
    target = [float(v) for v in field['target']]
    up = [float(v) for v in field['up']]
    node = next(n for n in document['nodes'] if 'camera' in n)
    forward = unit([target[k] - position[k] for k in range(3)])
    right = unit(cross(forward, up))
    true_up = cross(right, forward)
    def angle(a, b):
        return math.degrees(math.acos(max(-1.0, min(1.0, dot(unit(a), unit(b))))))
    q = node['rotation']
    degrees = max(angle(rotate(q, [0, 0, -1]), forward), angle(rotate(q, [0, 1, 0]), true_up))
    offset = math.dist(node['translation'], position)
    fov = math.degrees(document['cameras'][node['camera']]['perspective']['yfov'])
    print('camera_degrees %.3g\ncamera_offset %.3g\ncamera_fov_degrees %.6g' %
          (degrees, offset, fov))


def brighter_side(octree, x, n, ng):
    """The irradiance of the brighter side of the surface at x (lightmap.h:
    a glTF lightmap holds one value a texel): each side's geometric normal,
    the shading normal turned to it."""
    best = None
    for side in (1.0, -1.0):
        g = [side * v for v in ng]
        m = n if dot(n, g) >= 0 else [-v for v in n]
        e = octree.irradiance(x, m, g)
        if best is None or sum(e) > sum(best):
            best = e
    return best


def main():
    glb, lot, dump = sys.argv[1:4]
    document, binary = glb_chunks(glb)
    pixels, width, height = read_dump(dump)
    extras = document['materials'][0]['extras']['lightmap']
    scale = extras['scale']
    image = document['images'][document['textures'][extras['texture']]['source']]
    png = decode_png(view_bytes(document, binary, image['bufferView']))
    assert len(png) == height and len(png[0]) == width, 'PNG and EXR sizes differ'
    def decoded(i, j):
        return [scale * srgb_decode(b) for b in png[j][i]]
    def exr(i, j):
        return pixels[(i, j)]

    octree, checked, worst = Octree(lot), 0, 0.0
    mesh = list(triangles(document, binary))
    for corners in mesh:
        p = [c[0] for c in corners]
        ng = unit(cross([p[1][k] - p[0][k] for k in range(3)], [p[2][k] - p[0][k] for k in range(3)]))
        for i, j, w in inside_texels(corners, width, height, 4):
            x = [sum(w[c] * p[c][k] for c in range(3)) for k in range(3)]
            n = unit([sum(w[c] * corners[c][1][k] for c in range(3)) for k in range(3)])
            expected = brighter_side(octree, x, n, ng)
            for k in range(3):
                worst = max(worst, abs(exr(i, j)[k] - expected[k]) / max(expected[k], 1e-3 * scale))
            checked += 1

    total = 0.0
    for j in range(height):
        for i in range(width):
            a, b = decoded(i, j), exr(i, j)
            total += sum((a[k] - b[k]) ** 2 / (b[k] ** 2 + 0.01) for k in range(3))
    sample_total, sample_worst = 0.0, 0.0
    for corners in mesh:
        u = sum(c[2][0] for c in corners) / 3
        v = sum(c[2][1] for c in corners) / 3
        a, b = bilinear(decoded, width, height, u, v), bilinear(exr, width, height, u, v)
        sample_total += sum((a[k] - b[k]) ** 2 / (b[k] ** 2 + 0.01) for k in range(3))
        sample_worst = max([sample_worst] + [abs(a[k] - b[k]) / max(b[k], 0.05 * scale)
                                             for k in range(3)])
    print('texels %d\noctree_max_relative %.3g' % (checked, worst))
    print('png_relative_mse %.3g' % (total / (3 * width * height)))
    print('samples %d\nsample_relative_mse %.3g\nsample_max_relative %.3g' %
          (len(mesh), sample_total / (3 * len(mesh)), sample_worst))
    if len(sys.argv) > 4:
        check_camera(document, sys.argv[4])


if __name__ == '__main__':
    main()
