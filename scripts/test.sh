#!/usr/bin/env bash
# Quick start, second command: installs what is missing, builds with warnings as errors, runs
# the whole test suite (GPU tests on lavapipe), then rebuilds with AddressSanitizer and
# UndefinedBehaviorSanitizer and runs the CPU-side suites (unit, loader) under them.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh ci
ctest --preset ci "$@"
scripts/build.sh asan
ctest --preset asan
