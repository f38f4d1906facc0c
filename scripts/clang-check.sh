#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The clang side of CI: builds the library, the tests and the demo with clang++ and warnings as
# errors (build/clang), then runs clang-tidy with the repository's .clang-tidy over the library
# sources (src/, capi/), the public header included. The gcc side is the release preset, which
# also treats warnings as errors.
#
# Usage: bash scripts/clang-check.sh   (installs clang and clang-tidy when missing, as root on
# Debian 12). Exits non-zero on any warning or clang-tidy finding.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
exec </dev/null

# shellcheck source=scripts/deps.sh
. "$root/scripts/deps.sh"
KAIROS_DEBIAN_PACKAGES+=(clang clang-tidy)
kairos_ensure_deps || exit 1
kairos_parallel_defaults

build=build/clang
echo "==== scripts/clang-check.sh: clang++ build with -Werror into $build ===="
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
    -DCMAKE_COMPILE_WARNING_AS_ERROR=ON -DKAIROS_BUILD_BENCH=OFF -DKAIROS_ABI_CHECK=OFF >/dev/null
cmake --build "$build"

echo "==== scripts/clang-check.sh: clang-tidy over src/ and capi/ ===="
jobs=${CMAKE_BUILD_PARALLEL_LEVEL:-2}
status=0
find src capi -name '*.cpp' | sort |
    xargs -P "$jobs" -n 1 clang-tidy -p "$build" --quiet >"$build/tidy.log" 2>&1 || status=$?
# clang-tidy prints "N warnings generated" for warnings it suppressed (system headers): noise.
grep -v -E '^[0-9]+ warnings? (and [0-9]+ errors? )?generated\.$' "$build/tidy.log" || true
if [ "$status" -ne 0 ]; then
    echo "scripts/clang-check.sh: clang-tidy found problems (log: $build/tidy.log)" >&2
    exit 1
fi
echo "scripts/clang-check.sh: clang build and clang-tidy clean"
