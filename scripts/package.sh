#!/usr/bin/env bash
# Builds the Debian package: a Release build with the shared libLantern and the prefix /usr in
# build/package, then `cpack -G DEB` (cmake/LanternPackage.cmake), then lintian when it is
# installed. Prints the package's path. Usage: scripts/package.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh package >&2
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S . -B build/package "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
    -DLANTERN_BUILD_TESTS=OFF -DLANTERN_TESTING_HOOKS=OFF -DCMAKE_INSTALL_PREFIX=/usr \
    -DCMAKE_SKIP_INSTALL_RPATH=ON -DLANTERN_INSTALL_PYTHONDIR=lib/python3/dist-packages \
    -DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache >&2
cmake --build build/package >&2
(cd build/package && cpack -G DEB >&2)
deb=$(ls build/package/lantern_*.deb)
if command -v lintian >/dev/null; then
    lintian --no-tag-display-limit "$deb" >&2 || true
fi
echo "$deb"
