#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# ABI test: compare libkairos's ABI (libabigail abidw, public headers only) with the committed baseline.
#
# Usage: check_abi.sh check  <libkairos.so.0> <baseline.abi> <work dir> <header dir>...
#        check_abi.sh update <libkairos.so.0> <baseline.abi> <work dir> <header dir>...
# check: exits 0 only when abidiff finds no difference at all. Any non-zero abidiff status fails:
# a field inserted mid-struct is an "ABI change" (4), not an "incompatible change" (8), so
# testing bit 8 alone would let it through.
# update: rewrites the baseline (scripts/update-abi-baseline.sh calls this).
# Exit 77 (ctest: skipped) when abidw is missing and CI is not set; in CI that is a failure.
set -euo pipefail

mode=${1:?check or update}
lib=${2:?path to libkairos.so.0}
baseline=${3:?path to the baseline .abi}
work_dir=${4:?work dir}
shift 4
[ "$#" -gt 0 ] || { echo "check_abi.sh: give the public header directories" >&2; exit 2; }
source_dir=$(cd "$(dirname "$0")/../.." && pwd)

for tool in abidw abidiff; do
    if ! command -v "$tool" >/dev/null; then
        if [ -n "${CI:-}" ]; then
            echo "check_abi.sh: $tool not found and CI is set: install abigail-tools" >&2
            exit 1
        fi
        echo "check_abi.sh: $tool not found (apt-get install abigail-tools); skipping the ABI check" >&2
        exit 77
    fi
done

# The options fix what the baseline records:
#   --headers-dir ... --exported-interfaces-only --drop-private-types
#       only the exported functions and the types the public headers define (no C++ internals)
#   --no-corpus-path --no-comp-dir-path --no-show-locs --no-elf-needed
#       nothing that depends on where or how the tree was built, or on line numbers
# and the translation units' absolute source paths are made relative to the source tree, so the
# baseline is byte-identical across rebuilds and clones.
dump() {
    local out=$1 args=() dir
    shift
    for dir in "$@"; do args+=(--headers-dir "$dir"); done
    abidw "${args[@]}" --exported-interfaces-only --drop-private-types \
        --no-corpus-path --no-comp-dir-path --no-show-locs --no-elf-needed \
        --out-file "$out.raw" "$lib"
    sed "s|path='$source_dir/|path='|g" "$out.raw" >"$out"
    rm -f "$out.raw"
    # Without debug info abidw sees symbols but no types, and the comparison would mean little.
    if ! grep -q "<class-decl name='kairos_api'" "$out"; then
        echo "check_abi.sh: abidw found no type information in $lib (build with -g, e.g. RelWithDebInfo)" >&2
        exit 1
    fi
}

mkdir -p "$work_dir"
fresh=$work_dir/libkairos.abi
dump "$fresh" "$@"

case "$mode" in
    update)
        cp "$fresh" "$baseline"
        echo "check_abi.sh: wrote $baseline; add a line to abi/CHANGELOG.md in the same commit"
        ;;
    check)
        [ -f "$baseline" ] || { echo "check_abi.sh: no baseline at $baseline" >&2; exit 1; }
        status=0
        abidiff --no-default-suppression "$baseline" "$fresh" >"$work_dir/abidiff.txt" 2>&1 || status=$?
        if [ "$status" -ne 0 ]; then
            cat "$work_dir/abidiff.txt" >&2
            echo "check_abi.sh: abidiff exited $status (bits: 1 error, 2 usage, 4 ABI change, 8 incompatible change)." >&2
            echo "If the change is intended (only appending to a growing struct or adding functions within" >&2
            echo "the major version), run scripts/update-abi-baseline.sh and add a line to abi/CHANGELOG.md" >&2
            echo "in the same commit." >&2
            exit 1
        fi
        echo "check_abi.sh: the ABI of $lib matches $baseline"
        ;;
    *) echo "check_abi.sh: unknown mode $mode" >&2; exit 2 ;;
esac
