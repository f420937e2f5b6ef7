#!/bin/sh
# atlas.t — the atlas tool as a user types it, on the Cornell box: a file
# that an independent reader here (Python: the container's CRCs, the
# header, every UV in [0, 1], every triangle counterclockwise with a
# positive area, every chart index in range, triangles of different charts
# at least twice the padding apart along x or y) and
# gb_atlas_read (through the lightmap tool) accept;
# --stats; the same bytes on a second run; usage errors; nothing left by
# a failed run. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/atlas
scene=$GB_ROOT/scenes/cornell/cornell.scene

needs atlas scene-info photons cluster lightmap

# ---- a run ----
"$tool" --quiet --stats "$scene" -o "$dir/box.atlas" >"$dir/stats" 2>"$dir/err"
ok $? "atlas: exit status 0"
[ -s "$dir/box.atlas" ] && [ ! -s "$dir/err" ]
ok $? "... writes the atlas, nothing on stderr with --quiet"

charts=$(value charts "$dir/stats")
ok "$([ "${charts:-0}" -ge 16 ]; echo $?)" "--stats: charts ($charts) at least the box's 16 quads"
fill=$(value fill_ratio "$dir/stats")
ok "$(awk -v f="$fill" 'BEGIN { exit !(f > 0.5 && f <= 1) }'; echo $?)" \
    "--stats: fill ratio ($fill) in (0.5, 1]"
for key in max_angle_distortion mean_angle_distortion seconds; do
    v=$(value $key "$dir/stats")
    ok "$(awk -v v="$v" 'BEGIN { exit !(v != "" && v + 0 >= 0) }'; echo $?)" "--stats: $key ($v)"
done
ok "$(awk -v v="$(value max_angle_distortion "$dir/stats")" 'BEGIN { exit !(v + 0 < 0.01) }'; \
    echo $?)" "--stats: the box's flat quads keep their angles"
ok "$([ "$(value size "$dir/stats")" = 1024x1024 ]; echo $?)" "--stats: the default size, 1024x1024"

triangles=$("$GB_BIN/scene-info" "$scene" 2>/dev/null | sed -n 's/^triangles  *//p')

# check_atlas FILE TRIANGLES: the file read apart from gibake's reader.
check_atlas() {
    python3 - "$1" "$2" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
expected_triangles = int(sys.argv[2])
def fail(what):
    print("# " + what)
    sys.exit(1)
if data[:8] != b"\xabGBK\r\n\x1a\n" or data[8:12] != b"ATLS":
    fail("not an ATLS container")
count = struct.unpack_from("<I", data, 24)[0]
if zlib.crc32(data[:28] + data[32:32 + 48 * count]) != struct.unpack_from("<I", data, 28)[0]:
    fail("header CRC")
sections = {}
for i in range(count):
    name, offset, size, crc = struct.unpack_from("<24sQQI", data, 32 + 48 * i)
    payload = data[offset:offset + size]
    if zlib.crc32(payload) != crc:
        fail("CRC of a section")
    sections[name.rstrip(b"\0").decode()] = payload
h = sections["header"]
_, T, C, W, H, density, P = struct.unpack_from("<QIIIIfI", h, 0)
if T != expected_triangles or not 1 <= C <= T or density <= 0:
    fail("header: %d triangles, %d charts" % (T, C))
uv = struct.unpack("<%df" % (6 * T), sections["uvs"])
chart = struct.unpack("<%dI" % T, sections["charts"])
records = [struct.unpack_from("<IfffIIII", sections["chart_records"], 32 * c) for c in range(C)]
for t in range(T):
    q = uv[6 * t:6 * t + 6]
    if not all(0.0 <= x <= 1.0 for x in q):
        fail("triangle %d: a UV outside [0, 1]" % t)
    if (q[2] - q[0]) * (q[5] - q[1]) - (q[3] - q[1]) * (q[4] - q[0]) <= 0:
        fail("triangle %d: not counterclockwise" % t)
    if chart[t] >= C:
        fail("triangle %d: chart out of range" % t)
    x, y, w, hh = records[chart[t]][4:8]
    for k in range(3):
        if not (x - 1e-3 <= q[2 * k] * W <= x + w + 1e-3 and y - 1e-3 <= q[2 * k + 1] * H <= y + hh + 1e-3):
            fail("triangle %d: outside its chart's rect" % t)
# Charts apart: every two triangles of different charts at least 2P texels
# apart along x or y (the max-norm distance of two triangles: the largest
# gap along an axis or an edge normal scaled to |nx| + |ny| = 1).
def corners(t):
    return [(uv[6 * t + 2 * k] * W, uv[6 * t + 2 * k + 1] * H) for k in range(3)]
def distance(a, b):
    normals = [(1, 0), (0, 1)]
    for p in (a, b):
        normals += [(p[(k + 1) % 3][1] - p[k][1], p[k][0] - p[(k + 1) % 3][0]) for k in range(3)]
    best = 0.0
    for nx, ny in normals:
        for s in (1, -1):
            n = abs(nx) + abs(ny)
            if n > 0:
                x, y = s * nx / n, s * ny / n
                best = max(best, min(x * q[0] + y * q[1] for q in b) -
                           max(x * q[0] + y * q[1] for q in a))
    return best
for s in range(T):
    for t in range(s + 1, T):
        if chart[s] != chart[t] and distance(corners(s), corners(t)) < 2 * P - 1e-9:
            fail("triangles %d and %d of charts %d and %d: nearer than 2P" % (s, t, chart[s], chart[t]))
PY
}
check_atlas "$dir/box.atlas" "$triangles"
ok $? "an independent reader accepts the file ($triangles triangles)"

