#!/bin/sh
# lightmap.t — lightmap (the light octree baked into the atlas,
# vivianloc-2007 §4.2.3) on the Cornell box: photons and cluster bake
# cornell.lot, atlas cornell.atlas, lightmap the EXR and the glTF binary.
# Readers written apart from gibake's C (lightmap_check.py: the GLB, its
# PNG, the .lot and the octree's irradiance in double) check that every
# sampled texel is the octree's irradiance at its point, and that the
# embedded PNG, decoded with the scale its material's extras give, is the
# EXR within 10^-3 relative MSE, over the whole image and at each
# triangle's TEXCOORD_1, and its camera is the scene's; the Khronos glTF
# validator finds 0 errors and 0 warnings. The
# files do not depend on --threads; usage errors, the atlas or octree of
# another scene and a bad output are clear errors that leave no file.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the
# repository; GLTF_VALIDATOR: the npm package gltf-validator's folder
# (default build/node/node_modules/gltf-validator, which
# `npm install --prefix build/node gltf-validator` makes).

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/lightmap
scene=$GB_ROOT/scenes/cornell/cornell.scene
check=$GB_ROOT/tests/cli/lightmap_check.py
validate=$GB_ROOT/tests/cli/gltf_validate.mjs
validator=${GLTF_VALIDATOR:-$GB_ROOT/build/node/node_modules/gltf-validator}

needs lightmap atlas photons cluster

# ---- the command line ----
"$tool" --help >"$dir/out" 2>&1
ok "$([ $? = 0 ] && grep -q '^usage: lightmap' "$dir/out"; echo $?)" "--help: usage on stdout"
"$tool" --version >"$dir/out" 2>&1
ok "$([ $? = 0 ] && grep -q '^lightmap (gibake)' "$dir/out"; echo $?)" "--version"
expect_failure "no operands" 2 "expected SCENE NAME.atlas NAME.lot and -o OUT.exr"
expect_failure "no -o" 2 "expected SCENE" "$scene" a.atlas a.lot
expect_failure "--threads 0" 2 "threads: '0' is not an integer" -j 0 "$scene" a.atlas a.lot \
    -o "$dir/x.exr"
expect_failure "unknown option" 2 "unknown option '--frobnicate'" --frobnicate

# ---- the bake ----
"$GB_BIN/photons" -n 200000 --quiet "$scene" -o "$dir/cornell.phot" 2>"$dir/err" &&
    "$GB_BIN/cluster" --depth 5 --quiet "$scene" "$dir/cornell.phot" -o "$dir/cornell.lot" \
        2>>"$dir/err" &&
    "$GB_BIN/atlas" --size 128 --quiet "$scene" -o "$dir/cornell.atlas" 2>>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
ok $status "photons, cluster --depth 5 and atlas --size 128 bake the Cornell box"

"$tool" --quiet --stats -j 2 "$scene" "$dir/cornell.atlas" "$dir/cornell.lot" \
    -o "$dir/a.exr" --glb "$dir/a.glb" --depfile "$dir/a.d" >"$dir/stats" 2>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
ok $status "lightmap writes the EXR and the glTF binary"
sed 's/^/# /' "$dir/stats"
ok "$([ "$(value width "$dir/stats")" = 128 ] && [ "$(value height "$dir/stats")" = 128 ]; \
    echo $?)" "the lightmap has the atlas's size"
ok "$(below 0 "$(value covered_texels "$dir/stats")" &&
    below 0 "$(value gutter_texels "$dir/stats")"; echo $?)" "texels covered and a gutter"
ok "$(grep -q 'cornell.atlas' "$dir/a.d" && grep -q 'cornell.lot' "$dir/a.d" &&
    grep -q 'cornell.obj' "$dir/a.d"; echo $?)" "--depfile names the scene, the atlas and the octree"

"$tool" --quiet -j 1 "$scene" "$dir/cornell.atlas" "$dir/cornell.lot" -o "$dir/b.exr" \
    --glb "$dir/b.glb" 2>/dev/null
