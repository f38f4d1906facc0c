#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start, the main job: install missing Debian packages, build Kairos (release preset), run
# the demo (fast and spinning objects that tunnel between frames, and their times of impact),
# step the scene of a few thousand objects (picture: build/demo/kairos_scene.png), and
# draw the shape-cast accuracy/speed chart from a fresh run (build/demo/cast-chart.png; the
# committed bench/results/ are never rewritten).
#
# Usage: bash scripts/demo.sh   (as root on Debian 12 it installs what is missing; as another
# user it prints the apt-get line to run first). KAIROS_DEMO_NO_CHART=1 skips the chart.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=scripts/deps.sh
. "$root/scripts/deps.sh"
kairos_ensure_deps || exit 1
kairos_parallel_defaults
cd "$root"

cmake --preset release --log-level=WARNING
cmake --build --preset release --target kairos_demo kairos_scene
for program in kairos_demo kairos_scene; do
    if [ ! -x "build/release/examples/$program" ]; then
        echo "scripts/demo.sh: build/release/examples/$program was not built" >&2
        exit 1
    fi
done

echo
echo "==== 1. Three objects that tunnel between frames, and their first times of impact ===="
build/release/examples/kairos_demo

echo
echo "==== 2. A world of a few thousand moving objects ===="
mkdir -p build/demo
build/release/examples/kairos_scene 30 build/demo/kairos_scene
if gnuplot build/demo/kairos_scene.gp; then
    echo "picture: build/demo/kairos_scene.png"
else
    echo "gnuplot could not draw build/demo/kairos_scene.png; the raster is build/demo/kairos_scene.ppm" >&2
fi

if [ "${KAIROS_DEMO_NO_CHART:-0}" != 1 ]; then
    echo
    echo "==== 3. Regenerating the shape-cast accuracy/speed chart (about a minute) ===="
    KAIROS_RESULTS_DIR="$PWD/build/demo" KAIROS_CAST_RUNS=1 bash scripts/cast-chart.sh
    echo "chart: build/demo/cast-chart.png (data: build/demo/cast.csv; the committed run is bench/results/)"
fi
