#!/usr/bin/env bash
# Installs, with apt-get, every Debian 12 package Lantern needs to build, run and test;
# does nothing (and needs no root) when all of them are already installed.
#
# Usage: scripts/install-deps.sh [build|test|all|slurm]   (default: all)
#   build  what `cmake --build` and `lantern render` need
#   test   build + the tools the test suite drives (Xvfb, xdotool, oiiotool, valgrind, clang,
#          gltfpack and draco_transcoder, OSMesa for the OpenGL peer benchmark, a single-node Slurm for the farm tests, pytest and NumPy
#          for the Python module's tests, matplotlib for the accuracy plot)
#   slurm  only Slurm and munge (scripts/slurm-single-node.sh install)
#   package the build tools and what scripts/package.sh adds: file and dpkg-dev (CPack's
#          shlibdeps), lintian
set -euo pipefail

what=${1:-all}

build_pkgs=(
    build-essential cmake ninja-build ccache pkg-config git
    libvulkan-dev vulkan-validationlayers mesa-vulkan-drivers glslang-tools
    libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libopenexr-dev
    libcli11-dev libfmt-dev libglfw3-dev libimgui-dev libx11-dev
    libpng-dev libyaml-cpp-dev libwebp-dev
    libgtest-dev libgmock-dev libbenchmark-dev
    libmeshoptimizer-dev libdraco-dev libtinyobjloader-dev
    python3-dev pybind11-dev python3-numpy
)
# The farm tests start a private single-node Slurm (scripts/slurm-single-node.sh).
slurm_pkgs=(slurm-wlm slurmctld slurmd slurm-client munge)
test_pkgs=(
    xvfb xauth xdotool x11-utils openimageio-tools vulkan-tools zsh fish man-db groff-base
    clang-14 libclang-rt-14-dev valgrind python3 librsvg2-bin
    gltfpack draco libosmesa6-dev
    "${slurm_pkgs[@]}" python3-yaml python3-pytest python3-matplotlib python3-distributed
)

case "$what" in
build) pkgs=("${build_pkgs[@]}") ;;
package) pkgs=("${build_pkgs[@]}" file dpkg-dev lintian) ;;  # scripts/package.sh: CPack's shlibdeps
test | all) pkgs=("${build_pkgs[@]}" "${test_pkgs[@]}") ;;
slurm) pkgs=("${slurm_pkgs[@]}") ;;
*)
    echo "usage: $0 [build|test|all|slurm|package]" >&2
    exit 2
    ;;
esac

missing=()
for p in "${pkgs[@]}"; do
    # dpkg-query prints "install ok installed" only for a fully installed package.
    if [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" != "install ok installed" ]; then
        missing+=("$p")
    fi
done

if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi

echo "install-deps: installing ${#missing[@]} missing package(s): ${missing[*]}" >&2
sudo=()
if [ "$(id -u)" != 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        sudo=(sudo)
    else
        echo "install-deps: not root and no sudo; install these packages: ${missing[*]}" >&2
        exit 1
    fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get -o DPkg::Lock::Timeout=300 update -qq
"${sudo[@]}" apt-get -o DPkg::Lock::Timeout=300 install -y -qq --no-install-recommends "${missing[@]}"
