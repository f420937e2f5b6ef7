#!/bin/sh
# imgdiff.t — imgdiff as a user types it: known numbers on tiny PPM images
# written here (8-bit sRGB, so mse_srgb8 is exact), relative_mse_trimmed
# on 2000-pixel ones against figures worked out here, masks, heatmaps,
# errors.
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
tool=$GB_BIN/imgdiff

# value KEY FILE: the value printed for KEY in FILE
needs imgdiff

printf 'P3\n2 1\n255\n100 100 100 0 0 0\n' >"$dir/a.ppm"
printf 'P3\n2 1\n255\n110 110 110 0 0 0\n' >"$dir/b.ppm"
printf 'P3\n2 1\n255\n0 0 0 255 255 255\n' >"$dir/mask.ppm"
printf 'P3\n1 1\n255\n0 0 0\n' >"$dir/small.ppm"

"$tool" "$dir/a.ppm" "$dir/b.ppm" >"$dir/out" 2>"$dir/err"
ok $? "two 2x1 images: exit status 0"
ok "$([ "$(value pixels "$dir/out")" = 2 ]; echo $?)" "2 pixels compared"
ok "$([ "$(value mse_srgb8 "$dir/out")" = 50 ]; echo $?)" \
    "mse_srgb8 = 3 * 10^2 / 6 = 50 (got $(value mse_srgb8 "$dir/out"))"
ok "$([ "$(value psnr "$dir/out")" = 31.1411 ]; echo $?)" \
    "psnr = 10 log10(255^2 / 50) = 31.1411 dB (got $(value psnr "$dir/out"))"
ok "$([ ! -s "$dir/err" ]; echo $?)" "nothing on stderr"

ok "$([ "$(value relative_mse_trimmed "$dir/out")" = "$(value relative_mse "$dir/out")" ]; echo $?)" \
    "2 pixels (fewer than 1000): relative_mse_trimmed = relative_mse, nothing left out"

# relative_mse_trimmed on 2000 x 1 images: the reference grey 110, the image
# grey 100 but for pixels 500 and 1500, white (255). The expected figures
# are worked out here from the sRGB decoding of the 8-bit values: r_grey and
# r_white, a pixel's (a - b)^2 / (b^2 + 0.01).
# ppm FILE GREY [PIXEL...]: a 2000 x 1 image, grey GREY, white at each PIXEL
ppm() {
    file=$1 grey=$2
    shift 2
    awk -v grey="$grey" -v white=" $* " 'BEGIN { print "P3\n2000 1\n255"
        for (p = 0; p < 2000; ++p) { v = index(white, " " p " ") ? 255 : grey; print v, v, v } }' >"$file"
}
# relative A B: (a - b)^2 / (b^2 + 0.01) of the 8-bit sRGB values A and B
relative() {
    awk -v a="$1" -v b="$2" 'function lin(v) { v /= 255; return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ^ 2.4 }
        BEGIN { printf "%.9g", (lin(a) - lin(b)) ^ 2 / (lin(b) ^ 2 + 0.01) }'
}
# near X Y: X within 1e-5 of Y, relative (imgdiff prints 6 digits)
near() {
    awk -v x="$1" -v y="$2" 'BEGIN { d = x - y; exit !(x != "" && (d < 0 ? -d : d) <= 1e-5 * (y < 0 ? -y : y)) }'
}
r_grey=$(relative 100 110)
r_white=$(relative 255 110)
ppm "$dir/ref2000.ppm" 110
ppm "$dir/grey2000.ppm" 100
ppm "$dir/spots2000.ppm" 100 500 1500
"$tool" "$dir/grey2000.ppm" "$dir/ref2000.ppm" >"$dir/out"
ok "$(near "$(value relative_mse_trimmed "$dir/out")" "$(value relative_mse "$dir/out")" &&
    near "$(value relative_mse "$dir/out")" "$r_grey"; echo $?)" \
    "2000 pixels, every one the same error: relative_mse_trimmed = relative_mse = r_grey = $r_grey"
"$tool" "$dir/spots2000.ppm" "$dir/ref2000.ppm" >"$dir/out"
plain=$(awk -v g="$r_grey" -v w="$r_white" 'BEGIN { printf "%.9g", (1998 * g + 2 * w) / 2000 }')
ok "$(near "$(value relative_mse "$dir/out")" "$plain"; echo $?)" \
    "2 white pixels of 2000: relative_mse = (1998 r_grey + 2 r_white) / 2000 = $plain"
ok "$(near "$(value relative_mse_trimmed "$dir/out")" "$r_grey"; echo $?)" \
    "2 white pixels of 2000: relative_mse_trimmed leaves both out (floor(2000 / 1000) = 2): r_grey (got $(value relative_mse_trimmed "$dir/out"))"
# --mask: the first 1000 pixels (white pixel 500 among them): 1 left out;
# the first 999: none.
awk 'BEGIN { print "P3\n2000 1\n255"; for (p = 0; p < 2000; ++p) print (p < 1000 ? "255 255 255" : "0 0 0") }' >"$dir/m1000.ppm"
awk 'BEGIN { print "P3\n2000 1\n255"; for (p = 0; p < 2000; ++p) print (p < 999 ? "255 255 255" : "0 0 0") }' >"$dir/m999.ppm"
"$tool" --mask "$dir/m1000.ppm" "$dir/spots2000.ppm" "$dir/ref2000.ppm" >"$dir/out"
ok "$([ "$(value pixels "$dir/out")" = 1000 ] && near "$(value relative_mse_trimmed "$dir/out")" "$r_grey" &&
    near "$(value relative_mse "$dir/out")" "$(awk -v g="$r_grey" -v w="$r_white" 'BEGIN { printf "%.9g", (999 * g + w) / 1000 }')"; echo $?)" \
    "--mask of 1000 pixels, one white: relative_mse_trimmed leaves it out (r_grey), relative_mse does not"