"$GB_BIN/photons" --count 2000 --quiet "$scene" -o "$dir/box.phot" 2>"$dir/err" &&
    "$GB_BIN/cluster" --depth 3 --knn 20 --quiet "$scene" "$dir/box.phot" -o "$dir/box.lot" \
        2>"$dir/err" &&
    "$GB_BIN/lightmap" "$scene" "$dir/box.atlas" "$dir/box.lot" -o "$dir/box.exr" \
        >/dev/null 2>"$dir/err"
ok $? "gb_atlas_read accepts it (lightmap bakes into it)"

"$tool" -q "$scene" -o "$dir/again.atlas"
cmp -s "$dir/box.atlas" "$dir/again.atlas"
ok $? "a second run gives the same bytes"

"$tool" -q --stats --texels-per-unit 0.05 --padding 1 --cone 30 "$scene" -o "$dir/t.atlas" \
    >"$dir/stats" 2>"$dir/err"
ok $? "--texels-per-unit, --padding, --cone"
ok "$([ "$(value texels_per_unit "$dir/stats")" = 0.05 ] &&
    [ "$(value size "$dir/stats")" != 1024x1024 ]; echo $?)" \
    "... at that density, the atlas as large as it needs ($(value size "$dir/stats"))"
check_atlas "$dir/t.atlas" "$triangles"
ok $? "... a file the independent reader accepts"

"$tool" -q --depfile "$dir/box.d" "$scene" -o "$dir/d.atlas"
ok "$(grep -q 'cornell.obj' "$dir/box.d"; echo $?)" "--depfile names the mesh read"

# ---- help and version ----
"$tool" --help >"$dir/out"
ok $? "--help exits 0"
ok "$(grep -q '^usage: atlas' "$dir/out" && grep -q 'fill ratio' "$dir/out"; echo $?)" \
    "--help prints the usage and defines the fill ratio"
"$tool" --version >"$dir/out"
ok $? "--version exits 0"

# ---- errors ----
expect_failure "no -o" 2 "expected one SCENE" "$scene"
expect_failure "--size with --texels-per-unit" 2 "exclude each other" --size 64 \
    --texels-per-unit 2 "$scene" -o "$dir/x.atlas"
expect_failure "a size too small" 2 "size" --size 4 "$scene" -o "$dir/x.atlas"
expect_failure "a cone of 0" 2 "cone" --cone 0 "$scene" -o "$dir/x.atlas"
expect_failure "a negative padding" 2 "padding" --padding -1 "$scene" -o "$dir/x.atlas"
expect_failure "an unknown option" 2 "unknown option" --frobnicate "$scene" -o "$dir/x.atlas"
expect_failure "a missing scene" 1 "missing.scene" "$dir/missing.scene" -o "$dir/m.atlas"
ok "$([ ! -e "$dir/m.atlas" ]; echo $?)" "... leaves no output"
expect_failure "charts that cannot fit" 1 "do not fit" --size 8 --padding 4 "$scene" \
    -o "$dir/f.atlas"
ok "$([ ! -e "$dir/f.atlas" ]; echo $?)" "... leaves no output"

tap_done
