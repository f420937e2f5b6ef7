#!/bin/sh
# report_finish.sh REPORT BIN SWEEP — the last step of make report: gathers
# REPORT/points/*.csv in sweep order (REPORT/points.tsv) into results.csv,
# the references and their noise floors into references.csv, each scene's
# Pareto front (least relative_mse_trimmed against reference --mode full,
# imgdiff's relative MSE with the 0.1 % largest pixel errors left out, for
# the time to the image) into pareto.csv, each topo bake's segment --evaluate into
# segments.csv, the plots (gnuplot, PNG and SVG) into plots/, the page
# index.html and the tables of docs/figures.md, readme-table.md and
# readme-segment-table.md.
#
# Each point gets the direct pass's error of its scene and size (the column
# direct_pass_rel_mse of the direct point with the same full reference,
# bench/report_point.sh) and direct_share, that error over the point's
# full_rel_mse: how much of the point's error its direct pass alone makes.
#
# A reference's comparison is void when its noise floor (relative MSE
# between its seed-0 and seed-1 images) is not below the smallest error
# measured against it: references.csv says "void", index.html says it.
set -e
report=$1 bin=$2 sweep=$3
cd "$report"
header="scene,scene_hash,method,point,resolution,frames,spp,vplspp,navg,tiling,bins,bounces,vpls,visibility,voxels,photons,depth,vdls,bake,bake_wall_s,bake_cpu_s,voxelize_wall_s,voxelize_cpu_s,voxelize_rss_kib,thin_wall_s,thin_cpu_s,thin_rss_kib,segment_wall_s,segment_cpu_s,segment_rss_kib,photons_wall_s,photons_cpu_s,photons_rss_kib,cluster_wall_s,cluster_cpu_s,cluster_rss_kib,bake_bytes,gbview_rss_kib,frame_ms,frame_first_ms,passes_ms,full_ref,full_rel_mse,full_mse_srgb8,full_psnr,full_max_error,full_floor_rel_mse,full_floor_mse_srgb8,full_within_2x_floor,own_ref,own_rel_mse,own_mse_srgb8,own_psnr,own_max_error,own_floor_rel_mse,own_floor_mse_srgb8,own_within_2x_floor,time_ms,status,full_rel_mse_trimmed,own_rel_mse_trimmed,direct_pass_rel_mse,direct_share,tolerance,interpolation"
# Columns (results.csv): 42 full_ref, 43 full_rel_mse, 51 own_rel_mse, 58
# time_ms, 59 status, 60 full_rel_mse_trimmed, 61 own_rel_mse_trimmed, 62
# direct_pass_rel_mse (the direct points': bench/report_point.sh; the others'
# copied here from the direct point of the same full reference, the first in
# the sweep), 63 direct_share = 62 / 43, 64 tolerance and 65 interpolation
# (octree: cluster --tolerance and --interpolation; the last two columns of
# points.tsv).
{
    echo "$header"
    cut -f 1 points.tsv | while read -r id; do cat "points/$id.csv"; done
} | awk -F, -v OFS=, '
    BEGIN { while ((getline line < "points.tsv") > 0) { n = split(line, f, "\t"); tolerance[f[1]] = f[n - 1]; interpolation[f[1]] = f[n] } }
    { row[NR] = $0 }
    NR > 1 && $3 == "direct" && $59 == "ok" && !($42 in pass) { pass[$42] = $62 }
    END {
        print row[1]
        for (i = 2; i <= NR; i++) { $0 = row[i]
            if ($59 == "ok" && $62 == "" && ($42 in pass)) $62 = pass[$42]
            $63 = ($62 != "" && $43 + 0 > 0) ? sprintf("%.4g", $62 / $43) : ""
            $64 = tolerance[$4]
            $65 = interpolation[$4]
            print }
    }' >results.csv.tmp

