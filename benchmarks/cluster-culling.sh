#!/usr/bin/env bash
# What clusters, culling and levels of detail buy (gpu/Clusters.h, docs/performance.md
# "Clusters"): grids of spheres of 0.1, 2.0 and 8.1 million triangles (benchmarks/make-grid.py,
# each sphere its own mesh) drawn by `lantern bench frame` at WIDTHxHEIGHT (median of RUNS
# frames, two rounds), viewed whole as Lantern frames them, with --no-culling, culled, and
# with --lod-error 0.5 and 1; then the 8.1 M grid from inside (the camera among the spheres,
# half of them behind it), culled and not; then the pictures compared: culled against
# everything bit for bit, the levels of detail against the exact one by `lantern compare`.
# Usage: benchmarks/cluster-culling.sh   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern;
#        WIDTH, HEIGHT default 1920 1080; RUNS default 3; SIZES default "0.1e6 2.0e6 8.1e6")
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
width=${WIDTH:-1920} height=${HEIGHT:-1080} runs=${RUNS:-3} sizes=${SIZES:-"0.1e6 2.0e6 8.1e6"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
frame() {  # scene, options...: the GPU render pass's median and the triangles drawn
    "$lantern" bench frame "$@" --width "$width" --height "$height" --runs "$runs" --warmup 1 |
        grep -E "GPU render pass|renderView|clustered triangles" | tr -s ' ' | paste -sd ';'
}
for size in $sizes; do python3 benchmarks/make-grid.py "$out/grid-$size.gltf" --triangles "$size"; done
last="$out/grid-${sizes##* }.gltf"
inside=(--look-at 0.3,1.2,0.2,-6,0.2,-9,0,1,0)
for round in 1 2; do  # two rounds, each configuration once per round: a slow spell shows
    for size in $sizes; do
        for mode in --no-culling "" "--lod-error 0.5" "--lod-error 1"; do
            # shellcheck disable=SC2086
            printf 'round %s %-8s %-16s %s\n' "$round" "$size" "${mode:-culled}" "$(frame "$out/grid-$size.gltf" $mode)"
        done
    done
    for mode in --no-culling ""; do
        # shellcheck disable=SC2086
        printf 'round %s %-8s %-16s %s\n' "$round" "inside" "${mode:-culled}" "$(frame "$last" "${inside[@]}" $mode)"
    done
done
"$lantern" render "$last" "${inside[@]}" -o "$out/inside-culled.exr" --width "$width" --height "$height" >/dev/null
"$lantern" render "$last" "${inside[@]}" --no-culling -o "$out/inside-all.exr" --width "$width" --height "$height" >/dev/null
cmp "$out/inside-culled.exr" "$out/inside-all.exr" && echo "inside: culled and unculled pictures are the same, bit for bit"
"$lantern" render "$last" -o "$out/whole-exact.exr" --width "$width" --height "$height" >/dev/null
for bound in 0.5 1; do
    "$lantern" render "$last" --lod-error "$bound" -o "$out/whole-lod.exr" --width "$width" --height "$height" >/dev/null
    echo "--lod-error $bound against the exact picture:"
    "$lantern" compare "$out/whole-lod.exr" "$out/whole-exact.exr" | grep -E "^all|FLIP" || true
done
