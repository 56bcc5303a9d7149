#!/usr/bin/env bash
# Times loading (and loading + rendering one 1000x600 PNG) of the mesh benchmark files with
# Lantern and with F3D (Debian's f3d), the whole process of each, alternating, 3 runs each: prints
# the median wall time and peak memory (/usr/bin/time "%e s %M KB") per file and tool and the
# ratio F3D / Lantern. docs/performance.md ("Loading mesh files") has the results.
# Usage: benchmarks/mesh-load-bench.sh [DIR]   (DIR: what benchmarks/make-meshes.py wrote;
#        default build/meshes; LANTERN=path/to/lantern, default build/release/apps/lantern/lantern)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build/meshes}
lantern=${LANTERN:-build/release/apps/lantern/lantern}
runs=3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# One run: "SECONDS KB" of the command, which must succeed.
measure() {
    /usr/bin/time -f "%e %M" -o "$out/time" "$@" >"$out/log" 2>&1 || {
        echo "failed: $*" >&2
        tail -n 5 "$out/log" >&2
        exit 1
    }
    cat "$out/time"
}

median() { sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

printf '%-10s %-7s %18s %18s %8s %8s\n' file what "lantern s / MiB" "f3d s / MiB" "time" "memory"
for file in "$dir"/torus.obj "$dir"/torus.ply "$dir"/torus.stl; do
    for what in load render; do
        if [ "$what" = load ]; then
            ours=("$lantern" info "$file")
            theirs=(f3d --no-render "$file")
        else
            ours=("$lantern" render "$file" --width 1000 --height 600 -o "$out/lantern.png")
            theirs=(xvfb-run -a f3d --resolution 1000,600 --output "$out/f3d.png" "$file")
        fi
        : >"$out/ours"
        : >"$out/theirs"
        for _ in $(seq "$runs"); do  # alternating, so that a busy moment hits both
            measure "${ours[@]}" >>"$out/ours"
            measure "${theirs[@]}" >>"$out/theirs"
        done
        ot=$(cut -d' ' -f1 "$out/ours" | median)
        om=$(cut -d' ' -f2 "$out/ours" | median)
        tt=$(cut -d' ' -f1 "$out/theirs" | median)
        tm=$(cut -d' ' -f2 "$out/theirs" | median)
        awk -v f="$(basename "$file")" -v w="$what" -v ot="$ot" -v om="$om" -v tt="$tt" -v tm="$tm" \
            'BEGIN {printf "%-10s %-7s %9.2f / %6.0f %9.2f / %6.0f %7.2fx %7.2fx\n",
                    f, w, ot, om / 1024, tt, tm / 1024, tt / ot, tm / om}'
    done
done