ok "$(cmp -s "$dir/a.exr" "$dir/b.exr" && cmp -s "$dir/a.glb" "$dir/b.glb"; echo $?)" \
    "1 thread or 2: byte-identical EXR and glTF binary"

# ---- the final gather (--quality) ----
expect_failure "--paths without --quality" 2 "need --quality N > 0" --paths "$scene" \
    a.atlas a.lot -o "$dir/x.exr"
expect_failure "--bounces with --paths" 2 "not with --paths" --quality 4 --bounces 2 --paths \
    "$scene" a.atlas a.lot -o "$dir/x.exr"
expect_failure "--quality -1" 2 "quality: '-1'" --quality -1 "$scene" a.atlas a.lot \
    -o "$dir/x.exr"
expect_failure "--accuracy without --quality" 2 "need --quality N > 0" --accuracy 0.1 \
    "$scene" a.atlas a.lot -o "$dir/x.exr"
expect_failure "--accuracy 2" 2 "accuracy: '2'" --quality 4 --accuracy 2 "$scene" a.atlas \
    a.lot -o "$dir/x.exr"
expect_failure "no .lot without --paths" 2 "expected SCENE NAME.atlas NAME.lot" --quality 4 \
    "$scene" "$dir/cornell.atlas" -o "$dir/x.exr"
"$tool" --quiet --quality 4 --paths "$scene" "$dir/cornell.atlas" "$dir/cornell.lot" \
    -o "$dir/paths_lot.exr" 2>"$dir/err" &&
    "$tool" --quiet --quality 4 --paths "$scene" "$dir/cornell.atlas" -o "$dir/paths.exr" \
        2>>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
ok "$([ $status = 0 ] && cmp -s "$dir/paths_lot.exr" "$dir/paths.exr"; echo $?)" \
    "--paths without NAME.lot: the same lightmap as with it"
for threads in 1 2; do
    "$tool" --quiet -j $threads --quality 8 "$scene" "$dir/cornell.atlas" "$dir/cornell.lot" \
        -o "$dir/gather$threads.exr" 2>"$dir/err" || sed 's/^/# /' "$dir/err"
done
ok "$([ -s "$dir/gather1.exr" ] && cmp -s "$dir/gather1.exr" "$dir/gather2.exr"; echo $?)" \
    "--quality 8: 1 thread or 2, byte-identical"
# The truth: the unbiased gather (--paths) at every texel, 128 rays; two seeds of it differ
# by 0.008 (measured), the octree read by 0.10, the octree's gather of 16
# rays by 0.013 (interpolated at the default --accuracy): the gather must bring
# the octree's error down.
"$tool" --quiet --quality 128 --paths --accuracy 0 "$scene" "$dir/cornell.atlas" \
    "$dir/cornell.lot" -o "$dir/truth.exr" 2>"$dir/err" &&
    "$tool" --quiet --quality 16 "$scene" "$dir/cornell.atlas" "$dir/cornell.lot" \
        -o "$dir/gather16.exr" 2>>"$dir/err" &&
    "$GB_BIN/imgdiff" "$dir/a.exr" "$dir/truth.exr" >"$dir/octree_error" 2>>"$dir/err" &&
    "$GB_BIN/imgdiff" "$dir/gather16.exr" "$dir/truth.exr" >"$dir/gather_error" 2>>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
octree_error=$(value relative_mse "$dir/octree_error")
gather_error=$(value relative_mse "$dir/gather_error")
echo "# relative MSE against --paths --quality 128: octree $octree_error, gather of 16 $gather_error"
ok "$([ $status = 0 ] && below "$gather_error" 0.03 &&
    below "$gather_error" "$(echo "$octree_error" | awk '{print $1 / 3}')"; echo $?)" \
    "--quality 16 against --paths: under 0.03 and under a third of the octree read's error"

