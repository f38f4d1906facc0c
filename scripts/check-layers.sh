#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Checks the layering of src/ (docs/layout.md): a file includes only headers of its own folder
# and of the folders below it, and no file under src/ or capi/ is longer than 600 lines.
#
#   math < shapes < gjk < casts < motion < world      broadphase: math only      world: all
#
# Usage: bash scripts/check-layers.sh   (from anywhere; exits 1 and names each violation)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

max_lines=600
# The folders each layer may include besides its own.
declare -A below=(
    [math]=""
    [shapes]="math"
    [gjk]="math shapes"
    [casts]="math shapes gjk"
    [motion]="math shapes gjk casts"
    [broadphase]="math"
    [world]="math shapes gjk casts motion broadphase"
)

status=0
fail() {
    echo "check-layers: $*" >&2
    status=1
}

while IFS= read -r file; do
    layer=${file#src/}
    layer=${layer%%/*}
    if [ -z "${below[$layer]+set}" ]; then
        fail "$file: folder '$layer' is not a layer (math shapes gjk casts motion broadphase world)"
        continue
    fi
    allowed=" $layer ${below[$layer]} "
    while IFS= read -r line; do
        number=${line%%:*}
        target=$(sed -E 's/^[0-9]+:[[:space:]]*#[[:space:]]*include[[:space:]]*"([^"]*)".*/\1/' <<<"$line")
        case "$target" in
            */*) folder=${target%%/*} ;;
            *) fail "$file:$number: \"$target\": include library headers from src/ as the root (\"layer/file.hpp\")"; continue ;;
        esac
        if [[ "$allowed" != *" $folder "* ]]; then
            fail "$file:$number: $layer includes \"$target\" (allowed: $layer ${below[$layer]})"
        fi
    done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$file" || true)
done < <(find src -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) | sort)

while IFS= read -r file; do
    lines=$(wc -l <"$file")
    if [ "$lines" -gt "$max_lines" ]; then
        fail "$file: $lines lines (at most $max_lines)"
    fi
done < <(find src capi -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) | sort)

if [ "$status" -eq 0 ]; then
    echo "check-layers: $(find src -type f -name '*.[ch]pp' | wc -l) files in src/ include downward only; none over $max_lines lines"
fi
exit "$status"
