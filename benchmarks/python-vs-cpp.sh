#!/usr/bin/env bash
# Renders per second of a 256x256 builtin:teapot from Python (lantern module) against the same
# loop through the C++ API (lantern_render_loop), in interleaved rounds (C++, Python, C++, ...)
# so that both see the same machine; prints each round and the medians' ratio.
# Usage: benchmarks/python-vs-cpp.sh [BUILD_DIR] [ROUNDS] [RENDERS]   (default build/dev 5 200)
# PYTHON=... chooses the interpreter (default /usr/bin/python3, which the module is built for).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/dev}
rounds=${2:-5}
renders=${3:-200}
# Debian's python3 (its python3-numpy), not a pyenv or virtualenv one first on PATH.
python=${PYTHON:-$( [ -x /usr/bin/python3 ] && echo /usr/bin/python3 || echo python3 )}
cpp=() py=()
for ((r = 1; r <= rounds; r++)); do
    c=$("$build/benchmarks/lantern_render_loop" builtin:teapot 256 256 "$renders")
    p=$(PYTHONPATH="$build/python" "$python" benchmarks/render_loop.py builtin:teapot 256 256 "$renders")
    echo "round $r: $c"
    echo "round $r: $p"
    cpp+=("$(sed -E 's/.*: ([0-9.]+) renders\/s.*/\1/' <<<"$c")")
    py+=("$(sed -E 's/.*: ([0-9.]+) renders\/s.*/\1/' <<<"$p")")
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
mc=$(median "${cpp[@]}")
mp=$(median "${py[@]}")
awk -v c="$mc" -v p="$mp" 'BEGIN {printf "median renders/s: C++ %.2f, Python %.2f; Python / C++ = %.3f\n", c, p, p / c}'
