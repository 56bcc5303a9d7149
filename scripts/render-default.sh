#!/usr/bin/env bash
# Quick start, first command: installs what is missing, builds, and renders the default scene
# headless to out/default.exr plus a PNG preview, printing both paths.
set -euo pipefail
cd "$(dirname "$0")/.."
LANTERN_DEPS=build scripts/build.sh release >&2
mkdir -p out
# The Red Book example drew its teapots on black.
exec build/release/apps/lantern/lantern render builtin:default --background 0,0,0 -o out/default.exr -o out/default.png "$@"