# The references: floor and the smallest error compared with each.
{
    echo "reference,scene,mode,resolution,spp,seed0_wall_s,floor_rel_mse,floor_mse_srgb8,smallest_error,status"
    while IFS="$(printf '\t')" read -r ref name mode res spp; do
        floor=$(awk '$1 == "relative_mse" { print $2 }' "ref/$ref.floor")
        floor8=$(awk '$1 == "mse_srgb8" { print $2 }' "ref/$ref.floor")
        wall=$(awk '{ print $1 }' "ref/$ref-seed0.exr.time" 2>/dev/null | tail -n 1)
        awk -F, -v ref="$ref" -v floor="$floor" -v floor8="$floor8" -v name="$name" -v mode="$mode" \
            -v res="$res" -v spp="$spp" -v wall="$wall" '
            NR > 1 && $42 == ref && (min == "" || $43 + 0 < min) { min = $43 + 0 }
            NR > 1 && $50 == ref && (min == "" || $51 + 0 < min) { min = $51 + 0 }
            END { printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", ref, name, mode, res, spp, wall, floor, floor8, min,
                  (floor + 0 < min + 0 ? "ok" : "void") }' results.csv.tmp
    done <refs.tsv
} >references.csv.tmp

# settings of a row (awk function shared below)
settings='function settings(m,   s) {
    if (m == "flc") s = "navg=" $9 " frames=" $6 ($10 + 0 ? " tiling=" $10 : "")
    else if (m == "flc-iv") s = "navg=" $9 " frames=" $6 ($10 + 0 ? " tiling=" $10 : "") " bins=" $11
    else if (m == "implicit") s = "bins=" $11 " bounces=" $12
    else if (m == "topo") s = "vpls=" $13 " visibility=" $14 " voxels=" $15
    else if (m == "octree") s = "photons=" $16 " depth=" $17 " vdls=" $18 " tolerance=" $64 ($65 == "surface" ? " interpolation=surface" : "")
    else s = "-"
    return s " " $5
}'

