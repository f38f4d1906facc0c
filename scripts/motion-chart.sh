#!/bin/sh
# SPDX-License-Identifier: MIT
# Regenerates the motion cast accuracy/speed data and chart: builds bench_motion_cast (the shipped
# RelWithDebInfo flags) and runs Kairos over tolerances 1e-1 .. 1e-10 and rotation angles up to
# 22.5, 45, 90 and 162 degrees per step, with FCL (screw motion, zero translation, conservative
# advancement) and Bullet f64's btContinuousConvexCollision on the same motions, in one program.
#   scripts/motion-chart.sh [cases per set]  -> bench/results/motion.csv, bench/results/motion-chart.png
#   KAIROS_MOTION_PLOT_ONLY=1 scripts/motion-chart.sh   redraws the chart from the existing CSV
# Needs: Google Benchmark, FCL, Bullet's double build, gnuplot (Debian: gnuplot-nox).
# The machines are shared and noisy: compare within one run (the CSV), not across runs.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${KAIROS_BENCH_BUILD:-$root/build/motion-bench}
results=$root/bench/results
mkdir -p "$results"
if [ "${KAIROS_MOTION_PLOT_ONLY:-0}" = 1 ]; then
    : # redraw the chart from the existing bench/results/motion.csv
else
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKAIROS_BUILD_BENCH=ON -DKAIROS_ABI_CHECK=OFF >/dev/null
    cmake --build "$build" --target bench_motion_cast -j2 >/dev/null
    "$build/bench/bench_motion_cast" "$results/motion.csv" "${1:-192}"
fi

gnuplot <<GP
set terminal pngcairo size 1600,1150 font "DejaVu Sans,11"
set output "$results/motion-chart.png"
set datafile separator ","
set multiplot layout 2,2 title "Kairos motion cast (rotation): speed against accuracy, beside FCL (screw, CA) and Bullet f64 (btContinuousConvexCollision); errors against a long double reference" font ",14"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
f="$results/motion.csv"
sel(s, a, m, col) = (strcol(1) eq s && abs(column(2) - a) < 0.5 && strcol(3) eq m) ? column(col) : 1/0
pos(v) = (v > 0 ? v : 1e-17)
c1="#1f77b4"; c2="#d62728"; c3="#2ca02c"; c4="#9467bd"

set logscale xy
set format x "10^{%L}"
set title "box/box, turns up to 90 deg: median ns per query against the median toi error"
set xlabel "median |toi - reference| (fraction of the step; both hit)"
set ylabel "ns per query (median)"
set key top right font ",9"
plot f using (pos(sel("box/box",90,"kairos",9))):(sel("box/box",90,"kairos",5)) w lp lc rgb c1 pt 7 t "Kairos, tolerance 1e-1 .. 1e-10", \
     f using (pos(sel("box/box",90,"kairos_disk",9))):(sel("box/box",90,"kairos_disk",5)) w lp lc rgb c4 pt 6 t "Kairos, disk bisection only", \
     f using (pos(sel("box/box",90,"bullet64_ccd",9))):(sel("box/box",90,"bullet64_ccd",5)) w p lc rgb c2 pt 5 ps 2 t "Bullet f64 btContinuousConvexCollision", \
     f using (pos(sel("box/box",90,"fcl_ca_screw",9))):(sel("box/box",90,"fcl_ca_screw",5)) w p lc rgb c3 pt 9 ps 2 t "FCL CA, screw"

set title "hull32/hull32, turns up to 90 deg"
plot f using (pos(sel("hull32/hull32",90,"kairos",9))):(sel("hull32/hull32",90,"kairos",5)) w lp lc rgb c1 pt 7 t "Kairos", \
     f using (pos(sel("hull32/hull32",90,"kairos_disk",9))):(sel("hull32/hull32",90,"kairos_disk",5)) w lp lc rgb c4 pt 6 t "Kairos, disk bisection only", \
     f using (pos(sel("hull32/hull32",90,"bullet64_ccd",9))):(sel("hull32/hull32",90,"bullet64_ccd",5)) w p lc rgb c2 pt 5 ps 2 t "Bullet f64", \
     f using (pos(sel("hull32/hull32",90,"fcl_ca_screw",9))):(sel("hull32/hull32",90,"fcl_ca_screw",5)) w p lc rgb c3 pt 9 ps 2 t "FCL CA, screw"

unset logscale x
set format x "%g"
set logscale y
set title "The rotation curve: ns per query against the largest turn per step (Kairos at 1e-6)"
set xlabel "largest turn per body per step (degrees)"
set ylabel "ns per query (median)"
set xrange [0:170]
plot f using (sel("box/box",column(2),"kairos",4) == 1e-6 ? column(2) : 1/0):(sel("box/box",column(2),"kairos",5)) w lp lc rgb c1 pt 7 t "box/box", \
     f using (sel("hull32/hull32",column(2),"kairos",4) == 1e-6 ? column(2) : 1/0):(sel("hull32/hull32",column(2),"kairos",5)) w lp lc rgb c2 pt 7 t "hull32/hull32", \
     f using (sel("capsule/box",column(2),"kairos",4) == 1e-6 ? column(2) : 1/0):(sel("capsule/box",column(2),"kairos",5)) w lp lc rgb c3 pt 7 t "capsule/box", \
     f using (sel("cylinder/cone",column(2),"kairos",4) == 1e-6 ? column(2) : 1/0):(sel("cylinder/cone",column(2),"kairos",5)) w lp lc rgb c4 pt 7 t "cylinder/cone", \
     f using (sel("box/box",column(2),"fcl_ca_screw",4) > 0 ? column(2) : 1/0):(sel("box/box",column(2),"fcl_ca_screw",5)) w lp lc rgb c1 dt 2 pt 9 t "FCL CA box/box (dashed)", \
     f using (sel("box/box",column(2),"bullet64_ccd",4) > 0 ? column(2) : 1/0):(sel("box/box",column(2),"bullet64_ccd",5)) w lp lc rgb c1 dt 3 pt 5 t "Bullet box/box (dotted)"

set title "Misses and late answers against the largest turn (all four sets; Kairos at every tolerance)"
set ylabel "misses + late answers (of the set)"
unset logscale y
set yrange [0:*]
plot f using (strcol(3) eq "kairos" ? column(2) : 1/0):(column(11) + column(12)) w p lc rgb c1 pt 7 t "Kairos", \
     f using (strcol(3) eq "bullet64_ccd" ? column(2) : 1/0):(column(11) + column(12)) w p lc rgb c2 pt 5 t "Bullet f64", \
     f using (strcol(3) eq "fcl_ca_screw" ? column(2) : 1/0):(column(11) + column(12)) w p lc rgb c3 pt 9 t "FCL CA, screw"
unset multiplot
GP
echo "wrote $results/motion.csv and $results/motion-chart.png"
