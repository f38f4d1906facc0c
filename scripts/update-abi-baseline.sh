#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Rewrites abi/libkairos.abi from a freshly built libkairos (for an intended, logged ABI change).
#
# Usage: scripts/update-abi-baseline.sh [build dir]   (default: build/release, the release preset)
# Builds the library in that tree (configuring the release preset first when the tree does not
# exist), dumps its ABI exactly as the ctest test abi_abidiff does, writes the baseline and shows
# what changed. Commit abi/libkairos.abi together with a new line in abi/CHANGELOG.md.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build/release}
cd "$root"
if [ ! -f "$build/CMakeCache.txt" ]; then
    if [ "$build" = "$root/build/release" ]; then
        cmake --preset release
    else
        echo "update-abi-baseline.sh: $build is not a configured build tree" >&2
        exit 1
    fi
fi
if ! grep -Eq '^CMAKE_BUILD_TYPE:[A-Z]+=(RelWithDebInfo|Debug)$' "$build/CMakeCache.txt"; then
    echo "update-abi-baseline.sh: $build has no debug info; use a RelWithDebInfo (release preset) tree" >&2
    exit 1
fi
cmake --build "$build" --target kairos
lib=$(find "$build" -maxdepth 1 -name 'libkairos.so.0' -print -quit)
[ -n "$lib" ] || { echo "update-abi-baseline.sh: no libkairos.so.0 in $build" >&2; exit 1; }

old=$(mktemp)
trap 'rm -f "$old"' EXIT
cp abi/libkairos.abi "$old" 2>/dev/null || : >"$old"
bash tests/abi/check_abi.sh update "$lib" abi/libkairos.abi "$build/abi-check" include "$build/include"
if [ -s "$old" ]; then
    echo "--- abidiff old baseline -> new baseline:"
    abidiff --no-default-suppression "$old" abi/libkairos.abi || true
fi
echo "Now add one line to abi/CHANGELOG.md saying what changed and why, and commit both files."
