#!/usr/bin/env bash
# Quick start, the main job: install missing Debian packages, build Kairos (release preset) and run the demo.
#
# Usage: bash scripts/demo.sh [demo arguments]   (as root on Debian 12 it installs what is
# missing; as another user it prints the apt-get line to run first).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=scripts/deps.sh
. "$root/scripts/deps.sh"
kairos_ensure_deps || exit 1
kairos_parallel_defaults
cd "$root"

cmake --preset release --log-level=WARNING
cmake --build --preset release --target kairos_demo
demo=build/release/examples/kairos_demo
if [ ! -x "$demo" ]; then
    echo "scripts/demo.sh: $demo was not built" >&2
    exit 1
fi
echo
exec "$demo" "$@"
