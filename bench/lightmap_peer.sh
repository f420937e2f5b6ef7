#!/bin/sh
# lightmap_peer.sh — gibake's lightmap bake against a peer, Blender Cycles
# (3.4, Debian's `blender`), baking the same quantity into the same atlas:
# CPU seconds against error. Not run in CI (make bench runs it: tens of
# minutes on 2 cores).
#
# The quantity: the indirect irradiance E per atlas texel (W/m^2, linear
# RGB, light that has bounced at least once, without the albedo), as
# `lightmap` writes it. gibake's bakes:
#   octree: photons -n LIGHTMAP_PEER_PHOTONS, cluster, atlas --size SIZE
#     --padding LIGHTMAP_PEER_PADDING, then `lightmap --quality Q` for each
#     Q of the scene's list (0: the light octree read at the texel; N: a
#     final gather of N rays reading the octree where they meet the scene,
#     at lightmap's default --accuracy: gathers on a lattice of texels, the
#     texels between interpolated); CPU seconds: photons + cluster + atlas +
#     that lightmap run;
#   paths: atlas, then `lightmap --paths --quality Q` (no octree, no
#     photons: the unbiased gather) for each Q of the scene's paths list;
#     CPU seconds: atlas + that lightmap run.
# (user + system, /usr/bin/time).
# Cycles' bake: bench/cycles_bake.py (its header says how) in one Blender
# process per sample count, from the glb `lightmap --glb` writes (atlas UVs
# as TEXCOORD_1; the .scene's point and directional lights and environment
# added), DIFFUSE without colour, {DIRECT, INDIRECT} less {DIRECT}, times
# pi; its CPU seconds are the whole Blender process's (start-up, import, two
# bakes, the EXR); column "step" gives the {DIRECT, INDIRECT} bake alone
# (what Cycles would cost if its INDIRECT-only filter worked), and for
# gibake the lightmap run alone. Every tool and Blender run with
# LIGHTMAP_PEER_THREADS threads (default 2; atlas has no such option), one
# at a time.
#
# The truth: `lightmap --paths --quality T --accuracy 0` (unbiased
# path-traced gather at every texel), the mean of seeds 1 and 2 (the rows
# use seed 0); its noise floor is the relative MSE of seed 1 against seed
# 2, / 4 (each seed's noise is half their difference's, the mean's half
# again). The error: bench/lightmap_error's relative MSE against the truth
# on "seen" (by the scene's camera), "interior" (5 texels or more from a
# chart's edge) and "covered" texels, and the ratio of means mean(bake) /
# mean(truth) (a bias; it checks that both bake the same quantity).
#
# Then the crossing points: for each Cycles row, the gibake CPU seconds
# that reach the same seen-texel error (per bake, octree or paths, log-log
# interpolation between the cheapest pair of its rows that brackets it;
# the cheaper bake's, or "<=" a cheaper row at or under that error; ">"
# when no row reaches it) and Cycles' CPU
# seconds over those; again by interior texels, where the two bakes'
# conventions agree (seen and covered texels include those at a chart's
# edge, whose centre lies outside the triangle: Cycles extends its
# neighbours' values there, gibake evaluates the triangle's plane
# extended).
#
# With LIGHTMAP_PEER_UNWRAP not 0, Blender also makes lightmap UVs of its
# own for each scene (cycles_bake.py --unwrap: UV > Lightmap Pack, what a
# Blender user bakes into when a scene has none: the peer of `atlas`, which
# gibake's rows are charged), and the crossing tables add a column with
# that call's CPU seconds added to Cycles'.
#
# LIGHTMAP_PEER_SCENES: entries PATH:SIZE:QUALITIES:SPPS:T[:PATHS] (PATH
# under scenes/; QUALITIES, SPPS and PATHS comma-separated; T the truth's
# rays; PATHS the paths bake's qualities, none when left out); default the
# Cornell box at 512 and Sponza at 1024 with fewer rows (about 30 minutes
# each on 2 cores). LIGHTMAP_PEER_CYCLES_TRUTH: if not 0, also a Cycles
# bake at that many samples (seed 1) measured against the truth (default
# 0). LIGHTMAP_PEER_BLENDER: the blender to run (default blender). GB_BIN:
# the tools (default build/bin). Prints Markdown tables on stdout.

