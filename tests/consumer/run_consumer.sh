#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Consumer test: install the build tree into a scratch prefix and build outside programs against it.
#
# Usage: run_consumer.sh <step> <build dir> <work dir>
#   install    cmake --install <build dir> into <work dir>/prefix and check what was installed
#   cmake      configure, build and run tests/consumer with find_package(kairos 0 REQUIRED)
#   pkgconfig  cc main.c $(pkg-config --cflags --libs kairos), run it with LD_LIBRARY_PATH
#   major      find_package(kairos 1 REQUIRED) must fail: the package is same-major compatible
#   python     the installed Python package imports and finds the installed library by itself
#              (PYTHONPATH set to its directory, KAIROS_LIBRARY unset, no build tree reachable)
#   all        every step above, in order
# Environment: CMAKE (default cmake), CC (default cc), CFLAGS and LDFLAGS (e.g. the sanitizer
# flags of the build under test), KAIROS_EXPECTED_VERSION (e.g. 0.1.0; checked when set), PYTHON3
# (the interpreter of the python step; exit 77, skipped, when it lacks numpy).
set -euo pipefail

step=${1:?step: install, cmake, pkgconfig, major or all}
build_dir=$(cd "${2:?build dir}" && pwd)
work_dir=${3:?work dir}
here=$(cd "$(dirname "$0")" && pwd)
cmake=${CMAKE:-cmake}
cc=${CC:-cc}
prefix=$work_dir/prefix

fail() { echo "run_consumer.sh ($step): FAIL: $*" >&2; exit 1; }

# The directory holding libkairos.so.0 under the prefix (lib, or lib/<multiarch> for /usr-like layouts).
libdir_of() {
    local found
    found=$(find "$prefix" -name libkairos.so.0 -print -quit)
    [ -n "$found" ] || fail "no libkairos.so.0 under $prefix (did the install step run?)"
    dirname "$found"
}

