#!/usr/bin/env bash
# Installs what is missing (Debian 12), configures and builds Lantern with the given CMake
# preset (default: dev). Prints nothing but errors unless the build does work.
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-dev}
scripts/install-deps.sh "${LANTERN_DEPS:-all}"
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
if [ ! -f "build/$preset/build.ninja" ]; then
    cmake --preset "$preset" >/dev/null
fi
cmake --build "build/$preset" -j "$(nproc)"