. "$(dirname "$0")/common.sh"
needs photons cluster atlas lightmap
error_program=$(bench_program lightmap_error) || exit 1
c=shared/cornell-original.scene
s=shared/sponza.scene
scenes=${LIGHTMAP_PEER_SCENES:-"$c:512:0,16,64,256,1024:16,64,256,1024:4096:4,8,16,32,64,256 \
$s:1024:0,16,64:16,64,256:512:4,8,16,32,64"}
threads=${LIGHTMAP_PEER_THREADS:-2}
photon_count=${LIGHTMAP_PEER_PHOTONS:-1000000}
padding=${LIGHTMAP_PEER_PADDING:-2}
cycles_truth=${LIGHTMAP_PEER_CYCLES_TRUTH:-0}
unwrap=${LIGHTMAP_PEER_UNWRAP:-0}
blender=${LIGHTMAP_PEER_BLENDER:-blender}
if ! command -v "$blender" >/dev/null 2>&1 || ! command -v oiiotool >/dev/null 2>&1; then
    echo "lightmap_peer.sh: no $blender or oiiotool (make bench-deps installs them)" >&2
    exit 1
fi

# timed COMMAND...: runs COMMAND under /usr/bin/time; cpu then prints its
# user + system seconds.
timed() {
    /usr/bin/time -f '%U %S' -o "$dir/time" "$@"
}
cpu() {
    tail -n 1 "$dir/time" | awk '{ printf "%.2f", $1 + $2 }'
}

# error IMAGE: lightmap_error of IMAGE against the scene's truth, into $dir/error.
error() {
    "$error_program" "$scene" "$bake/atlas" "$1" "$bake/truth.exr" >"$dir/error"
}

# row METHOD SETTING CPU STEP: a table row from $dir/error, and a line of
# $dir/rows for the crossing points.
row() {
    e() { value "$1" "$dir/error"; }
    printf '| %s | %s | %s | %s | %s | %.4g | %.4g | %.4g | %.3f | %.3f |\n' "$name" "$1" "$2" \
        "$3" "$4" "$(e seen_relative_mse)" "$(e interior_relative_mse)" \
        "$(e covered_relative_mse)" "$(e seen_ratio_of_means)" "$(e interior_ratio_of_means)"
    echo "$name $1 $2 $3 $(e seen_relative_mse) $(e interior_relative_mse)" >>"$dir/rows"
}

# cycles OPTIONS...: bench/cycles_bake.py on the scene's glb, its output in
# $bake/cycles.out.
cycles() {
    timed "$blender" -b --factory-startup -t "$threads" --python-exit-code 1 \
        -P "$root/bench/cycles_bake.py" -- "$scene" "$bake/scene.glb" \
        --size "$width" "$height" --margin "$padding" "$@" \
        >"$bake/cycles.out" 2>"$bake/cycles.err" || {
        echo "lightmap_peer.sh: $name: blender failed:" >&2
        tail -n 5 "$bake/cycles.err" >&2
        exit 1
    }
}

echo "lightmap against Blender $("$blender" --version 2>/dev/null | sed -n 's/^Blender //p' |
    head -n 1) Cycles (bench/cycles_bake.py); photons -n $photon_count, atlas padding" \
    "$padding, $threads threads; $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg);" \
    "$(date -u +%Y-%m-%d)"
echo
echo "| scene | bake | setting | CPU s | step CPU s | seen rel. MSE | interior rel. MSE |" \
    "covered rel. MSE | seen ratio of means | interior ratio of means |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"