"$tool" --mask "$dir/m999.ppm" "$dir/spots2000.ppm" "$dir/ref2000.ppm" >"$dir/out"
ok "$([ "$(value pixels "$dir/out")" = 999 ] &&
    [ "$(value relative_mse_trimmed "$dir/out")" = "$(value relative_mse "$dir/out")" ] &&
    below "$r_grey" "$(value relative_mse_trimmed "$dir/out")"; echo $?)" \
    "--mask of 999 pixels: none left out, relative_mse_trimmed = relative_mse (above r_grey: the white pixel counts)"

"$tool" "$dir/a.ppm" "$dir/a.ppm" >"$dir/out"
ok "$([ "$(value mse_srgb8 "$dir/out")" = 0 ] && [ "$(value rmse "$dir/out")" = 0 ] &&
    [ "$(value psnr "$dir/out")" = inf ]; echo $?)" "an image against itself: 0, 0, inf"

"$tool" --mask "$dir/mask.ppm" "$dir/a.ppm" "$dir/b.ppm" >"$dir/out"
ok "$([ "$(value pixels "$dir/out")" = 1 ] && [ "$(value mse_srgb8 "$dir/out")" = 0 ]; echo $?)" \
    "--mask leaves out the black pixel, the one that differs"

# --fail-above E: exit 1 (one line on stderr) when relative_mse > E, else 0;
# --quiet prints nothing either way.
"$tool" "$dir/a.ppm" "$dir/b.ppm" >"$dir/out"
error=$(value relative_mse "$dir/out")
below=$(awk -v e="$error" 'BEGIN { print e * 0.99 }')
above=$(awk -v e="$error" 'BEGIN { print e * 1.01 }')
"$tool" --fail-above "$below" "$dir/a.ppm" "$dir/b.ppm" >"$dir/out" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ] && grep -q '^relative_mse ' "$dir/out" &&
    [ "$(cat "$dir/err")" = "imgdiff: relative_mse $error is above $below" ]; echo $?)" \
    "--fail-above just below the error ($below < $error): exit 1, measures printed, one line why"
"$tool" --fail-above "$above" "$dir/a.ppm" "$dir/b.ppm" >/dev/null 2>"$dir/err"
ok "$([ $? = 0 ] && [ ! -s "$dir/err" ]; echo $?)" "--fail-above just above the error: exit 0"
"$tool" --quiet --fail-above "$below" "$dir/a.ppm" "$dir/b.ppm" >"$dir/out" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ] && [ ! -s "$dir/out" ] && [ ! -s "$dir/err" ]; echo $?)" \
    "--quiet --fail-above: exit 1 and nothing printed"
"$tool" -q "$dir/a.ppm" "$dir/b.ppm" >"$dir/out" 2>"$dir/err"
ok "$([ $? = 0 ] && [ ! -s "$dir/out" ] && [ ! -s "$dir/err" ]; echo $?)" "-q: exit 0, nothing printed"
"$tool" --fail-above -1 "$dir/a.ppm" "$dir/b.ppm" >/dev/null 2>"$dir/err"
status=$?
ok "$([ $status = 2 ] && grep -qx "imgdiff: --fail-above: '-1' is not a number in \[0, 1e+30\]" "$dir/err"; echo $?)" \
    "--fail-above -1: usage error, exit 2 (got $status)"

"$tool" --heatmap "$dir/heat.png" "$dir/a.ppm" "$dir/b.ppm" >/dev/null
ok "$([ -s "$dir/heat.png" ]; echo $?)" "--heatmap writes a PNG"

"$tool" "$dir/a.ppm" "$dir/small.ppm" >"$dir/out" 2>"$dir/err"
status=$?
ok "$([ $status = 1 ]; echo $?)" "images of different sizes: exit status 1 (got $status)"
ok "$([ "$(cat "$dir/err")" = "imgdiff: images differ in size: 2x1 and 1x1" ]; echo $?)" \
    "images of different sizes: one message on stderr"
ok "$([ ! -s "$dir/out" ]; echo $?)" "images of different sizes: nothing on stdout"

"$tool" "$dir/a.ppm" "$dir/missing.exr" >/dev/null 2>"$dir/err"
ok "$([ $? = 1 ] && grep -q "^imgdiff: .*missing.exr" "$dir/err"; echo $?)" \
    "a missing file: exit status 1 and a message naming it"

"$tool" "$dir/a.ppm" >/dev/null 2>&1
status=$?
ok "$([ $status = 2 ]; echo $?)" "one image only: usage, exit status 2 (got $status)"
"$tool" --help >"$dir/out"
ok "$([ $? = 0 ] && grep -q "^usage: imgdiff" "$dir/out"; echo $?)" "--help on stdout, status 0"
"$tool" --version >"$dir/out"
ok "$([ $? = 0 ] && grep -q "imgdiff (gibake)" "$dir/out"; echo $?)" "--version"

tap_done
