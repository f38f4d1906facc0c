#!/bin/sh
# SPDX-License-Identifier: MIT
# Regenerates the stability catalogue: builds bench_stability (the shipped RelWithDebInfo flags,
# one build job), runs every family of hard cases through Kairos and its peers, and draws the
# failure-rate heatmap (method x family).
#   scripts/stability-chart.sh   -> bench/results/stability.csv, bench/results/stability.png,
#                                   bench/results/stability-reproducers.txt (one reproducer line per
#                                   failing method and family; the table on stdout as well)
# Needs: FCL, libccd, Bullet's double build, gnuplot (Debian: libfcl-dev libccd-dev libbullet-dev gnuplot-nox).
# Exits non-zero when a family is one-sided (no judged case of one outcome): the table would be meaningless.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${KAIROS_STABILITY_BUILD:-$root/build/stability}
results=$root/bench/results
mkdir -p "$results"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKAIROS_BUILD_BENCH=ON -DKAIROS_ABI_CHECK=OFF >/dev/null
nice -n 10 cmake --build "$build" --target bench_stability -j1 >/dev/null
status=0
"$build/bench/bench_stability" "$results/stability.csv" > "$build/stability.txt" || status=$?
cat "$build/stability.txt"
# One reproducer per failing method and family, kept beside the CSV (peers' failures to report).
grep '^REPRO ' "$build/stability.txt" > "$results/stability-reproducers.txt" || true

# The grid's extent from the data: the largest method and family indices.
last_method=$(awk -F, 'NR > 1 && $10 > m { m = $10 } END { print m + 0 }' "$results/stability.csv")
last_family=$(awk -F, 'NR > 1 && $11 > m { m = $11 } END { print m + 0 }' "$results/stability.csv")

gnuplot <<GP
set terminal pngcairo size 1700,900 font "DejaVu Sans,11" noenhanced
set output "$results/stability.png"
set datafile separator ","
set title "Stability catalogue: failure rate (%) by method and family (blank: not applicable; bounds in the README)" font ",14"
set palette defined (0 "#f7fbff", 0.001 "#fff5d6", 5 "#fdae61", 25 "#e34a33", 100 "#7f0000")
set cbrange [0:100]
set cblabel "failure rate (%)"
set xrange [-0.5:$last_family.5]
set yrange [$last_method.5:-0.5]
set xtics rotate by 35 right font ",10"
set ytics font ",10"
set tics scale 0
unset key
f="$results/stability.csv"
plot f skip 1 using 11:10:(0.5):(0.5):(column(5)*100):xtic(2):ytic(1) with boxxyerror fs solid 1.0 noborder fc palette, \
     f skip 1 using 11:10:(sprintf("%.1f", column(5)*100)) with labels font ",9"
GP
echo "wrote $results/stability.csv, $results/stability.png and $results/stability-reproducers.txt"
exit $status
