#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# ABI test: libkairos exports exactly the header's kairos_* functions, under SONAME libkairos.so.0 and node KAIROS_0.
#
# Usage: check_exports.sh <libkairos.so.0> <kairos.h>. Environment: NM, READELF (default nm, readelf).
# Also checks what would stop dlclose from unloading the library (GNU unique symbols,
# DF_1_NODELETE) and that the stack is not executable.
set -euo pipefail

lib=${1:?path to libkairos.so.0}
header=${2:?path to include/kairos/kairos.h}
nm=${NM:-nm}
readelf=${READELF:-readelf}
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# ---- SONAME and the version node ----------------------------------------------------------------
soname=$("$readelf" -d "$lib" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
[ "$soname" = libkairos.so.0 ] || fail "SONAME is '$soname', expected libkairos.so.0"
# Captured first: with pipefail, grep -q quitting early makes readelf die of SIGPIPE on a large
# version table (the sanitizer build's), and the pipeline fails although the name is there.
versions=$("$readelf" -V "$lib")
grep -q 'Name: KAIROS_0$' <<<"$versions" || fail "no version definition KAIROS_0 (readelf -V)"

# ---- Exported symbols: only kairos_* functions, each under KAIROS_0 ----------------------------
exported=()
while read -r value type name; do
    if [ -z "$name" ]; then  # nm prints no value column for some symbol kinds
        name=$type
        type=$value
    fi
    if [ "$type" = A ] && { [ "$name" = KAIROS_0 ] || [ "$name" = KAIROS_0.2 ]; }; then continue; fi  # version nodes
    # kairos_world_settings_init grew a version in 0.2 (cmake/kairos.map): its default is
    # KAIROS_0.2, and the 0.1 one stays as a non-default KAIROS_0 version for old binaries.
    case "$name" in
        kairos_world_settings_init@KAIROS_0) compat_init=1; continue ;;
        kairos_world_settings_init@@KAIROS_0.2) ;;
        kairos_*@@KAIROS_0) ;;
        *) fail "exported symbol '$name' ($type) is not a kairos_ symbol under KAIROS_0"; continue ;;
    esac
    [ "$type" = T ] || fail "exported symbol '$name' has type $type, expected T (a function; no data)"
    name=${name%@@KAIROS_0.2}
    exported+=("${name%@@KAIROS_0}")
done < <("$nm" -D --defined-only "$lib")
[ "${#exported[@]}" -gt 0 ] || fail "nm -D --defined-only found no kairos_ functions"
[ "${compat_init:-0}" = 1 ] || fail "no kairos_world_settings_init@KAIROS_0 (the 0.1 init, for binaries linked against 0.1)"

# ---- The exported set is exactly the set the header declares -----------------------------------
declared=$(sed -n 's/^KAIROS_API[^(]*[ *]\(kairos_[a-z0-9_]*\)(.*/\1/p' "$header" | sort -u)
actual=$(printf '%s\n' "${exported[@]}" | sort -u)
[ -n "$declared" ] || fail "found no KAIROS_API declarations in $header"
if [ "$declared" != "$actual" ]; then
    fail "exports differ from the header's declarations (< header only, > library only):"
    diff <(echo "$declared") <(echo "$actual") >&2 || true
fi

# ---- Nothing pins the library in memory; no executable stack -----------------------------------
if "$readelf" --dyn-syms -W "$lib" | awk '$5 == "UNIQUE"' | grep .; then
    fail "GNU unique symbols (above) would stop dlclose from unloading the library"
fi
if "$readelf" -d "$lib" | grep -E 'FLAGS_1.*NODELETE'; then
    fail "the library is marked DF_1_NODELETE (-z nodelete): dlclose cannot unload it"
fi
if "$readelf" -lW "$lib" | grep GNU_STACK | grep RWE >/dev/null; then
    fail "the library asks for an executable stack"
fi

count=$(echo "$actual" | wc -l)
if [ "$failures" -ne 0 ]; then
    echo "check_exports.sh: $failures problem(s) in $lib" >&2
    exit 1
fi
echo "check_exports.sh: $lib exports exactly the $count kairos_ functions of the header, SONAME $soname, node KAIROS_0"
