#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Broad-phase benchmark and chart: runs bench_world (Kairos's space-time sweeps beside FCL and
# Bullet) and draws bench/results/world.png, the step time against N for each scene.
#
# Usage: scripts/world-chart.sh [build-dir]      (default build-dir: build-bench, RelWithDebInfo)
#        KAIROS_CHART_ONLY=1 scripts/world-chart.sh   redraws the chart from bench/results/world.csv
# Writes bench/results/world.csv (one row per scene, N and broad phase: the fastest of three
# repetitions, thread CPU time, with swaps, pairs and false positives), world.txt (Google
# Benchmark's report), world_interleaved.csv (all broad phases stepped through one scene in lock
# step: CPU time per step and the ratio to Kairos's space-time sweep, the figures that hold on a
# busy machine) and world.png (drawn from world_interleaved.csv).
# Needs cmake, Google Benchmark, FCL, Bullet's double build and gnuplot. Takes about ten minutes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-bench}
out=$root/bench/results
mkdir -p "$out"

if [ -z "${KAIROS_CHART_ONLY:-}" ]; then
    if [ ! -f "$build/CMakeCache.txt" ]; then
        cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKAIROS_ABI_CHECK=OFF >/dev/null
    fi
    cmake --build "$build" --target bench_world -j2
    "$build/bench/bench_world" --benchmark_repetitions=3 --csv="$out/world.csv" | tee "$out/world.txt"
    "$build/bench/bench_world" --interleaved="$out/world_interleaved.csv"
fi

command -v gnuplot >/dev/null || { echo "gnuplot not found: chart not drawn" >&2; exit 1; }
data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
# One file per (scene, variant): N and milliseconds per step.
awk -F, -v dir="$data" 'NR > 1 { f = dir "/" $1 "__" $3 ".dat"; print $2, $4 >> f }' "$out/world_interleaved.csv"
for f in "$data"/*.dat; do sort -n -o "$f" "$f"; done

plot_scene() {  # scene title
    local scene=$1 title=$2 cmd="" sep=""
    for v in kairos_spacetime_sap kairos_spacetime_sap_global kairos_spacetime_sap_queued kairos_encapsulating_sap \
             fcl_dynamic_aabb_tree bullet_32bit_axis_sweep3 bullet_dbvt; do
        local f="$data/${scene}__${v}.dat"
        [ -s "$f" ] || continue
        local style
        case $v in
            kairos_spacetime_sap) style="lw 3 lc rgb '#c0392b' pt 7" ;;
            kairos_spacetime_sap_global) style="lw 1.5 lc rgb '#e67e22' pt 5 dt 2" ;;
            kairos_spacetime_sap_queued) style="lw 1.5 lc rgb '#f1c40f' pt 9 dt 2" ;;
            kairos_encapsulating_sap) style="lw 1.5 lc rgb '#8e44ad' pt 11 dt 3" ;;
            fcl_dynamic_aabb_tree) style="lw 2 lc rgb '#2471a3' pt 13" ;;
            bullet_32bit_axis_sweep3) style="lw 2 lc rgb '#17a589' pt 15" ;;
            bullet_dbvt) style="lw 2 lc rgb '#7f8c8d' pt 4" ;;
        esac
        cmd+="$sep'$f' using 1:2 with linespoints $style title '${v//_/ }'"
        sep=", "
    done
    echo "set title '$title'"
    echo "plot $cmd"
}

{
    echo "set terminal pngcairo size 1400,1000 font 'sans,10'"
    echo "set output '$out/world.png'"
    echo "set multiplot layout 2,2 title 'Broad phase: CPU time per step against N (unit cubes filling 10 % of the volume; all broad phases stepped in lock step)'"
    echo "set logscale xy"
    echo "set xlabel 'objects N'"
    echo "set ylabel 'ms per step'"
    echo "set xrange [700:140000]"
    echo "set grid"
    echo "set key bottom right font ',8'"
    plot_scene uniform5 'all moving, 5 % of a box per step'
    plot_scene uniform50 'all moving, 50 % of a box per step'
    plot_scene moving10 '10 % moving, 5 % of a box per step'
    plot_scene flock 'flock: one common velocity, 50 % of a box per step'
    echo "unset multiplot"
} | gnuplot
echo "wrote $out/world.csv and $out/world.png"
