#!/usr/bin/env bash
# Renders per second from 1 to N cores (docs/performance.md "All the cores"): a batch of the
# glTF samples of ../shared/assets (COUNT files x 4 views) rendered by `lantern render --list`,
# small (256x256 PNG) and large (1280x720 EXR), on the first k cores (taskset) for k = 1, 2,
# 4, ... up to the machine's cores, three ways:
#   threads    one batch, lavapipe with k rasteriser threads (LP_NUM_THREADS=k, its default);
#   processes  k batches side by side, each a k-th of the list, lavapipe one thread each;
#   both       k / 2 batches (at least one) of 2 threads each;
#   --processes one batch that Lantern runs as k processes (`render --processes k`), one
#              lavapipe thread each: what `processes` measures, done by Lantern itself.
# Prints renders per second for each. Usage: benchmarks/cores.sh [COUNT=24]
#   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern; ASSETS=../shared/assets/gltf-samples)
set -euo pipefail
cd "$(dirname "$0")/.."
count=${1:-24}
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
assets=$(realpath "${ASSETS:-../shared/assets/gltf-samples}")
cores=$(nproc)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mapfile -t samples < <(find "$assets" \( -name '*.gltf' -o -name '*.glb' \) | sort)
good=()
for s in "${samples[@]}"; do
    "$lantern" render "$s" --width 64 --height 64 -o "$out/probe.png" >/dev/null 2>&1 && good+=("$s")
done
for ((i = 0; i < count; ++i)); do echo "${good[i % ${#good[@]}]}"; done >"$out/list.txt"
echo "cores: $count files (${#good[@]} distinct samples) x 4 views; machine: $cores cores"

now() { date +%s.%N; }
# batch K_CORES PROCESSES THREADS SIZE EXT [OWN]: renders per second (OWN: one command with
# --processes PROCESSES instead of PROCESSES commands)
batch() {
    local k=$1 procs=$2 threads=$3 w=$4 h=$5 ext=$6 own=${7:-}
    local flags=()
    if [[ -n $own ]]; then flags=(--processes "$procs"); procs=1; fi
    split -n "l/$procs" -d "$out/list.txt" "$out/part."
    local t0 t1 dir="$out/img/$k-$procs-$threads-$w" failed=0
    mkdir -p "$dir"  # a new folder each run: Lantern overwrites no file it did not make
    t0=$(now)
    for part in "$out"/part.*; do
        LP_NUM_THREADS=$threads taskset -c "0-$((k - 1))" "$lantern" render --list "$part" \
            "${flags[@]}" --allow-folder "$assets" --views front,right,back,left --width "$w" --height "$h" \
            -o "$dir/$(basename "$part")_{index}_{view}.$ext" >/dev/null 2>"$part.err" &
    done
    for job in $(jobs -p); do wait "$job" || failed=1; done
    ((failed == 0)) || { cat "$out"/part.*.err >&2; exit 1; }
    t1=$(now)
    rm -f "$out"/part.*
    [ "$(find "$dir" -type f | wc -l)" -eq $((count * 4)) ] || { echo "cores: images missing in $dir" >&2; exit 1; }
    awk -v n=$((count * 4)) -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", n / (b - a) }'
}
printf '%-6s %-10s %14s %14s\n' cores way "256x256 png/s" "1280x720 exr/s"
k=1
while ((k <= cores)); do
    for way in threads processes both --processes; do
        case $way in
        threads) procs=1 threads=$k ;;
        processes) procs=$k threads=1 ;;
        both) procs=$(((k + 1) / 2)) threads=$((k > 1 ? 2 : 1)) ;;
        --processes) procs=$k threads=1 ;;
        esac
        ((k == 1)) && [[ $way != threads ]] && continue
        [[ $way == both ]] && ((k <= 2)) && continue  # the same as threads or processes
        own=$([[ $way == --processes ]] && echo 1 || true)
        small=$(batch "$k" "$procs" "$threads" 256 256 png "$own")
        large=$(batch "$k" "$procs" "$threads" 1280 720 exr "$own")
        printf '%-6s %-10s %14s %14s\n' "$k" "$way" "$small" "$large"
    done
    ((k == cores)) && break
    k=$((k * 2 > cores ? cores : k * 2))
done