: >"$dir/notes"
: >"$dir/unwrap"
for entry in $scenes; do
    path=${entry%%:*}
    rest=${entry#*:}
    size=${rest%%:*}
    rest=${rest#*:}
    qualities=$(echo "${rest%%:*}" | tr , ' ')
    rest=${rest#*:}
    spps=$(echo "${rest%%:*}" | tr , ' ')
    rest=${rest#*:}
    truth=${rest%%:*}
    paths_qualities=
    [ "$rest" = "$truth" ] || paths_qualities=$(echo "${rest#*:}" | tr , ' ')
    scene=$root/scenes/$path
    name=$(basename "$scene" .scene)
    bake=$dir/$name
    mkdir -p "$bake"
    j="-j $threads"

    # The shared steps, once: the atlas (every bake's), the photons and
    # cluster (the octree bake's).
    timed "$GB_BIN/atlas" -q --stats --size "$size" --padding "$padding" "$scene" \
        -o "$bake/atlas" >"$bake/atlas.stats" || exit 1
    atlas_cpu=$(cpu)
    timed "$GB_BIN/photons" -q $j -n "$photon_count" "$scene" -o "$bake/phot" || exit 1
    shared=$(echo "$atlas_cpu $(cpu)" | awk '{ print $1 + $2 }')
    timed "$GB_BIN/cluster" -q $j "$scene" "$bake/phot" -o "$bake/lot" || exit 1
    shared=$(echo "$shared $(cpu)" | awk '{ print $1 + $2 }')
    texels=$(value size "$bake/atlas.stats")
    width=${texels%x*}
    height=${texels#*x}
    lightmap() {
        "$GB_BIN/lightmap" -q $j "$@" "$scene" "$bake/atlas" "$bake/lot"
    }
    lightmap -o "$bake/glb.exr" --glb "$bake/scene.glb" || exit 1

    # The truth and its noise floor.
    for seed in 1 2; do
        lightmap --paths --quality "$truth" --accuracy 0 --seed "$seed" \
            -o "$bake/truth$seed.exr" || exit 1
    done
    oiiotool "$bake/truth1.exr" "$bake/truth2.exr" --add --mulc 0.5 -d float \
        -o "$bake/truth.exr" || exit 1
    "$error_program" "$scene" "$bake/atlas" "$bake/truth1.exr" "$bake/truth2.exr" >"$dir/error"
    echo "$name: truth lightmap --paths --quality $truth --accuracy 0, seeds 1 and 2 averaged;" \
        "noise floor" \
        "(seed 1 against 2, / 4): seen $(value seen_relative_mse "$dir/error" |
            awk '{ printf "%.3g", $1 / 4 }'), interior $(value interior_relative_mse \
            "$dir/error" | awk '{ printf "%.3g", $1 / 4 }'), covered $(value \
            covered_relative_mse "$dir/error" | awk '{ printf "%.3g", $1 / 4 }');" \
        "$(value seen_texels "$dir/error") seen, $(value interior_texels "$dir/error")" \
        "interior, $(value covered_texels "$dir/error") covered texels of ${width}x$height;" \
        "atlas: $atlas_cpu CPU s, photons + cluster + atlas: $shared CPU s" >>"$dir/notes"

    for q in $qualities; do
        timed "$GB_BIN/lightmap" -q $j --quality "$q" "$scene" "$bake/atlas" "$bake/lot" \
            -o "$bake/q$q.exr" || exit 1
        step=$(cpu)
        error "$bake/q$q.exr" || exit 1
        row gibake "--quality $q" "$(echo "$shared $step" | awk '{ printf "%.2f", $1 + $2 }')" \
            "$step"
    done
    for q in $paths_qualities; do
        timed "$GB_BIN/lightmap" -q $j --paths --quality "$q" "$scene" "$bake/atlas" \
            -o "$bake/paths$q.exr" || exit 1
        step=$(cpu)
        error "$bake/paths$q.exr" || exit 1
        row gibake "--paths --quality $q" \
            "$(echo "$atlas_cpu $step" | awk '{ printf "%.2f", $1 + $2 }')" "$step"
    done
    for spp in $spps; do
        cycles --samples "$spp" --seed 0 -o "$bake/cycles$spp.exr"
        error "$bake/cycles$spp.exr" || exit 1
        row Cycles "$spp spp" "$(cpu)" "$(value bake_seconds_direct_indirect "$bake/cycles.out")"
    done
    if [ "$unwrap" != 0 ]; then
        cycles --unwrap
        echo "$name $(value unwrap_seconds "$bake/cycles.out")" >>"$dir/unwrap"
        echo "$name: Blender's own lightmap UVs (cycles_bake.py --unwrap, UV > Lightmap" \
            "Pack): $(value unwrap_seconds "$bake/cycles.out") CPU s, the Blender" \
            "process $(cpu) CPU s" >>"$dir/notes"
    fi
    if [ "$cycles_truth" != 0 ]; then
        cycles --samples "$cycles_truth" --seed 1 -o "$bake/cycles-truth.exr"
        error "$bake/cycles-truth.exr" || exit 1
        echo "$name: Cycles at $cycles_truth spp (seed 1, $(cpu) CPU s) against the truth:" \
            "relative MSE seen $(value seen_relative_mse "$dir/error"), interior" \
            "$(value interior_relative_mse "$dir/error"), covered $(value \
            covered_relative_mse "$dir/error"); ratio of means seen $(value \
            seen_ratio_of_means "$dir/error"), interior $(value interior_ratio_of_means \
            "$dir/error")" >>"$dir/notes"
    fi
done
echo
sed 's/^/- /' "$dir/notes"

# crossing CLASS: the crossing points table by CLASS's relative MSE (seen or
# interior).
crossing() {
    echo
    echo "Crossing points by $1 texels: the gibake CPU seconds at each Cycles row's error."
    echo
    unwrap_column= unwrap_rule=
    if [ -s "$dir/unwrap" ]; then
        unwrap_column=" (Cycles + Lightmap Pack) / gibake |" unwrap_rule="---:|"
    fi
    echo "| scene | Cycles spp | Cycles CPU s | $1 rel. MSE | gibake CPU s, same error |" \
        "Cycles / gibake |$unwrap_column"
    echo "|---|---:|---:|---:|---:|---:|$unwrap_rule"
    awk -v column="$2" '
    FILENAME ~ /unwrap$/ { unwrap[$1] = $2; next }
    { scene = $1; cpu = $(NF - 2); err = $(NF - column) }
    $2 == "gibake" {
        key = scene SUBSEP $3   # the bake: --quality (octree) or --paths
        if (!(key in count)) { families[scene] = families[scene] " " $3 }
        n = count[key]++; t[key, n] = cpu; e[key, n] = err
        n_all = all[scene]++; t_all[scene, n_all] = cpu; e_all[scene, n_all] = err
    }
    $2 == "Cycles" { ++m; cs[m] = scene; spp[m] = $3; tc[m] = cpu; ec[m] = err }
    END {
        for (k = 1; k <= m; ++k) {
            scene = cs[k]; best = -1
            split(substr(families[scene], 2), names, " ")
            for (f in names) {
                key = scene SUBSEP names[f]; rows = count[key]
                # the cheapest segment of this bake whose errors bracket the row'"'"'s
                for (i = 0; i + 1 < rows; ++i) {
                    e0 = e[key, i]; e1 = e[key, i + 1]
                    if ((e0 - ec[k]) * (e1 - ec[k]) <= 0 && e0 != e1) {
                        x = (log(ec[k]) - log(e0)) / (log(e1) - log(e0))
                        tg = exp(log(t[key, i]) + x * (log(t[key, i + 1]) - log(t[key, i])))
                        if (best < 0 || tg < best) best = tg
                        break
                    }
                }
            }
            # a row at or under its error bounds the time from above
            upper = -1; lowest = -1
            for (i = 0; i < all[scene]; ++i) {
                if (e_all[scene, i] <= ec[k] && (upper < 0 || t_all[scene, i] < upper))
                    upper = t_all[scene, i]
                if (lowest < 0 || e_all[scene, i] < e_all[scene, lowest]) lowest = i
            }
            # the ratio of Cycles seconds to gibake seconds, and its bound
            if (best >= 0 && (upper < 0 || best <= upper)) {
                at = sprintf("%.2f", best); bound = ""; tg = best
            } else if (upper >= 0) {
                at = sprintf("<= %.2f", upper); bound = ">= "; tg = upper
            } else if (lowest >= 0) {
                tg = t_all[scene, lowest]; at = sprintf("> %.2f", tg); bound = "< "
            } else {
                at = "-"; tg = -1
            }
            ratio = tg > 0 ? sprintf("%s%.2f", bound, tc[k] / tg) : "-"
            with_unwrap = ""
            if (scene in unwrap)
                with_unwrap = tg > 0 ? sprintf(" %s%.2f |", bound, (tc[k] + unwrap[scene]) / tg) \
                                     : " - |"
            printf "| %s | %s | %s | %.4g | %s | %s |%s\n", scene, spp[k], tc[k], ec[k], at, ratio,
                with_unwrap
        }
    }' "$dir/unwrap" "$dir/rows"
}
crossing seen 1
crossing interior 0
