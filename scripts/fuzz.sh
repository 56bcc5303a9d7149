#!/usr/bin/env bash
# Fuzzes for a bounded time with seven libFuzzer targets: the glTF/GLB loader (bytes, and the
# document structure), the `lantern render` command line (option values, --dry-run) and the
# mesh formats' loaders (OBJ with an MTL, PLY, STL, OFF: tests/fuzz/MeshFuzz.cpp): builds
# the asan preset (clang, AddressSanitizer + UndefinedBehavior-
# Sanitizer + libFuzzer), seeds a corpus from ../shared/assets (the samples and the
# glTF-Validator's invalid files), the regression inputs and tests/fuzz/seeds/ (the mesh targets
# from tests/fuzz/mesh-seeds/FORMAT/ and mesh-regressions/), runs each for a seventh of the time,
# and prints libFuzzer's totals. Usage: scripts/fuzz.sh [SECONDS] (default 120). Exit non-zero on a crash;
# the input that crashed is left in build/asan/fuzz-findings/ (add it to
# tests/fuzz/regressions/ with the fix).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
scripts/build.sh asan >/dev/null
shared=${LANTERN_SHARED_DIR:-../shared}
corpus=build/asan/fuzz-corpus
findings=build/asan/fuzz-findings
mkdir -p "$corpus" "$findings"
if [ -d "$shared/assets" ]; then
    find "$shared/assets" \( -name '*.gltf' -o -name '*.glb' \) -size -1024k -print0 |
        while IFS= read -r -d '' f; do cp -f "$f" "$corpus/$(echo "$f" | md5sum | cut -c1-16)"; done
else
    echo "fuzz: $shared/assets not found; seeding from the regression inputs only" >&2
fi
cp -f tests/fuzz/regressions/* "$corpus/" 2>/dev/null || true
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
# Seven targets share the time: the byte fuzzer (GltfFuzz.cpp: any bytes as .gltf/.glb), the
# structure fuzzer (GltfStructureFuzz.cpp: valid documents mutated as JSON trees, seeded also
# with tests/fuzz/seeds/) and the command-line fuzzer (CliFuzz.cpp: arguments one per line,
# seeded with tests/fuzz/cli-seeds/ and cli-regressions/, with a dictionary of every render
# option read from `lantern help --markdown`), and one per mesh format (MeshFuzz.cpp, seeded with
# tests/fuzz/mesh-seeds/FORMAT/ and the mesh regressions of that format). -jobs/-workers 1: the 2-core CI machine;
# -timeout: a hang (one input over 10 s) is a finding. The corpora live under build/asan only:
# libFuzzer writes new units into its first corpus folder, never a tracked one.
log=build/asan/fuzz.log
: >"$log"
status=0
total=0
dict=build/asan/fuzz-cli.dict
build/asan/apps/lantern/lantern help --markdown |
    awk '/^## `lantern render`/ {on = 1; next} /^## / {on = 0} on' |
    grep -oE -- '`--[a-z][a-z0-9-]*' | tr -d '`' | sort -u | sed 's/.*/"&"/' >"$dict"
targets=(gltf structure cli obj ply stl off)
for target in "${targets[@]}"; do
    dirs=("$corpus")
    extra=(-max_len=65536)
    if [ "$target" = structure ]; then
        mkdir -p "$corpus-structure"
        cp -f tests/fuzz/seeds/*.gltf "$corpus-structure/" 2>/dev/null || true
        dirs=("$corpus-structure" "$corpus")
    elif [ "$target" = cli ]; then
        mkdir -p "$corpus-cli"
        cp -f tests/fuzz/cli-seeds/* tests/fuzz/cli-regressions/* "$corpus-cli/"
        dirs=("$corpus-cli")
        # The command prints on every run: stdout and stderr closed (libFuzzer keeps its own).
        extra=(-max_len=4096 -dict="$dict" -close_fd_mask=3)
    elif [ "$target" != gltf ]; then
        mkdir -p "$corpus-$target"
        cp -f tests/fuzz/mesh-seeds/"$target"/* "$corpus-$target/"
        cp -f tests/fuzz/mesh-regressions/*."$target" "$corpus-$target/" 2>/dev/null || true
        dirs=("$corpus-$target")
    fi
    one=build/asan/fuzz-$target.log
    build/asan/tests/fuzz/lantern_fuzz_$target "${dirs[@]}" -max_total_time="$(( (seconds + ${#targets[@]} - 1) / ${#targets[@]} ))" \
        -timeout=10 -rss_limit_mb=2048 "${extra[@]}" -artifact_prefix="$findings/$target-" \
        -print_final_stats=1 >"$one" 2>&1 || status=$?
    cat "$one" >>"$log"
    echo "fuzz: $target" >&2
    grep -E '^(#[0-9]+ +(INITED|DONE)|Done|stat::|==[0-9]+==ERROR|SUMMARY|Test unit written)' "$one" || true
    runs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$one" | tail -n 1)
    total=$((total + ${runs:-0}))
    [ "$status" = 0 ] || break
done
[ "$status" = 0 ] || echo "fuzz: libFuzzer exited with $status; see $log and $findings/" >&2
echo "Done $total runs of the seven fuzzers (glTF bytes, glTF structure, command line, OBJ, PLY, STL, OFF)" | tee -a "$log"
exit "$status"