# ---- the furnace: a closed box of albedo 0.5 whose inside emits 1 ----
# Its indirect irradiance is pi Le rho / (1 - rho) = pi everywhere, edges
# and corners included; a texel past its triangle's edge (the reach) must
# read the triangle, not the outside of the box beyond it. The albedo is
# Kd 1 times a texture of 0.5 (an EXR, read linear): a gather that read Kd
# alone would see rho = 1.
printf 'newmtl wall\nKd 1 1 1\nKe 1 1 1\nmap_Kd half.exr\n' >"$dir/furnace.mtl"
oiiotool --pattern constant:color=0.5,0.5,0.5 4x4 3 -d float -o "$dir/half.exr" 2>"$dir/err" ||
    sed 's/^/# /' "$dir/err"
printf 'mtllib furnace.mtl\nusemtl wall\n' >"$dir/furnace.obj"
printf 'v %s\n' "0 0 0" "1 0 0" "1 1 0" "0 1 0" "0 0 1" "1 0 1" "1 1 1" "0 1 1" \
    >>"$dir/furnace.obj"
printf 'vt 0.5 0.5\n' >>"$dir/furnace.obj"
printf 'f %s/1 %s/1 %s/1\n' 1 5 6 1 6 2 4 3 7 4 7 8 1 4 8 1 8 5 2 6 7 2 7 3 1 2 3 1 3 4 \
    5 8 7 5 7 6 >>"$dir/furnace.obj"
"$GB_BIN/photons" -q -n 20000 "$dir/furnace.obj" -o "$dir/furnace.phot" 2>"$dir/err" &&
    "$GB_BIN/cluster" -q --depth 3 "$dir/furnace.obj" "$dir/furnace.phot" \
        -o "$dir/furnace.lot" 2>>"$dir/err" &&
    "$GB_BIN/atlas" -q --size 64 "$dir/furnace.obj" -o "$dir/furnace.atlas" 2>>"$dir/err" &&
    "$tool" -q --stats --quality 128 --paths "$dir/furnace.obj" "$dir/furnace.atlas" \
        "$dir/furnace.lot" -o "$dir/furnace.exr" >"$dir/furnace_stats" 2>>"$dir/err" &&
    oiiotool --dumpdata "$dir/furnace.exr" >"$dir/furnace.txt" 2>>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
# The texels that hold light, sorted over pi: the 0.1 % and 99.9 % points.
awk '/Pixel/ { if ($4 + 0 > 0) print $4 / 3.14159265 }' "$dir/furnace.txt" | sort -g \
    >"$dir/furnace_sorted"
lit=$(wc -l <"$dir/furnace_sorted")
low=$(sed -n "$((lit / 1000 + 1))p" "$dir/furnace_sorted")
high=$(sed -n "$((lit - lit / 1000))p" "$dir/furnace_sorted")
echo "# furnace: $lit texels lit of $(value covered_texels "$dir/furnace_stats") covered;" \
    "0.1 % .. 99.9 % at $low .. $high pi"
ok "$([ $status = 0 ] && [ "$lit" -ge "$(value covered_texels "$dir/furnace_stats")" ] &&
    below 0.85 "$low" && below "$high" 1.15; echo $?)" \
    "furnace: every covered texel lit, 99.8 % of them within 15 % of pi (--paths, 128 rays, the texture's albedo)"

# ---- the values, read back apart from gibake ----
if command -v python3 >/dev/null && command -v oiiotool >/dev/null; then
    oiiotool --dumpdata "$dir/a.exr" >"$dir/a.txt" &&
        python3 "$check" "$dir/a.glb" "$dir/cornell.lot" "$dir/a.txt" "$scene" >"$dir/check" \
            2>"$dir/err"
    status=$?
    [ $status = 0 ] || sed 's/^/# /' "$dir/err"
    ok $status "lightmap_check.py reads the GLB, its PNG, the octree and the EXR"
    sed 's/^/# /' "$dir/check"
    # Measured: 1.9e-6 (the C in float, the check in double).
    ok "$(below 100 "$(value texels "$dir/check")" &&
        below "$(value octree_max_relative "$dir/check")" 1e-4; echo $?)" \
        "every sampled texel is the octree's irradiance at its point, within 10^-4"
    # Measured: 9.8e-6 whole, 5.1e-6 at the centroids (8-bit sRGB of lightmap / scale).
    ok "$(below "$(value png_relative_mse "$dir/check")" 1e-3; echo $?)" \
        "the PNG decoded with its scale: the EXR within 10^-3 relative MSE"
    ok "$(below "$(value sample_relative_mse "$dir/check")" 1e-3; echo $?)" \
        "sampled at each triangle's TEXCOORD_1: the EXR within 10^-3 relative MSE"
    # The published camera (fov 39.3077 degrees), as the reference renders it.
    ok "$(below "$(value camera_degrees "$dir/check")" 1e-3 &&
        below "$(value camera_offset "$dir/check")" 1e-3 &&
        [ "$(value camera_fov_degrees "$dir/check")" = 39.3077 ]; echo $?)" \
        "the glTF camera: the scene camera's place, view, up and field of view"
    ok "$([ "$(value png_relative_mse "$dir/check")" = "$(value png_relative_mse "$dir/stats")" ];
        echo $?)" "the tool's own PNG error (--stats) is the one measured here"