# Pareto front per scene: by ms to the image, each point with a smaller
# full_rel_mse_trimmed than every faster one. pareto.csv's columns 1-8 are
# as they were when the front was by full_rel_mse; 9 and 10 follow.
awk -F, "$settings"'
    NR > 1 && $59 == "ok" { n++; sc[n] = $1; ms[n] = $58 + 0; err[n] = $60 + 0; plain[n] = $43; m[n] = $3; set[n] = settings($3); id[n] = $4; own[n] = $51; bk[n] = $20; share[n] = $63 }
    END {
        print "scene,method,settings,time_ms,full_rel_mse,own_rel_mse,bake_wall_s,point,full_rel_mse_trimmed,direct_share"
        for (i = 1; i <= n; i++) if (!(sc[i] in done)) {
            done[sc[i]] = 1; k = 0
            for (j = 1; j <= n; j++) if (sc[j] == sc[i]) idx[++k] = j
            for (a = 2; a <= k; a++) for (b = a; b > 1 && ms[idx[b]] < ms[idx[b - 1]]; b--) { t = idx[b]; idx[b] = idx[b - 1]; idx[b - 1] = t }
            best = ""
            for (a = 1; a <= k; a++) { j = idx[a]
                if (best == "" || err[j] < best) { best = err[j]
                    printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", sc[j], m[j], set[j], ms[j], plain[j], own[j], bk[j], id[j], err[j], share[j] } }
        }
    }' results.csv.tmp >pareto.csv.tmp
# segment --evaluate of each topo bake (bake/CONFIG/segment-evaluate.txt).
{
    echo "scene,voxels,bake,pairs,visible,unlocated,clusters,gates,same_cluster_precision,same_cluster_recall,one_gate_precision,one_gate_recall,seconds"
    while IFS="$(printf '\t')" read -r bake name voxels; do
        awk -v name="$name" -v voxels="$voxels" -v bake="$bake" '
            $1 == "pairs" { pairs = $2 } $1 == "visible" { visible = $2 } $1 == "unlocated" { unlocated = $2 }
            $1 == "clusters" { clusters = $2 } $1 == "gates" { gates = $2 } $1 == "seconds" { seconds = $2 }
            $1 == "same-cluster" { sp = $2; sr = $3 } $1 == "one-gate" { gp = $2; gr = $3 }
            END { printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", name, voxels, bake, pairs, visible, unlocated,
                  clusters, gates, sp, sr, gp, gr, seconds }' "bake/$bake/segment-evaluate.txt"
    done <segments.tsv
} >segments.csv.tmp
mv segments.csv.tmp segments.csv
mv results.csv.tmp results.csv
mv references.csv.tmp references.csv
mv pareto.csv.tmp pareto.csv
scenes=$(cut -f 2 points.tsv | awk '!seen[$0]++')

# Plots.
mkdir -p plots
plots_ok=1
if command -v gnuplot >/dev/null; then
    for s in $scenes; do
        for m in direct topo octree flc implicit flc-iv; do
            awk -F, -v s="$s" -v m="$m" 'NR > 1 && $59 == "ok" && $1 == s && $3 == m { print $58, $60, ($20 == "" ? 0 : $20) }' results.csv \
                >"plots/$s-$m.dat"
        done
        awk -F, -v s="$s" 'NR > 1 && $1 == s { print $4, $9 }' pareto.csv >"plots/$s-pareto.dat"
    done
    awk -F, 'NR > 1 && $3 == "topo" && $20 != "" && !seen[$19]++ { print $15, $20, $37 }' results.csv | sort -n >plots/voxels.dat
    awk -F, 'NR > 1 && $3 == "octree" && $20 != "" && !seen[$19]++ { print $16, $20, $37 }' results.csv | sort -n >plots/photons.dat
    awk -F, 'NR > 1 && $59 == "ok" { split($5, r, "x"); print r[1] * r[2], $39, $1 "-" $3 }' results.csv | sort -n >plots/resolution.dat
    awk -F, 'NR > 1 && $59 == "ok" && $3 == "topo" { print $13, $39 }' results.csv | sort -n >plots/vpls.dat
    # the octree's bytes against its own error, one series a scene, photon count and depth
    rm -f plots/octree-bytes-*.dat
    awk -F, 'NR > 1 && $59 == "ok" && $3 == "octree" { print $37, $61, $64, $18 > ("plots/octree-bytes-" $1 "-p" $16 "-d" $17 ".dat") }' results.csv
    for term in png svg; do
        if [ $term = png ]; then t="set terminal png size 800,560"; else t="set terminal svg size 800,560"; fi
        for s in $scenes; do
            plot= plot2=
            for m in direct topo octree flc implicit flc-iv; do
                [ -s "plots/$s-$m.dat" ] || continue
                plot="$plot${plot:+, }'plots/$s-$m.dat' using 1:2 with points pointsize 1.5 title '$m'"
                plot2="$plot2${plot2:+, }'plots/$s-$m.dat' using (\$3 > 0 ? \$3 : 0.01):2 with points pointsize 1.5 title '$m'"
            done
            gnuplot <<EOF || plots_ok=0
$t
set output 'plots/$s-error-frame.$term'
set title "$s: error against reference --mode full, for the frame time"
set logscale xy
set xlabel 'ms to the image (wall; flc, flc-iv: frames x frame ms)'
set ylabel 'relative MSE, the 0.1 % largest pixel errors left out'
set key outside right
plot $plot, 'plots/$s-pareto.dat' using 1:2 with steps linewidth 2 linecolor rgb 'black' title 'Pareto front'
set output 'plots/$s-error-bake.$term'
set title "$s: error against bake time (no bake: shown at 0.01 s)"
set xlabel 'bake s (wall, every tool)'
plot $plot2
EOF
        done
        gnuplot <<EOF || plots_ok=0
$t
set logscale xy
set key outside right
set output 'plots/cost-voxels.$term'
set title 'topo bake against voxel resolution'
set xlabel 'voxelize -r'
set ylabel 'bake s (wall)'
set y2label 'bytes (.seg + .grid.vdb)'
set y2tics
set logscale y2
plot 'plots/voxels.dat' using 1:2 with linespoints title 'bake s', '' using 1:3 axes x1y2 with linespoints title 'bytes'
set output 'plots/cost-photons.$term'
set title 'octree bake against photon count'
set xlabel 'photons -n'
set y2label 'bytes (.lot)'
plot 'plots/photons.dat' using 1:2 with linespoints title 'bake s', '' using 1:3 axes x1y2 with linespoints title 'bytes'
unset y2label
unset y2tics
set output 'plots/cost-resolution.$term'
set title 'frame ms against pixels (every point)'
set xlabel 'pixels'
set ylabel 'frame ms'
plot 'plots/resolution.dat' using 1:2 with points title 'points'
set output 'plots/cost-vpls.$term'
set title 'topo frame ms against VPL count'
set xlabel 'VPLs'
plot 'plots/vpls.dat' using 1:2 with points title 'topo'
EOF
        plot=
        for f in plots/octree-bytes-*.dat; do
            [ -s "$f" ] || continue
            series=${f#plots/octree-bytes-}
            plot="$plot${plot:+, }'$f' using 1:2 with points pointsize 1.5 title '${series%.dat}', '' using 1:2:(sprintf('k%d t%s', \$4, strcol(3))) with labels offset 0,1 font ',8' notitle"
        done
        [ -z "$plot" ] || gnuplot <<EOF || plots_ok=0
$t
set logscale xy
set key outside right
set output 'plots/octree-bytes.$term'
set title 'light octree: bytes against the error of its indirect term'
set xlabel 'bytes (.lot)'
set ylabel 'relative MSE against full --min-bounces 2, trimmed'
plot $plot
EOF
    done 2>plots/gnuplot.log
else
    plots_ok=0
    echo "report_finish.sh: gnuplot not found (Debian gnuplot-nox): no plots" >&2
fi

# docs/figures.md's report table: each scene's Pareto front and the best under budgets.
date=$(date -u +%Y-%m-%d)
load=$(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null || echo '?')
awk -F, -v sweep="$sweep" -v date="$date" -v load="$load" '
    FNR == 1 { file++ }
    file == 1 && FNR > 1 { rows[++n] = $0 }
    END {
        printf "`make report SWEEP=%s` (bench/report_finish.sh from results.csv), %s, load average %s at the end. ", sweep, date, load
        print "Each scene'"'"'s Pareto front: the points no faster point beats on relative MSE against `reference --mode full` with the 0.1 % largest per-pixel errors left out (imgdiff'"'"'s `relative_mse_trimmed`); ms to the image, wall, on llvmpipe (flc and flc-iv: their frames times the frame ms). Direct share: the error the direct pass alone makes (the `direct` point'"'"'s, weighed against the full solution) over the point'"'"'s relative MSE.\n"
        print "| scene | method | settings | ms to the image | trimmed rel. MSE vs full | rel. MSE vs full | rel. MSE vs own reference | direct share | bake s |"
        print "|---|---|---|---:|---:|---:|---:|---:|---:|"
        for (i = 1; i <= n; i++) { split(rows[i], f, ",")
            printf "| %s | %s | %s | %.1f | %.5f | %.5f | %.5f | %s | %s |\n", f[1], f[2], f[3], f[4], f[9], f[5], f[6], (f[10] == "" ? "-" : sprintf("%.2f", f[10])), (f[7] == "" ? "-" : f[7]) }
    }' pareto.csv >readme-table.md

# docs/figures.md's segment table, from segments.csv.
awk -F, -v sweep="$sweep" -v date="$date" '
    NR == 1 { next }
    { rows[++n] = $0 }
    END {
        if (n == 0) exit
        printf "`make report SWEEP=%s` (bench/report_finish.sh from segments.csv), %s: `segment --evaluate --pairs 100000 --seed 0` of each topo bake (the bake rules'"'"' default options).\n\n", sweep, date
        print "| scene | voxelize -r | clusters / gates | visible pairs | same-cluster precision / recall | one-gate precision / recall |"
        print "|---|---:|---|---:|---|---|"
        for (i = 1; i <= n; i++) { split(rows[i], f, ",")
            printf "| %s | %s | %s / %s | %s | %s / %s | %s / %s |\n", f[1], f[2], f[7], f[8], f[5], f[9], f[10], f[11], f[12] }
    }' segments.csv >readme-segment-table.md

# index.html
esc() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g'; }
{
    cat <<EOF
<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>gibake make report</title>
<style>body{font-family:sans-serif;margin:1em 2em}table{border-collapse:collapse;font-size:80%}
td,th{border:1px solid #ccc;padding:2px 5px;text-align:right}td:first-child{text-align:left}
img.px{image-rendering:pixelated;width:160px}.void{color:#b00;font-weight:bold}</style></head><body>
<h1>gibake: speed against error</h1>
<p>Sweep <code>$(echo "$sweep" | esc)</code>, $(date -u '+%Y-%m-%d %H:%M UTC'), load average $load.
Error: relative MSE of the frame (<code>--terms both</code>) against <code>reference --mode full</code>,
and of the method's own term against its own reference (direct: <code>--mode direct</code>; flc: <code>indirect1-unshadowed</code>; flc-iv: <code>indirect1</code>;
implicit: <code>indirect1</code>; octree: <code>full --min-bounces 2</code>; topo: <code>reference --vpl</code> of the same VPLs).
Frame ms: the mean <code>frame (wall)</code> of <code>gbview --timings</code> on llvmpipe (frames after the first; with one frame, the first, one-time passes included);
ms to the image: the frame ms, times the frames for flc and flc-iv, which accumulate them. Plots, Pareto fronts and budgets use ms to the image.
Timings were taken while other jobs may have shared the cores; the assertions of tests/cli/report.t never read them.
Data: <a href="results.csv">results.csv</a>, <a href="references.csv">references.csv</a>, <a href="pareto.csv">pareto.csv</a>.
Rows whose status is not ok (a failed or timed-out render) have no errors and are left out of the plots and fronts.</p>
<p>Relative MSE is the mean over the pixels and channels of (a - b)² / (b² + 0.01), so a few pixels can decide it (a shadow edge of the direct pass, a light leak).
<br><b>Trimmed</b> (<code>relative_mse_trimmed</code> of <code>imgdiff</code>): the same mean with the floor(pixels / 1000) pixels of largest relative error (mean over their channels) left out
(0.1 %: 4 of a 64×64 frame, 9 of 96×96); the Pareto fronts, their plots and the budgets use it against the full reference.
<br><b>Direct share</b> (<code>direct_share</code>): the direct pass's error over the point's relative MSE (both against the full reference). The direct pass's error is measured once per scene and size,
on the <code>direct</code> point: the full reference plus (its frame − <code>reference --mode direct</code>) compared with the full reference,
the error a frame with this direct pass and a perfect indirect term would have. Every method draws the same direct pass, so a share near 1 says
the point's error is the direct pass's, not its indirect term's; none when the sweep has no <code>direct</code> point of that scene and size.
(The direct-only frame's own error against the full reference is the <code>direct</code> row's relative MSE: mostly the missing indirect light.)</p>
EOF
    echo "<h2>Noise floors of the references</h2>"
    awk -F, 'NR > 1 && $10 == "void" { printf "<p class=\"void\">comparison void: reference %s (noise floor %s) is not below the smallest error compared with it (%s)</p>\n", $1, $7, $9 }' references.csv
    echo "<table><tr><th>reference</th><th>mode</th><th>size</th><th>spp</th><th>seed 0 s</th><th>floor rel. MSE</th><th>floor 8-bit MSE</th><th>smallest error</th><th>status</th></tr>"
    awk -F, 'NR > 1 { printf "<tr><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td></tr>\n", $1, $3, $4, $5, $6, $7, $8, $9, $10 }' references.csv
    echo "</table>"
    for s in $scenes; do
        echo "<h2>$s</h2>"
        for budget in 50 200 1000; do
            awk -F, -v s="$s" -v b="$budget" 'NR > 1 && $1 == s && $4 + 0 <= b { best = $2 ", " $3 ", " $4 " ms, trimmed rel. MSE " $9 " (rel. MSE " $5 ")" }
                END { printf "<p>best under %d ms a frame: %s</p>\n", b, (best == "" ? "none in the sweep" : best) }' pareto.csv
        done
        if [ $plots_ok = 1 ]; then
            echo "<p><img src=\"plots/$s-error-frame.svg\" width=\"600\"> <img src=\"plots/$s-error-bake.svg\" width=\"600\"></p>"
        fi
        echo "<p>Pareto front (by trimmed relative MSE against the full reference):</p>"
        echo "<table><tr><th>method</th><th>settings</th><th>ms to the image</th><th>trimmed rel. MSE full</th><th>rel. MSE full</th><th>own</th><th>direct share</th><th>bake s</th></tr>"
        awk -F, -v s="$s" 'NR > 1 && $1 == s { printf "<tr><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td></tr>\n", $2, $3, $4, $9, $5, $6, $10, $7 }' pareto.csv
        echo "</table><p>Every point:</p>"
        echo "<table><tr><th>point</th><th>frame</th><th>reference (full)</th><th>heatmap</th><th>ms to the image</th><th>trimmed rel. MSE full</th><th>rel. MSE full</th><th>own</th><th>own trimmed</th><th>direct share</th><th>status</th></tr>"
        awk -F, -v s="$s" 'NR > 1 && $1 == s { printf "<tr><td>%s</td><td><img class=\"px\" src=\"img/%s.png\"></td><td><img class=\"px\" src=\"ref/%s-seed0.png\"></td><td><img class=\"px\" src=\"img/%s-heat.png\"></td><td>%s</td><td>%s</td><td>%s%s</td><td>%s%s</td><td>%s</td><td>%s</td><td>%s</td></tr>\n", $4, $4, $42, $4, $58, $60, $43, ($49 == 1 ? " (within 2× floor)" : ""), $51, ($57 == 1 ? " (within 2× floor)" : ""), $61, $63, $59 }' results.csv
        echo "</table>"
    done
    if [ $plots_ok = 1 ]; then
        echo "<h2>Cost scaling</h2><p>"
        for p in voxels photons resolution vpls; do echo "<img src=\"plots/cost-$p.svg\" width=\"600\">"; done
        [ ! -s plots/octree-bytes.svg ] || echo "<img src=\"plots/octree-bytes.svg\" width=\"600\">"
        echo "</p>"
    fi
    if [ "$(wc -l <segments.csv)" -gt 1 ]; then
        echo "<h2>Segmentation (segment --evaluate, 100 000 pairs)</h2><table><tr>"
        head -n 1 segments.csv | tr , '\n' | sed 's|.*|<th>&</th>|' | tr -d '\n'
        echo "</tr>"
        awk -F, 'NR > 1 { printf "<tr>"; for (i = 1; i <= NF; i++) printf "<td>%s</td>", $i; print "</tr>" }' segments.csv
        echo "</table>"
    fi
    if [ -s lightmap.md ]; then
        echo "<h2>Lightmap (bench/lightmap.sh): bake CPU time against the lightmap's error</h2>"
        echo "<p>$(head -n 1 lightmap.md | esc). Relative MSE per texel against the truth," \
            "(a - b)² / (b² + 0.01 mean(b)²), on the texels the camera sees, those 5 or more from a chart's edge, every covered one;" \
            "the ratio of means one texel in from the charts' edges, the worst chart's and the dark texels' (truth under a tenth of the mean).</p><table>"
        awk -F'|' '/^\|/ && !/^\|---/ { tag = (n++ ? "td" : "th"); printf "<tr>";
            for (i = 2; i < NF; i++) { gsub(/^ +| +$/, "", $i); printf "<%s>%s</%s>", tag, $i, tag }
            print "</tr>" }' lightmap.md
        echo "</table>"
    fi
    echo "<h2>Every point</h2><table><tr>"
    head -n 1 results.csv | tr , '\n' | sed 's|.*|<th>&</th>|' | tr -d '\n'
    echo "</tr>"
    awk -F, 'NR > 1 { printf "<tr>"; for (i = 1; i <= NF; i++) printf "<td>%s</td>", $i; print "</tr>" }' results.csv | sed 's/"//g'
    echo "</table></body></html>"
} >index.html.tmp
mv index.html.tmp index.html
echo "report: $(($(wc -l <results.csv) - 1)) points, $(($(wc -l <references.csv) - 1)) references, $(grep -c ',void$' references.csv || true) void"
