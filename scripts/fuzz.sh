#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets of tests/fuzz and runs each for a while.
#
# Usage: bash scripts/fuzz.sh [SECONDS]   (default 60 seconds per target)
#
# Installs clang and libFuzzer's runtime when missing (as root on Debian; as another user it
# prints the apt-get line), configures and builds tests/fuzz into build/fuzz with clang
# (-O1 -g, AddressSanitizer, UndefinedBehaviorSanitizer), then runs fuzz_shapes, fuzz_queries
# and fuzz_world one after the other, each on a copy of its committed corpus in
# build/fuzz/corpus-work/<target> (the committed corpus is only read). Prints the executions
# of each run and exits non-zero when any target found a crash, leak, timeout or contract
# violation, naming the saved input. Non-interactive: safe in CI.
#
# KAIROS_FUZZ_SEED=N fixes libFuzzer's random seed (-seed=N): the same build then replays the
# same sequence of inputs, so a run is reproducible (CI sets it; a campaign leaves it unset and
# explores a new sequence each time).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
exec </dev/null

usage() { echo "usage: bash scripts/fuzz.sh [SECONDS]   (seconds per target, default 60)"; }
seconds=${1:-60}
case "$seconds" in
    -h | --help) usage; exit 0 ;;
    '' | *[!0-9]*) usage >&2; exit 2 ;;
esac
if [ "$seconds" -lt 1 ]; then
    usage >&2
    exit 2
fi

# shellcheck source=scripts/deps.sh
. "$root/scripts/deps.sh"
# The fuzz build needs only these (clang's libFuzzer and sanitizer runtimes come with libclang-rt-dev).
KAIROS_DEBIAN_PACKAGES=(cmake make clang libclang-rt-dev)
kairos_ensure_deps || exit 1
kairos_parallel_defaults

build=build/fuzz
echo "==== scripts/fuzz.sh: configure and build tests/fuzz into $build ===="
cmake -S tests/fuzz -B "$build" -DCMAKE_CXX_COMPILER=clang++
cmake --build "$build"

targets=(fuzz_shapes fuzz_queries fuzz_world)
seed_arg=()
if [ -n "${KAIROS_FUZZ_SEED:-}" ]; then
    case "$KAIROS_FUZZ_SEED" in
        *[!0-9]*) echo "KAIROS_FUZZ_SEED must be a number" >&2; exit 2 ;;
    esac
    seed_arg=(-seed="$KAIROS_FUZZ_SEED")
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
mkdir -p "$build/logs"
failed=0
summary=()
for target in "${targets[@]}"; do
    work=$build/corpus-work/$target
    artifacts=$build/artifacts/$target
    log=$build/logs/$target.log
    mkdir -p "$work" "$artifacts"
    # Seeds join what earlier runs found; the committed corpus itself is never written.
    if [ -d "tests/fuzz/corpus/$target" ]; then
        find "tests/fuzz/corpus/$target" -maxdepth 1 -type f -exec cp -f {} "$work/" \;
    fi
    echo "==== $target: ${seconds} s (log: $log) ===="
    status=0
    # The outer timeout only guards against libFuzzer itself not stopping.
    timeout --kill-after=30 $((seconds + 300)) "$build/$target" \
        -max_total_time="$seconds" "${seed_arg[@]}" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
        -artifact_prefix="$artifacts/" "$work" >"$log" 2>&1 || status=$?
    runs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$log" | tail -n 1)
    [ -n "$runs" ] || runs=$(sed -n 's/^stat::number_of_executed_units: *\([0-9]*\).*/\1/p' "$log" | tail -n 1)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *\([0-9]*\).*/\1/p' "$log" | tail -n 1)
    crash=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -n 1)
    line="$target: ${runs:-?} executions, ${rate:-?}/s"
    if [ "$status" -ne 0 ] || [ -n "$crash" ]; then
        failed=1
        line="$line: FAILED (exit $status)${crash:+; input saved as $crash}"
        echo "---- last lines of $log ----"
        tail -n 40 "$log"
        if [ -n "$crash" ]; then
            echo "Reproduce: $build/$target $crash"
        fi
    fi
    echo "$line"
    summary+=("$line")
done

echo
echo "==== scripts/fuzz.sh summary ===="
printf '%s\n' "${summary[@]}"
if [ "$failed" -ne 0 ]; then
    echo "scripts/fuzz.sh: FAILED" >&2
    exit 1
fi
echo "scripts/fuzz.sh: no findings"