else
    missing "python3 and oiiotool (openimageio-tools)"
fi

# ---- trilinear interpolation (cluster --interpolation trilinear, the paper's;
# the lightmap above is of cluster's default, surface), read back apart ----
if command -v python3 >/dev/null && command -v oiiotool >/dev/null; then
    "$GB_BIN/cluster" --depth 5 --interpolation trilinear --quiet "$scene" "$dir/cornell.phot" \
        -o "$dir/trilinear.lot" 2>"$dir/err" &&
        "$tool" --quiet "$scene" "$dir/cornell.atlas" "$dir/trilinear.lot" -o "$dir/s.exr" \
            --glb "$dir/s.glb" 2>>"$dir/err" &&
        oiiotool --dumpdata "$dir/s.exr" >"$dir/s.txt" &&
        python3 "$check" "$dir/s.glb" "$dir/trilinear.lot" "$dir/s.txt" "$scene" \
            >"$dir/s.check" 2>>"$dir/err"
    status=$?
    [ $status = 0 ] || sed 's/^/# /' "$dir/err"
    sed 's/^/# trilinear: /' "$dir/s.check" | grep octree_max_relative
    ok "$([ $status = 0 ] && below 100 "$(value texels "$dir/s.check")" &&
        below "$(value octree_max_relative "$dir/s.check")" 1e-4 &&
        ! cmp -s "$dir/a.exr" "$dir/s.exr"; echo $?)" \
        "trilinear interpolation: every sampled texel is the octree's irradiance, within 10^-4, not the surface interpolation's"
else
    missing "python3 and oiiotool (openimageio-tools)"
fi

if command -v node >/dev/null && [ -d "$validator" ]; then
    node "$validate" "$dir/a.glb" "$validator" >"$dir/valid" 2>&1
    status=$?
    sed 's/^/# /' "$dir/valid"
    ok "$([ $status = 0 ] && [ "$(value errors "$dir/valid")" = 0 ] &&
        [ "$(value warnings "$dir/valid")" = 0 ]; echo $?)" \
        "the Khronos glTF validator: 0 errors, 0 warnings"
else
    missing "node and gltf-validator ($validator: npm install --prefix build/node gltf-validator)"
fi

# ---- textures: a PNG embedded as it is, an EXR encoded as PNG ----
cat >"$dir/tf.obj" <<'EOF2'
mtllib tf.mtl
v -2 0 -2
v 0 0 -2
v 0 0 2
v -2 0 2
v 2 0 -2
v 2 0 2
vt 0 0
vt 1 0
vt 1 1
vt 0 1
usemtl png
f 1/1 3/3 2/2
f 1/1 4/4 3/3
usemtl exr
f 2/1 3/4 6/3
f 2/1 6/3 5/2
EOF2
printf 'newmtl png\nKd 0.8 0.8 0.8\nmap_Kd tex.png\nnewmtl exr\nKd 0.5 0.6 0.7\nmap_Kd tex.exr\n' \
    >"$dir/tf.mtl"
