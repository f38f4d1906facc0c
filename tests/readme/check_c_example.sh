#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Extracts the C example from README.md, builds it against the built library, runs it, and
# checks what it prints, so the README's example stays true.
# Usage: check_c_example.sh README.md <include dir> <generated include dir> <libkairos.so path> <C compiler>
set -euo pipefail
readme=$1 inc=$2 geninc=$3 lib=$4 cc=$5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
awk '/^## A C example/{f=1} f&&/^```c/{g=1;next} g&&/^```/{exit} g{print}' "$readme" > "$work/example.c"
[ -s "$work/example.c" ] || { echo "no C example found in $readme"; exit 1; }
"$cc" -std=c99 -Wall -Wextra -pedantic -Werror -I"$inc" -I"$geninc" "$work/example.c" -o "$work/example" \
    -L"$(dirname "$lib")" -lkairos
out=$(LD_LIBRARY_PATH="$(dirname "$lib")" "$work/example")
echo "$out"
grep -q '^x in \[' <<<"$out"
grep -qF 'KAIROS_ERROR_INVALID_ARGUMENT: kairos_shape_sphere: radius must be > 0 (got -1)' <<<"$out"
echo "README C example: OK"
