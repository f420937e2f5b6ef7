#!/bin/sh
# report_point.sh REPORT BIN ID NAME SCENE METHOD WxH FRAMES BAKE FULLREF OWNREF "FLAGS"
# — one point of make report (bench/report_rules.sh writes the calls).
#
# Renders SCENE headless with gbview --method METHOD FLAGS --timings: the
# whole frame (--terms both, timed, compared with FULLREF, the reference's
# --mode full) and, for the indirect methods, the indirect term alone
# (compared with OWNREF, the method's own reference); direct's own
# comparison is its frame against reference --mode direct. Writes
# REPORT/points/ID.csv (one row, the columns of bench/report_finish.sh's
# header but the last three, direct_share, tolerance and interpolation,
# which report_finish.sh adds),
# REPORT/img/ID.png (the frame), ID-heat.png (imgdiff --heatmap against
# FULLREF) and appends "render ID" to REPORT/render.log.
#
# direct_pass_rel_mse, for a direct point only (report_finish.sh copies it
# to the other points of its scene and size): FULLREF + (frame - OWNREF) is
# the full solution with the direct pass's error added, OWNREF being the
# direct reference; its relative MSE against FULLREF is the direct pass's
# error on the scale of the full solution, the error a frame with this
# direct pass and a perfect indirect term would have.
set -e
report=$1 bin=$2 id=$3 name=$4 scene=$5 method=$6 res=$7 frames=$8 bake=$9
shift 9
fullref=$1 ownref=$2 flags=$3
img=$report/img
mkdir -p "$img" "$report/points"
echo "report: render $id"
echo "render $id" >>"$report/render.log"

bakeflag=
[ "$bake" = - ] || bakeflag="--bake $report/bake/$bake"
# A render that fails or outlasts REPORT_TIMEOUT seconds (default 900) gives
# a row whose status says so, with no errors; the report goes on.
limit="timeout ${REPORT_TIMEOUT:-900}"
time="/usr/bin/time -f %e_%U_%S_%M -o"
status=ok
# shellcheck disable=SC2086
$time "$img/$id.gbview.time" $limit "$bin/gbview" --headless --quiet --timings --method "$method" \
    --frames "$frames" --resolution "$res" $bakeflag $flags "$scene" -o "$img/$id.exr" \
    >"$img/$id.timings" || status="failed: gbview exit $?"
if [ "$status" != ok ]; then
    params=$(awk -F '\t' -v id="$id" '$1 == id { s = $5; for (i = 6; i <= 18; i++) s = s "," $i; print s; exit }' \
        "$report/points.tsv")
    echo "report: $id: $status" >&2
    echo "$name,,$method,$id,$params,$bake$(printf ',%.0s' $(seq 1 38)),$status,,," >"$report/points/$id.csv"
    exit 0
fi
if [ "$method" = direct ]; then
    cp "$img/$id.exr" "$img/$id.own.exr"
else
    # shellcheck disable=SC2086
    $limit "$bin/gbview" --headless --quiet --terms indirect --method "$method" --frames "$frames" \
        --resolution "$res" $bakeflag $flags "$scene" -o "$img/$id.own.exr"
fi
oiiotool "$img/$id.exr" --colorconvert linear sRGB -o "$img/$id.png" 2>/dev/null \
    || oiiotool "$img/$id.exr" -o "$img/$id.png"
"$bin/imgdiff" --heatmap "$img/$id-heat.png" "$img/$id.exr" "$report/ref/$fullref-seed0.exr" \
    >"$img/$id.full.diff"
"$bin/imgdiff" "$img/$id.own.exr" "$report/ref/$ownref-seed0.exr" >"$img/$id.own.diff"
if [ "$method" = direct ]; then
    oiiotool "$report/ref/$fullref-seed0.exr" "$img/$id.exr" --add "$report/ref/$ownref-seed0.exr" \
        --sub -d float -o "$img/$id.direct-pass.exr"
    "$bin/imgdiff" "$img/$id.direct-pass.exr" "$report/ref/$fullref-seed0.exr" >"$img/$id.direct-pass.diff"
fi

