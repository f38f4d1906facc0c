#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start: install missing Debian packages, then configure, build and run every test (release preset).
#
# Usage: bash scripts/test.sh   (as root on Debian 12 it installs what is missing; as another user
# it prints the apt-get line to run first). Runs `cmake --workflow --preset release` and ends with
# ctest's summary; exits non-zero when anything fails.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=scripts/deps.sh
. "$root/scripts/deps.sh"
kairos_ensure_deps || exit 1
kairos_parallel_defaults
cd "$root"

mkdir -p build
log=build/test-release.log
status=0
cmake --workflow --preset release 2>&1 | tee "$log" || status=${PIPESTATUS[0]}
echo
kairos_ctest_summary "tests, release preset (log: $log)" "$log"
if [ "$status" -ne 0 ]; then
    echo "scripts/test.sh: FAILED (cmake --workflow --preset release exited $status)" >&2
    exit "$status"
fi
echo "scripts/test.sh: all tests passed"
