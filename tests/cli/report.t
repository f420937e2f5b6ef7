#!/bin/sh
# report.t — make report FAST=1 (bench/report.mk) as CI runs it, with the
# tools of $GB_BIN and the report in the scratch folder, then assertions on
# its results.csv that hold whatever the machine's speed (no timing is
# asserted): a row for every method on the Cornell box; every error finite;
# on the two rooms (a wall between the light's room and the camera's) topo
# with full visibility at most as wrong as without; FLC after 16 frames
# better than after 1; octree and implicit better than direct light alone
# against the full reference; every reference's noise floor below the
# smallest error compared with it, or the report says the comparison is
# void; relative_mse_trimmed worked out again from the images (oiiotool)
# for every comparison, and below relative_mse; the direct pass's error and
# share beside each point of a scene with a direct point; the Pareto fronts
# by the trimmed figure (a doctored point whose few bad pixels make the
# worst relative MSE but the best trimmed one ends its front); segment
# --evaluate of each topo bake, better than chance on the two rooms; the
# plots, gallery and page written; a second make report renders nothing; a
# bad sweep line stops with its file and line. Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"
GB_BIN=$(cd "$GB_BIN" 2>/dev/null && pwd || echo "$GB_BIN")
# No time limit on a render (timeout 0): under the sanitizers or a loaded
# machine a slow render must still finish, never fail by the clock.
export REPORT_TIMEOUT=0

for t in voxelize thin segment photons cluster reference imgdiff scene-info gbview; do
    [ -x "$GB_BIN/$t" ] || { missing "$GB_BIN/$t not built"; tap_done; exit 1; }
done
command -v gnuplot >/dev/null || missing "gnuplot (Debian gnuplot-nox)"

report=$dir/report
# The report's own make: nothing inherited from a make that runs the suite.
run_report() {
    MAKEFLAGS= MAKELEVEL= MFLAGS= make -j2 --no-print-directory -C "$GB_ROOT" report FAST=1 \
        BIN="$GB_BIN" REPORT="$report" >"$1" 2>&1
}
run_report "$dir/log1"
status=$?
ok $status "make report FAST=1 BIN=\$GB_BIN REPORT=scratch: exit 0"
[ $status = 0 ] || sed 's/^/# /' "$dir/log1" | tail -30
csv=$report/results.csv
ok "$([ -s "$csv" ]; echo $?)" "results.csv written"

# col NAME: the column number of NAME in results.csv's header
col() { head -n 1 "$csv" | tr , '\n' | grep -nx "$1" | cut -d: -f1; }
# err SCENE METHOD PATTERN COLUMN: COLUMN of the row of SCENE and METHOD
# whose point id matches PATTERN (awk regular expression)
err() {
    awk -F, -v s="$1" -v m="$2" -v p="$3" -v c="$(col "$4")" \
        'NR > 1 && $1 == s && $3 == m && $4 ~ p { print $c; exit }' "$csv"
}

for m in direct topo octree flc implicit flc-iv; do
    n=$(awk -F, -v m="$m" 'NR > 1 && $1 == "cornell" && $3 == m' "$csv" | wc -l)
    ok "$([ "$n" -ge 1 ]; echo $?)" "a row for $m on the Cornell box ($n)"
done

bad=$(awk -F, -v st="$(col status)" 'NR > 1 && $st != "ok" { print $4 }' "$csv")
ok "$([ -z "$bad" ] && [ "$(wc -l <"$csv")" -gt 1 ]; echo $?)" "every point rendered (status ok)${bad:+ (not: $bad)}"

