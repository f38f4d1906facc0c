# SPDX-License-Identifier: MIT
# Shared helper of the quick-start scripts: installs missing Debian packages, prints ctest summaries.
# shellcheck shell=bash
# Sourced by scripts/test.sh, scripts/demo.sh and .ci/run; defines functions only.

# Everything a full build of the release preset needs: the compilers and CMake, GoogleTest,
# Google Benchmark and the peers the benchmarks compare against (libccd, FCL, Bullet),
# abigail-tools for the ABI check, python3 for the ctypes test, python3-numpy and python3-pytest
# for the Python package (Debian's /usr/bin/python3), binutils (nm, readelf) for the
# export check, gnuplot-nox for the benchmark plots, file for the packaging checks.
KAIROS_DEBIAN_PACKAGES=(
    cmake g++ make pkg-config binutils file
    libgtest-dev libgmock-dev libbenchmark-dev
    libccd-dev libfcl-dev libbullet-dev
    abigail-tools python3 python3-numpy python3-pytest gnuplot-nox
)

# Prints the packages of KAIROS_DEBIAN_PACKAGES that dpkg does not report as installed.
kairos_missing_packages() {
    local pkg
    for pkg in "${KAIROS_DEBIAN_PACKAGES[@]}"; do
        if [ "$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null)" != "install ok installed" ]; then
            echo "$pkg"
        fi
    done
}

# Installs exactly the missing packages when run as root (apt-get update first only when the
# package lists are empty, or when an install fails on stale lists). As another user it prints
# the command to run and returns 1. On a system without dpkg it warns and returns 0, leaving
# CMake to report what it cannot find.
kairos_ensure_deps() {
    if ! command -v dpkg-query >/dev/null 2>&1; then
        echo "kairos: not a Debian system (no dpkg-query); make sure these are installed:" \
             "${KAIROS_DEBIAN_PACKAGES[*]}" >&2
        return 0
    fi
    local missing
    missing=$(kairos_missing_packages | tr '\n' ' ')
    missing=${missing% }
    if [ -z "$missing" ]; then
        return 0
    fi
    if [ "$(id -u)" -ne 0 ]; then
        echo "kairos: missing Debian packages: $missing" >&2
        echo "Run as root first:" >&2
        if compgen -G '/var/lib/apt/lists/*_Packages*' >/dev/null; then
            echo "  apt-get install -y --no-install-recommends $missing" >&2
        else
            echo "  apt-get update && apt-get install -y --no-install-recommends $missing" >&2
        fi
        return 1
    fi
    echo "kairos: installing missing Debian packages: $missing"
    export DEBIAN_FRONTEND=noninteractive
    if ! compgen -G '/var/lib/apt/lists/*_Packages*' >/dev/null; then
        apt-get update </dev/null
    fi
    # shellcheck disable=SC2086 # one word per package
    if ! apt-get install -y --no-install-recommends $missing </dev/null; then
        echo "kairos: apt-get install failed; refreshing the package lists and trying once more" >&2
        apt-get update </dev/null
        # shellcheck disable=SC2086
        apt-get install -y --no-install-recommends $missing </dev/null
    fi
    missing=$(kairos_missing_packages | tr '\n' ' ')
    if [ -n "${missing% }" ]; then
        echo "kairos: still missing after apt-get install: $missing" >&2
        return 1
    fi
}

# Parallel builds and tests by default (CMake and CTest read these); the caller may set them.
kairos_parallel_defaults() {
    local cores
    cores=$(nproc 2>/dev/null || echo 2)
    export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-$cores}
    export CTEST_PARALLEL_LEVEL=${CTEST_PARALLEL_LEVEL:-$cores}
}

# kairos_ctest_summary <title> <log>: the ctest result lines of a logged run (the pass count, and
# the list of failed tests if any).
kairos_ctest_summary() {
    local title=$1 log=$2
    echo "==== $title ===="
    if [ ! -f "$log" ]; then
        echo "(no log at $log)"
        return 0
    fi
    if grep -q 'tests passed' "$log"; then
        # From "NN% tests passed" to the end: the failed and not-run lists, without the label times.
        sed -n '/tests passed/,$p' "$log" |
            grep -Ev '^(Label Time Summary:|[[:alnum:]_]+ += .*sec\*proc)' | cat -s || true
    else
        echo "ctest did not run to the end (configure or build failed); last lines:"
        tail -n 25 "$log"
    fi
}
