#!/usr/bin/env bash
# Quick start, second command: installs what is missing, then
#   1. builds with GCC and warnings as errors and runs the whole test suite (GPU tests on
#      lavapipe, window tests under Xvfb, the Slurm test on a single-node cluster);
#   2. builds with clang, AddressSanitizer and UndefinedBehaviorSanitizer and runs the whole
#      suite again under them (LeakSanitizer included);
#   3. fuzzes the glTF/GLB loader for a bounded time (LANTERN_FUZZ_SECONDS, default 60).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh ci
ctest --preset ci "$@"
scripts/build.sh asan
ctest --preset asan "$@"
scripts/fuzz.sh "${LANTERN_FUZZ_SECONDS:-60}"