# key value file -> the value of the line "key value"
field() { awk -v k="$1" '$1 == k { print $2; exit }' "$2"; }
# mean_ms of a --timings line
pass_ms() { awk -v p="$1" 'index($0, p) == 1 { print $(NF - 1); exit }' "$img/$id.timings"; }
hash=$("$bin/scene-info" --quiet "$scene" | awk '$1 == "hash" { print $2 }')
frame_ms=$(pass_ms "frame (wall)")
frame_first_ms=$(awk 'index($0, "frame (wall)") == 1 { print $NF }' "$img/$id.timings")
passes=$(awk 'NR > 1 && $0 !~ /^frame/ { n = NF - 2; s = $1; for (i = 2; i <= n; i++) s = s " " $i;
    printf "%s%s=%s", sep, s, $(NF - 1); sep = ";" }' "$img/$id.timings")
gbview_rss=$(tr _ ' ' <"$img/$id.gbview.time" | awk '{ print $4 }')

# Bake: per tool wall and CPU seconds and peak RSS from GNU time (TIME_BAKE),
# bytes of the files the method loads.
base=$(basename "$scene" .scene)
bake_cols=
bake_wall=0 bake_cpu=0 bytes=0
for tool in voxelize thin segment photons cluster; do
    t="$report/bake/$bake/$base.$tool.time"
    if [ "$bake" != - ] && [ -r "$t" ]; then
        set -- $(tail -n 1 "$t")
        cpu=$(awk -v u="$2" -v s="$3" 'BEGIN { printf "%.2f", u + s }')
        bake_cols="$bake_cols,$1,$cpu,$4"
        bake_wall=$(awk -v a="$bake_wall" -v b="$1" 'BEGIN { printf "%.2f", a + b }')
        bake_cpu=$(awk -v a="$bake_cpu" -v b="$cpu" 'BEGIN { printf "%.2f", a + b }')
    else
        bake_cols="$bake_cols,,,"
    fi
done
case $method in
topo) files="$base.seg $base.grid.vdb" ;;
octree) files="$base.lot" ;;
*) files= ;;
esac
for f in $files; do
    bytes=$((bytes + $(wc -c <"$report/bake/$bake/$f")))
done
[ "$bake" = - ] && bake_wall= bake_cpu=

# Errors against both references, their noise floors, the 2x flag.
errors() { # DIFF FLOOR REF
    awk -v ref="$3" '
        FNR == 1 { file++ }
        file == 1 { e[$1] = $2 } file == 2 { f[$1] = $2 }
        END { within = (e["relative_mse"] <= 2 * f["relative_mse"]) ? 1 : 0
              printf "%s,%s,%s,%s,%s,%s,%s,%d", ref, e["relative_mse"], e["mse_srgb8"], e["psnr"],
                  e["max_error"], f["relative_mse"], f["mse_srgb8"], within }' "$1" "$2"
}
full_cols=$(errors "$img/$id.full.diff" "$report/ref/$fullref.floor" "$fullref")
own_cols=$(errors "$img/$id.own.diff" "$report/ref/$ownref.floor" "$ownref")
trimmed_cols=$(field relative_mse_trimmed "$img/$id.full.diff"),$(field relative_mse_trimmed "$img/$id.own.diff")
direct_pass=
[ "$method" = direct ] && direct_pass=$(field relative_mse "$img/$id.direct-pass.diff")

# The parameters as points.tsv has them (columns 5..18).
params=$(awk -F '\t' -v id="$id" '$1 == id { s = $5; for (i = 6; i <= 18; i++) s = s "," $i; print s; exit }' \
    "$report/points.tsv")
# The time to the compared image: FLC (and flc-iv) accumulates its frames,
# the others show the same image each frame.
time_ms=$frame_ms
[ "$method" = flc ] || [ "$method" = flc-iv ] && time_ms=$(awk -v f="$frame_ms" -v k="$frames" 'BEGIN { printf "%.3f", f * k }')
echo "$name,$hash,$method,$id,$params,$bake,$bake_wall,$bake_cpu$bake_cols,$bytes,$gbview_rss,$frame_ms,$frame_first_ms,\"$passes\",$full_cols,$own_cols,$time_ms,$status,$trimmed_cols,$direct_pass" \
    >"$report/points/$id.csv.tmp"
mv "$report/points/$id.csv.tmp" "$report/points/$id.csv"