do_install() {
    rm -rf "$prefix"
    mkdir -p "$work_dir"
    "$cmake" --install "$build_dir" --prefix "$prefix"
    local libdir
    libdir=$(libdir_of)
    for f in include/kairos/kairos.h include/kairos/kairos_version.h; do
        [ -f "$prefix/$f" ] || fail "$f was not installed"
    done
    for f in libkairos.so libkairos.so.0 cmake/kairos/kairosConfig.cmake \
             cmake/kairos/kairosConfigVersion.cmake cmake/kairos/kairosTargets.cmake pkgconfig/kairos.pc; do
        [ -e "$libdir/$f" ] || fail "$libdir/$f was not installed"
    done
    # Only the public headers, and nothing of the internal static core.
    local headers
    headers=$(cd "$prefix/include" && find . -type f | sort | tr '\n' ' ')
    [ "$headers" = "./kairos/kairos.h ./kairos/kairos_version.h " ] || fail "unexpected headers installed: $headers"
    if find "$prefix" -name '*kairos_core*' | grep -q .; then fail "the internal core was installed"; fi
    if grep -q kairos_core "$libdir"/cmake/kairos/*.cmake; then fail "the CMake package mentions kairos_core"; fi
    # The development symlink leads to the SONAME file, which leads to the real file.
    [ "$(readlink "$libdir/libkairos.so")" = libkairos.so.0 ] || fail "libkairos.so does not point to libkairos.so.0"
    echo "installed into $prefix"
}

do_cmake() {
    local build=$work_dir/cmake-consumer
    rm -rf "$build"
    "$cmake" -S "$here" -B "$build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" \
        -DCMAKE_C_FLAGS="${CFLAGS:-}" -DCMAKE_EXE_LINKER_FLAGS="${LDFLAGS:-}" \
        -DCMAKE_BUILD_TYPE=Release -DKAIROS_CONSUMER_WANTS=0 >"$work_dir/cmake-configure.log" 2>&1 ||
        { cat "$work_dir/cmake-configure.log" >&2; fail "configuring the consumer project failed"; }
    grep "Found kairos" "$work_dir/cmake-configure.log"
    grep -q "Found kairos ${KAIROS_EXPECTED_VERSION:-} in $prefix/" "$work_dir/cmake-configure.log" ||
        fail "find_package did not find the package installed in $prefix"
    "$cmake" --build "$build" || fail "building the consumer project failed"
    # The imported target's location gives the program a RUNPATH into the prefix: no
    # LD_LIBRARY_PATH needed, and it must load the installed copy.
    "$build/kairos_consumer" || fail "the consumer program built with CMake failed"
}

do_pkgconfig() {
    command -v pkg-config >/dev/null || fail "pkg-config is not installed"
    local libdir out flags
    libdir=$(libdir_of)
    out=$work_dir/pkgconfig-consumer
    export PKG_CONFIG_PATH="$libdir/pkgconfig"
    if [ -n "${KAIROS_EXPECTED_VERSION:-}" ]; then
        [ "$(pkg-config --modversion kairos)" = "$KAIROS_EXPECTED_VERSION" ] ||
            fail "pkg-config --modversion kairos is $(pkg-config --modversion kairos), expected $KAIROS_EXPECTED_VERSION"
    fi
    flags=$(pkg-config --cflags --libs kairos)
    echo "pkg-config --cflags --libs kairos: $flags"
    # shellcheck disable=SC2086 # the flags are meant to split into words
    "$cc" -std=c99 -Wall -Wextra -pedantic -Werror ${CFLAGS:-} -o "$out" "$here/main.c" $flags ${LDFLAGS:-} ||
        fail "building main.c with pkg-config flags failed"
    LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$out" ||
        fail "the consumer program built with pkg-config failed"
}

do_major() {
    local build=$work_dir/cmake-consumer-major
    rm -rf "$build"
    if "$cmake" -S "$here" -B "$build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" \
        -DKAIROS_CONSUMER_WANTS=1 >"$work_dir/cmake-major.log" 2>&1; then
        cat "$work_dir/cmake-major.log" >&2
        fail "find_package(kairos 1 REQUIRED) succeeded against a 0.x install"
    fi
    # It must fail for the right reason: the version, not a missing package.
    grep -q "$prefix/.*kairosConfig.cmake, version: 0\." "$work_dir/cmake-major.log" ||
        { cat "$work_dir/cmake-major.log" >&2; fail "find_package(kairos 1) failed, but not on the version check"; }
    echo "find_package(kairos 1 REQUIRED) fails as it should"
}

do_python() {
    local python=${PYTHON3:-python3} init pkgdir
    "$python" -c "import numpy" 2>/dev/null || { echo "numpy missing for $python: skipped"; exit 77; }
    init=$(find "$prefix" -path '*/kairos/__init__.py' -print -quit)
    [ -n "$init" ] || fail "the Python package was not installed under $prefix"
    pkgdir=$(dirname "$(dirname "$init")")
    [ -f "$pkgdir/kairos/_location.py" ] || fail "kairos/_location.py was not installed"
    # From a directory outside the source and build trees, so only the install can be found.
    local loaded
    loaded=$(cd "$work_dir" && env -u KAIROS_LIBRARY PYTHONPATH="$pkgdir" PYTHONDONTWRITEBYTECODE=1 "$python" -c \
        "import kairos; b = kairos.Box((1, 2, 3)); print(kairos.library_path())") ||
        fail "python3 -c 'import kairos' failed on the installed package"
    echo "the installed package loaded $loaded"
    case "$(readlink -f "$loaded")" in
        "$(readlink -f "$prefix")"/*) ;;
        *) fail "the installed package loaded $loaded, not the library installed in $prefix" ;;
    esac
}

case "$step" in
    install) do_install ;;
    cmake) do_cmake ;;
    pkgconfig) do_pkgconfig ;;
    major) do_major ;;
    python) do_python ;;
    all) do_install; do_cmake; do_pkgconfig; do_major; do_python ;;
    *) fail "unknown step (install, cmake, pkgconfig, major, python or all)" ;;
esac
echo "run_consumer.sh $step: OK"