cat >"$dir/tf.scene" <<'EOF2'
gibake-scene 1
mesh tf.obj
light directional direction 0.6 -0.8 0 irradiance 2 2 2
camera position 3 2.5 -4 target 0 0 0.5 up 0 1 0 fov 50 resolution 320 240
EOF2
oiiotool --pattern checker:width=4:height=4 16x16 3 -o "$dir/tex.png" 2>"$dir/err" &&
    oiiotool --pattern fill:top=0.8,0.2,0.1:bottom=0.1,0.3,0.9 16x16 3 -d float \
        -o "$dir/tex.exr" 2>>"$dir/err" &&
    "$GB_BIN/photons" -q -n 20000 --store all "$dir/tf.scene" -o "$dir/tf.phot" 2>>"$dir/err" &&
    "$GB_BIN/cluster" -q --depth 4 "$dir/tf.scene" "$dir/tf.phot" -o "$dir/tf.lot" \
        2>>"$dir/err" &&
    "$GB_BIN/atlas" -q --size 64 "$dir/tf.scene" -o "$dir/tf.atlas" 2>>"$dir/err" &&
    "$tool" -q "$dir/tf.scene" "$dir/tf.atlas" "$dir/tf.lot" -o "$dir/tf.exr" \
        --glb "$dir/tf.glb" 2>>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
ok $status "a textured scene (a PNG and an EXR map_Kd) exported"
python3 - "$dir/tf.glb" "$dir/tex.png" >"$dir/tf" 2>&1 <<'EOF2'
import json, struct, sys
data = open(sys.argv[1], 'rb').read()
size = struct.unpack_from('<I', data, 12)[0]
doc, binary = json.loads(data[20:20 + size]), data[28 + size:]
def view(i):
    v = doc['bufferViews'][i]
    return binary[v.get('byteOffset', 0):v.get('byteOffset', 0) + v['byteLength']]
print('images', len(doc['images']))
print('png_mimes', sum(i['mimeType'] == 'image/png' and view(i['bufferView'])[:4] == b'\x89PNG'
                       for i in doc['images']))
print('png_as_is', int(view(doc['images'][1]['bufferView']) == open(sys.argv[2], 'rb').read()))
print('textured', sum('baseColorTexture' in m['pbrMetallicRoughness'] for m in doc['materials']))
a = doc['meshes'][0]['primitives'][0]['attributes']
def floats(i, width):
    acc = doc['accessors'][i]
    values = struct.unpack_from('<%df' % (acc['count'] * width), view(acc['bufferView']))
    return [values[k:k + width] for k in range(0, len(values), width)]
corner = [t for p, t in zip(floats(a['POSITION'], 3), floats(a['TEXCOORD_0'], 2))
          if p == (-2.0, 0.0, -2.0)]
print('texcoord0_flipped', int(corner == [(0.0, 1.0)]))
EOF2
sed 's/^/# /' "$dir/tf"
ok "$([ "$(value images "$dir/tf")" = 3 ] && [ "$(value png_mimes "$dir/tf")" = 3 ] &&
    [ "$(value textured "$dir/tf")" = 2 ]; echo $?)" \
    "the lightmap and both textures embedded as PNG, each material textured"
ok "$([ "$(value png_as_is "$dir/tf")" = 1 ]; echo $?)" "the PNG texture embedded byte for byte"
ok "$([ "$(value texcoord0_flipped "$dir/tf")" = 1 ]; echo $?)" \
    "TEXCOORD_0: the OBJ's v flipped to glTF's (vt 0 0 -> 0 1)"
oiiotool --dumpdata "$dir/tf.exr" >"$dir/tf.txt" &&
    python3 "$check" "$dir/tf.glb" "$dir/tf.lot" "$dir/tf.txt" "$dir/tf.scene" >"$dir/check" \
        2>"$dir/err"
