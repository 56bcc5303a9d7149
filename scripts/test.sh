#!/usr/bin/env bash
# Quick start, second command: installs what is missing, then runs five stages:
#   ci build     GCC, warnings as errors (scripts/build.sh ci)
#   ci suite     the whole test suite: GPU tests on lavapipe, window tests under Xvfb, the
#                Slurm tests on a private single-node cluster (ctest --preset ci)
#   asan build   clang with AddressSanitizer and UndefinedBehaviorSanitizer (scripts/build.sh asan)
#   asan suite   the whole suite again under them, LeakSanitizer included (ctest --preset asan)
#   fuzz         the glTF/GLB loader and the command line for LANTERN_FUZZ_SECONDS seconds (default 60)
# Every stage runs even when an earlier one failed, so that one failure does not hide the
# others; only a stage whose build failed is "not run". Each suite stage ends with the tests it
# skipped and why (a test skips, naming it, when the machine lacks what it needs: a device, a
# tool, a privilege). The end is one summary line per stage; the exit status is 0 only when
# every stage passed. Arguments go to both ctest runs (e.g. -L unit, -R Failure). Each stage's
# output is also kept in build/test-logs/.
set -uo pipefail
cd "$(dirname "$0")/.."

logs=build/test-logs
mkdir -p "$logs"
summary=()
failures=()

elapsed() { printf '%dm%02ds' $(($1 / 60)) $(($1 % 60)); }

# record NAME STATUS SECONDS [DETAILS]: one summary line, and the failures for the exit status.
record() {
    local line
    line=$(printf '%-11s %-8s %7s' "$1" "$2" "$(elapsed "$3")")
    [ -n "${4:-}" ] && line+="  $4"
    summary+=("$line")
    [ "$2" = passed ] || failures+=("$1 $2")
    echo "== test.sh: $line"
}

# run NAME LOG CMD...: runs CMD, its output shown and kept in LOG; sets `status` and `seconds`.
run() {
    local name=$1 log=$2 start=$SECONDS
    shift 2
    echo "== test.sh: $name: $*"
    "$@" 2>&1 | tee "$log"
    status=${PIPESTATUS[0]}
    seconds=$((SECONDS - start))
}

# skip_reasons LASTTESTLOG: "NAME<TAB>REASON" for every test whose GoogleTest output says it
# skipped; the reason is the message between "file:line: Skipped" and the blank line after it,
# or the rest of a "SKIPPED: " line (a script that exits with its SKIP_RETURN_CODE says why so).
skip_reasons() {
    awk '
        /^[0-9]+\/[0-9]+ Testing: / { name = $0; sub(/^[0-9]+\/[0-9]+ Testing: /, "", name); grab = 0; next }
        grab && (/^$/ || /^\[  SKIPPED \]/ || /^<end of output>$/) { grab = 0; print name "\t" reason; next }
        grab { reason = reason (reason == "" ? "" : " ") $0; next }
        /: Skipped$/ && !(name in seen) { seen[name] = 1; grab = 1; reason = "" }
        /^SKIPPED: / && !(name in seen) { seen[name] = 1; r = $0; sub(/^SKIPPED: /, "", r); print name "\t" r }
    ' "$1" 2>/dev/null
}

# suite NAME PRESET [CTEST ARGS...]: ctest on a preset, then its counts and skipped tests.
suite() {
    local name=$1 preset=$2 log=$logs/$1.log
    log=${log// /-}
    shift 2
    run "$name" "$log" ctest --preset "$preset" "$@"
    local total failed skipped details
    total=$(sed -n 's/^[0-9]*% tests passed, [0-9]* tests\{0,1\} failed out of \([0-9]*\)$/\1/p' "$log" | tail -n 1)
    failed=$(sed -n 's/^[0-9]*% tests passed, \([0-9]*\) tests\{0,1\} failed out of [0-9]*$/\1/p' "$log" | tail -n 1)
    local names
    names=$(sed -n 's/^[[:space:]]*[0-9]* - \(.*\) (Skipped)$/\1/p' "$log")
    skipped=$(printf '%s' "$names" | grep -c . || true)
    if [ -n "$total" ]; then
        details="$((total - failed - skipped)) passed, $failed failed, $skipped skipped (of $total)"
    else
        details="no test summary from ctest (see $log)"
    fi
    if [ "$skipped" -gt 0 ]; then
        local reasons
        reasons=$(skip_reasons "build/$preset/Testing/Temporary/LastTest.log")
        echo "== test.sh: $name skipped $skipped test(s):"
        while IFS= read -r test; do
            local reason
            reason=$(awk -F '\t' -v t="$test" '$1 == t { print $2; exit }' <<<"$reasons")
            echo "   $test: ${reason:-(no reason printed)}"
        done <<<"$names"
    fi
    local result=passed
    [ "$status" = 0 ] || result=FAILED
    record "$name" "$result" "$seconds" "$details"
}

# build NAME PRESET: sets `built` to whether the build succeeded.
build() {
    local log=$logs/$1.log
    run "$1" "${log// /-}" scripts/build.sh "$2"
    built=$status
    if [ "$built" = 0 ]; then record "$1" passed "$seconds"; else record "$1" FAILED "$seconds" "(exit $built)"; fi
}

build "ci build" ci
if [ "$built" = 0 ]; then suite "ci suite" ci "$@"; else record "ci suite" "not run" 0 "(the ci build failed)"; fi

build "asan build" asan
if [ "$built" = 0 ]; then
    suite "asan suite" asan "$@"
    run fuzz "$logs/fuzz.log" scripts/fuzz.sh "${LANTERN_FUZZ_SECONDS:-60}"
    runs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$logs/fuzz.log" | tail -n 1)
    if [ "$status" = 0 ]; then
        record fuzz passed "$seconds" "${runs:-?} runs, no crash"
    else
        record fuzz FAILED "$seconds" "(exit $status; findings in build/asan/fuzz-findings/)"
    fi
else
    record "asan suite" "not run" 0 "(the asan build failed)"
    record fuzz "not run" 0 "(the asan build failed)"
fi

echo
echo "== test.sh: summary (logs in $logs/)"
printf '   %s\n' "${summary[@]}"
if [ ${#failures[@]} -gt 0 ]; then
    echo "== test.sh: FAILED: $(printf '%s, ' "${failures[@]}" | sed 's/, $//')"
    exit 1
fi
echo "== test.sh: every stage passed"
