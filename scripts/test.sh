#!/usr/bin/env bash
# Quick start, second command: installs what is missing, builds with warnings as errors, and
# runs the whole test suite (CTest; GPU tests run on lavapipe, window tests under Xvfb).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh ci
ctest --preset ci "$@"