status=$?
[ $status = 0 ] || sed 's/^/# /' "$dir/err"
sed 's/^/# /' "$dir/check"
ok "$([ $status = 0 ] && below "$(value octree_max_relative "$dir/check")" 1e-4 &&
    below "$(value png_relative_mse "$dir/check")" 1e-3; echo $?)" \
    "the textured scene: the EXR is the octree's irradiance, the PNG the EXR"
ok "$(below "$(value camera_degrees "$dir/check")" 1e-3 &&
    below "$(value camera_offset "$dir/check")" 1e-5 &&
    [ "$(value camera_fov_degrees "$dir/check")" = 50 ]; echo $?)" \
    "an oblique camera: the glTF camera's place, view, up and field of view"
if command -v node >/dev/null && [ -d "$validator" ]; then
    node "$validate" "$dir/tf.glb" "$validator" >"$dir/valid" 2>&1
    status=$?
    sed 's/^/# /' "$dir/valid"
    ok "$([ $status = 0 ] && [ "$(value errors "$dir/valid")" = 0 ]; echo $?)" \
        "the textured scene's glTF binary: 0 errors"
else
    missing "node and gltf-validator"
fi

# A texture that cannot be read (the scene's hash does not cover the
# images' bytes, so the atlas and octree still fit): a clear error and
# neither output, the glTF binary being made before the EXR is written.
mkdir "$dir/bad"
cp "$dir/tf.obj" "$dir/tf.mtl" "$dir/tf.scene" "$dir/tex.png" "$dir/bad/"
echo "not an image" >"$dir/bad/tex.exr"
expect_failure "an unreadable texture" 1 "tex.exr: not an image" \
    -q "$dir/bad/tf.scene" "$dir/tf.atlas" "$dir/tf.lot" -o "$dir/bad/x.exr" \
    --glb "$dir/bad/x.glb"
ok "$([ ! -e "$dir/bad/x.exr" ] && [ ! -e "$dir/bad/x.glb" ]; echo $?)" \
    "an unreadable texture: no EXR, no glTF binary"

# ---- inputs of another scene, a bad output ----
floor_obj "$dir/floor.obj"
cat >"$dir/floor.scene" <<'EOF2'
gibake-scene 1
mesh floor.obj
light directional direction 0.6 -0.8 0 irradiance 2 2 2
EOF2
"$GB_BIN/atlas" --size 32 --quiet "$dir/floor.scene" -o "$dir/floor.atlas" 2>"$dir/err"
ok $? "atlas of a floor"
expect_failure "the atlas of another scene" 1 "floor.atlas: .*another scene" \
    --quiet "$scene" "$dir/floor.atlas" "$dir/cornell.lot" -o "$dir/stale.exr"
ok "$([ ! -e "$dir/stale.exr" ]; echo $?)" "the atlas of another scene: no EXR"
"$GB_BIN/photons" -q -n 2000 --store all "$dir/floor.scene" -o "$dir/floor.phot" 2>/dev/null &&
    "$GB_BIN/cluster" -q --depth 3 "$dir/floor.scene" "$dir/floor.phot" -o "$dir/floor.lot" \
        2>/dev/null
expect_failure "the octree of another scene" 1 "floor.lot: .*another scene" \
    --quiet "$scene" "$dir/cornell.atlas" "$dir/floor.lot" -o "$dir/stale.exr" \
    --glb "$dir/stale.glb"
ok "$([ ! -e "$dir/stale.exr" ] && [ ! -e "$dir/stale.glb" ]; echo $?)" \
    "the octree of another scene: no EXR, no glTF binary"
expect_failure "an output that names no image format" 1 "x.txt: unknown image format" \
    --quiet "$scene" "$dir/cornell.atlas" "$dir/cornell.lot" -o "$dir/x.txt"
expect_failure "a missing atlas" 1 "nothing.atlas" \
    --quiet "$scene" "$dir/nothing.atlas" "$dir/cornell.lot" -o "$dir/none.exr"
ok "$([ ! -e "$dir/none.exr" ]; echo $?)" "a missing atlas: no EXR"

tap_done