finite=$(awk -F, -v h="$(head -n 1 "$csv")" '
    BEGIN { n = split(h, name, ","); for (i = 1; i <= n; i++) if (name[i] ~ /_(rel_mse|mse_srgb8|psnr|max_error|rel_mse_trimmed)$/ && name[i] != "direct_pass_rel_mse") want[i] = 1 }
    NR > 1 { for (i in want) if ($i !~ /^[0-9.]+(e[-+]?[0-9]+)?$/) { print $4 " " name[i] "=" $i; exit } }' "$csv")
ok "$([ -z "$finite" ]; echo $?)" "every error is a finite number${finite:+ (not: $finite)}"

# relative_mse_trimmed, worked out here from the images for each point's
# two comparisons: oiiotool writes (a - b)^2 / (b^2 + 0.01), awk takes each
# pixel's mean over the channels, leaves out the floor(n / 1000) largest
# and averages the rest. At most relative_mse (below it here: every point
# has some pixels far off).
# trimmed IMAGE REFERENCE: that figure
trimmed() {
    oiiotool "$1" "$2" --sub --dup --mul "$2" --dup --mul --addc 0.01 --div -d float -o "$dir/rel.exr" &&
        oiiotool --dumpdata "$dir/rel.exr" | awk '/Pixel/ { printf "%.9g\n", ($(NF - 2) + $(NF - 1) + $NF) / 3 }' |
        sort -g | awk '{ v[NR] = $1 } END { k = int(NR / 1000); for (i = 1; i <= NR - k; i++) t += v[i]; printf "%.9g", t / (NR - k) }'
}
wrong=
while IFS=, read -r id fullref full full_t ownref own own_t; do
    for c in "full $report/img/$id.exr $fullref $full $full_t" "own $report/img/$id.own.exr $ownref $own $own_t"; do
        set -- $c
        expected=$(trimmed "$2" "$report/ref/$3-seed0.exr")
        awk -v got="$5" -v e="$expected" -v plain="$4" \
            'BEGIN { exit !(got != "" && (got - e < 0 ? e - got : got - e) <= 1e-5 * e && got + 0 < plain + 0) }' ||
            wrong="$wrong $id:$1=$5(here $expected, relative_mse $4)"
    done
done <<EOF2
$(awk -F, -v h="$(head -n 1 "$csv")" 'BEGIN { n = split(h, name, ","); for (i = 1; i <= n; i++) c[name[i]] = i }
    NR > 1 { print $4 "," $c["full_ref"] "," $c["full_rel_mse"] "," $c["full_rel_mse_trimmed"] "," $c["own_ref"] "," $c["own_rel_mse"] "," $c["own_rel_mse_trimmed"] }' "$csv")
EOF2
ok "$([ -z "$wrong" ] && [ "$(wc -l <"$csv")" -gt 1 ]; echo $?)" \
    "full_ and own_rel_mse_trimmed: as worked out from the images, below relative_mse${wrong:+ (not:$wrong)}"

# The direct pass's error: on the direct point, against the full reference,
# below its error against the direct reference (the same differences over
# a brighter reference) and below the direct-only frame's own error (that
# misses the indirect light). Every point of the scene carries it, and
# direct_share = it / full_rel_mse; the two rooms have no direct point.
pass=$(err cornell direct . direct_pass_rel_mse)
direct_own=$(err cornell direct . own_rel_mse)
direct_full=$(err cornell direct . full_rel_mse)
awk -v p="$pass" -v o="$direct_own" -v f="$direct_full" 'BEGIN { exit !(p != "" && p + 0 > 0 && p + 0 < o + 0 && p + 0 < f + 0) }'
ok $? "Cornell: the direct pass's error against the full reference ($pass) above 0, below the direct point's own ($direct_own) and its full error ($direct_full)"
shares=$(awk -F, -v h="$(head -n 1 "$csv")" 'BEGIN { n = split(h, name, ","); for (i = 1; i <= n; i++) c[name[i]] = i }
    NR > 1 && $3 == "direct" { pass[$1] = $c["direct_pass_rel_mse"] }
    NR > 1 { row[NR] = $0 }
    END { for (r = 2; r <= NR; r++) { $0 = row[r]; p = $c["direct_pass_rel_mse"]; s = $c["direct_share"]
        if (!($1 in pass)) { if (p != "" || s != "") print $4; continue }
        want = pass[$1] / $c["full_rel_mse"]
        if (p != pass[$1] || (s - want < 0 ? want - s : s - want) > 1e-3 * want) print $4 } }' "$csv" | tr '\n' ' ')
ok "$([ -z "$shares" ]; echo $?)" \
    "direct_pass_rel_mse and direct_share (= it / full_rel_mse) on each point of the scenes with a direct point, none on the others${shares:+ (not: $shares)}"

# The Pareto fronts are by full_rel_mse_trimmed: along each scene's front,
# by ms to the image, it decreases; every other point of the scene is beaten
# by a front point at most as slow with at most its trimmed error.
pareto=$report/pareto.csv
front=$(awk -F, -v t="$(col time_ms)" -v e="$(col full_rel_mse_trimmed)" -v st="$(col status)" '
    FNR == 1 { file++; next }
    file == 1 { on[$8] = 1; n[$1]++; fms[$1, n[$1]] = $4 + 0; fe[$1, n[$1]] = $9 + 0
        if (n[$1] > 1 && !($4 + 0 >= fms[$1, n[$1] - 1] && $9 + 0 < fe[$1, n[$1] - 1])) print "order:" $8 }
    file == 2 && $st == "ok" && !($4 in on) { beaten = 0
        for (i = 1; i <= n[$1]; i++) if (fms[$1, i] <= $t + 0 && fe[$1, i] <= $e + 0) beaten = 1
        if (!beaten) print "unbeaten:" $4 }' "$pareto" "$csv" | tr '\n' ' ')
ok "$([ -z "$front" ] && [ "$(wc -l <"$pareto")" -gt 1 ]; echo $?)" \
    "pareto.csv: each front by full_rel_mse_trimmed, every other point beaten${front:+ (not: $front)}"
# The same report with one point doctored: the Cornell box's slowest point
# given the largest relative MSE of all (a few pixels far off) but the
# smallest trimmed one. By the trimmed figure it ends the front.
cp -r "$report" "$dir/doctored"
slow=$(awk -F, -v t="$(col time_ms)" 'NR > 1 && $1 == "cornell" && $t + 0 >= max { max = $t + 0; id = $4 } END { print id }' "$csv")
awk -F, -v OFS=, -v p="$(col full_rel_mse)" -v q="$(col full_rel_mse_trimmed)" '{ $p = 1; $q = 1e-06; print }' \
    "$report/points/$slow.csv" >"$dir/doctored/points/$slow.csv"
(cd "$GB_ROOT" && sh bench/report_finish.sh "$dir/doctored" "$GB_BIN" doctored) >/dev/null 2>&1
last=$(awk -F, '$1 == "cornell" { id = $8 } END { print id }' "$dir/doctored/pareto.csv")
ok "$([ -n "$slow" ] && [ "$last" = "$slow" ]; echo $?)" \
    "a point with the largest relative MSE but the smallest trimmed one ends its scene's front ($slow; last: $last)"

grep -q "Pareto front (by trimmed relative MSE" "$report/index.html" && grep -q "relative_mse_trimmed" "$report/index.html" &&
    grep -q "direct_share" "$report/index.html"
ok $? "index.html: the front tables, what relative_mse_trimmed and direct_share are"

bake=$(awk -F, -v w="$(col bake_wall_s)" -v b="$(col bake_bytes)" \
    'NR > 1 && ($3 == "topo" || $3 == "octree") && ($w == "" || $b + 0 <= 0) { print $4 }' "$csv")
ok "$([ -z "$bake" ]; echo $?)" "topo and octree rows have bake seconds (TIME_BAKE) and bytes${bake:+ (not: $bake)}"

none=$(err two-rooms topo visibilitynone own_rel_mse)
full=$(err two-rooms topo visibilityfull own_rel_mse)
none_f=$(err two-rooms topo visibilitynone full_rel_mse)
full_f=$(err two-rooms topo visibilityfull full_rel_mse)
echo "# two rooms, topo vs reference --vpl: no visibility $none, full $full; vs full: $none_f, $full_f"
awk -v a="$full" -v b="$none" 'BEGIN { exit !(a != "" && b != "" && a + 0 <= b + 0) }'
ok $? "two rooms: topo with full visibility at most the error of no visibility (same VPLs)"

e1=$(err cornell flc -f1- own_rel_mse)
e16=$(err cornell flc -f16- own_rel_mse)
echo "# Cornell flc vs indirect1-unshadowed: 1 frame $e1, 16 frames $e16"
below "$e16" "$e1"
ok $? "flc: 16 frames below 1 frame"

# flc-iv's door test against the shadowed one bounce is flc_iv.t's; here
# the two rooms' figures against the full solution only go to the log.
flc=$(err two-rooms flc . full_rel_mse)
iv=$(err two-rooms flc-iv . full_rel_mse)
echo "# two rooms vs reference --mode full: flc $flc, flc-iv $iv"

# cluster --tolerance 0 (K_max VDLs a leaf always) against the default 0.2:
# the count chosen by the error is never above K_max, so never more bytes.
chosen=$(err cornell octree -t0.2- bake_bytes)
always=$(err cornell octree -t0- bake_bytes)
echo "# Cornell octree .lot bytes: tolerance 0.2 $chosen, 0 (K_max always) $always"
[ "$(err cornell octree -t0.2- tolerance)" = 0.2 ] && [ "$(err cornell octree -t0- tolerance)" = 0 ] &&
    awk -v a="$chosen" -v b="$always" 'BEGIN { exit !(a + 0 > 0 && a + 0 < b + 0) }'
ok $? "octree rows carry their tolerance; 0.2 makes a smaller .lot than K_max always"

# cluster --interpolation surface against trilinear, the same photons and
# settings: make report's sweep measures it 0.8x trilinear's error on the
# Cornell box (docs/figures.md, "light octree: surface interpolation").
trilinear=$(err cornell octree -t0.2-64x64 own_rel_mse)
surface=$(err cornell octree -t0.2-surface- own_rel_mse)
echo "# Cornell octree against its own reference: trilinear $trilinear, surface $surface"
[ "$(err cornell octree -t0.2-surface- interpolation)" = surface ] &&
    [ "$(err cornell octree -t0.2-64x64 interpolation)" = trilinear ] && below "$surface" "$trilinear"
ok $? "octree rows carry their interpolation; surface below trilinear on the Cornell box"

direct=$(err cornell direct . full_rel_mse)
octree=$(err cornell octree -t0.2- full_rel_mse)
implicit=$(err cornell implicit . full_rel_mse)
echo "# Cornell vs reference --mode full: direct $direct, octree $octree, implicit $implicit"
below "$octree" "$direct"
ok $? "octree below direct light alone against the full reference"
below "$implicit" "$direct"
ok $? "implicit below direct light alone against the full reference"

refs=$report/references.csv
wrong=$(awk -F, 'NR > 1 && ($7 == "" || $9 == "" || ($7 + 0 < $9 + 0) != ($10 == "ok")) { print $1 }' "$refs")
ok "$([ -s "$refs" ] && [ -z "$wrong" ]; echo $?)" "references.csv: each floor against the smallest error it meets, ok or void${wrong:+ (not: $wrong)}"
unsaid=
for r in $(awk -F, 'NR > 1 && $10 == "void" { print $1 }' "$refs"); do
    echo "# comparison void: $r"
    grep -q "comparison void: reference $r " "$report/index.html" || unsaid="$unsaid $r"
done
ok "$([ -z "$unsaid" ]; echo $?)" "index.html states every void comparison${unsaid:+ (not:$unsaid)}"

# segment --evaluate of each topo bake: a row each, fractions in [0, 1]; on
# the two rooms "same cluster" predicts visibility better than chance (its
# precision above the fraction of all pairs that see each other).
segments=$report/segments.csv
bakes=$(awk -F, 'NR > 1 && $3 == "topo" { print $19 }' "$csv" | sort -u | wc -l)
bad=$(awk -F, 'NR > 1 && ($4 != 100000 || $7 < 1) { print $3 }
    NR > 1 { for (i = 5; i <= 12; i++) if (i != 7 && i != 8 && !($i >= 0 && $i <= 1 && $i != "")) { print $3; next } }' "$segments")
ok "$([ "$(($(wc -l <"$segments") - 1))" = "$bakes" ] && [ -z "$bad" ]; echo $?)" \
    "segments.csv: a segment --evaluate row for each of the $bakes topo bakes, fractions in [0, 1]${bad:+ (not: $bad)}"
read -r visible precision <<EOF2
$(awk -F, 'NR > 1 && $1 == "two-rooms" { print $5, $9 }' "$segments")
EOF2
echo "# two rooms: visible pairs $visible, same-cluster precision $precision"
below "$visible" "$precision"
ok $? "two rooms: same cluster predicts visibility better than chance"
grep -q '^| two-rooms | ' "$report/readme-segment-table.md"
ok $? "readme-segment-table.md: the two rooms' row"

missing_img=
for id in $(awk -F, 'NR > 1 { print $4 }' "$csv"); do
    for f in "img/$id.png" "img/$id-heat.png"; do
        [ -s "$report/$f" ] && grep -q "src=\"$f\"" "$report/index.html" || missing_img="$missing_img $f"
    done
done
ok "$([ -z "$missing_img" ]; echo $?)" "gallery: every point's frame and heatmap, on the page${missing_img:+ (not:$missing_img)}"
plots=0
for s in cornell cornell-original two-rooms; do
    for f in "$s-error-frame.png" "$s-error-frame.svg" "$s-error-bake.svg"; do
        [ -s "$report/plots/$f" ] || plots=1
    done
done
ok $plots "plots: error against ms and against bake time, PNG and SVG, per scene"
[ -s "$report/plots/octree-bytes.svg" ] && grep -q 'src="plots/octree-bytes.svg"' "$report/index.html"
ok $? "plots: the octree's bytes against its error, on the page"
n=$(grep -c "best under \(50\|200\|1000\) ms a frame" "$report/index.html")
ok "$([ "$n" = 9 ]; echo $?)" "index.html: best under 50 / 200 / 1000 ms for each of the 3 scenes ($n lines)"
rows=$(($(wc -l <"$report/pareto.csv") - 1))
table=$(grep -c '^| [a-z]' "$report/readme-table.md")
ok "$([ "$rows" -ge 3 ] && [ "$table" = "$((rows + 1))" ]; echo $?)" "readme-table.md: the Pareto fronts ($rows rows) and a caption"

cp "$csv" "$dir/results.first"
renders=$(wc -l <"$report/render.log")
run_report "$dir/log2"
ok $? "make report again: exit 0"
again=$(grep -c "report: render" "$dir/log2")
ok "$([ "$again" = 0 ] && [ "$(wc -l <"$report/render.log")" = "$renders" ]; echo $?)" \
    "the second make report renders nothing ($again renders)"
cmp -s "$csv" "$dir/results.first"
ok $? "results.csv unchanged by the second run"

printf 'scene c scenes/cornell/cornell.scene\nc flc navg=64 colour=red\n' >"$dir/bad.sweep"
(cd "$GB_ROOT" && sh bench/report_rules.sh "$dir/bad.sweep" "$dir/bad") >/dev/null 2>"$dir/err"
status=$?
ok "$([ $status != 0 ] && grep -q "bad.sweep:2: unknown key \"colour\"" "$dir/err"; echo $?)" \
    "a bad sweep line: fails, naming file:line and the key"

tap_done
