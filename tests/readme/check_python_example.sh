#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the README's Python example (the first ```python block after "### From Python") against
# the built library, from the source tree's package.
# Usage: check_python_example.sh <README.md> <python dir> <libkairos.so> <python3>
# Exit 77 (skipped) when the interpreter lacks numpy, except in CI.
set -euo pipefail
readme=$1 pkg=$2 lib=$3 python=$4
"$python" -c "import numpy" 2>/dev/null || { echo "numpy missing for $python"; [ -n "${CI:-}" ] && exit 1; exit 77; }
code=$(awk '/^### From Python/ { f = 1 } f && /^```python$/ { p = 1; next } p && /^```$/ { exit } p { print }' "$readme")
[ -n "$code" ] || { echo "no python block after '### From Python' in $readme" >&2; exit 1; }
cd "$(mktemp -d)"
printf '%s\n' "$code" > example.py
KAIROS_LIBRARY=$lib PYTHONPATH=$pkg PYTHONDONTWRITEBYTECODE=1 "$python" example.py
