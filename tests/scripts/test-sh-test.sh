#!/usr/bin/env bash
# Tests scripts/test.sh itself on a fake checkout: its scripts/build.sh and scripts/fuzz.sh are
# stand-ins that fail on demand, its suite is a tiny CMake project run by the real ctest (a test
# that passes, one that fails on demand, one that skips the way GoogleTest does). Checks that
# every stage runs whatever failed before it, that each has its summary line, that skipped
# tests are listed with their reasons, that ctest's arguments are passed on, and the exit status.
# Usage: test-sh-test.sh TEST_SH WORK_DIR CMAKE GENERATOR
set -euo pipefail
test_sh=$1 work=$2 cmake=$3 generator=$4
export PATH="$(dirname "$cmake"):$PATH"

fail() {
    echo "FAILED: $*" >&2
    exit 1
}

# A fresh fake checkout in $work/repo.
make_repo() {
    rm -rf "$work"
    local repo=$work/repo
    mkdir -p "$repo/scripts" "$repo/t"
    cp "$test_sh" "$repo/scripts/test.sh"
    cat >"$repo/scripts/build.sh" <<'SH'
#!/usr/bin/env bash
set -e
cd "$(dirname "$0")/.."
echo "build $1" >>ran
if [ "$1" = "${FAKE_FAILING_BUILD:-}" ]; then echo "fake: the $1 build failed" >&2; exit 2; fi
cmake --preset "$1" >/dev/null
SH
    cat >"$repo/scripts/fuzz.sh" <<'SH'
#!/usr/bin/env bash
cd "$(dirname "$0")/.."
echo fuzz >>ran
echo "Done 4321 runs in 1 second(s)"
SH
    chmod +x "$repo/scripts/"*.sh
    cat >"$repo/t/skip.sh" <<'SH'
printf '[ RUN      ] Fake.SkipsWithAReason\n/src/fake.cpp:3: Skipped\n'
printf 'the fake tool is not installed (Debian package fake-tool)\n\n'
printf '[  SKIPPED ] Fake.SkipsWithAReason (0 ms)\n'
SH
    cat >"$repo/t/skip77.sh" <<'SH'
echo "SKIPPED: the fake module was not built (a sanitizer build)"
exit 77
SH
    cat >"$repo/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.21)
project(fake NONE)
enable_testing()
add_test(NAME Fake.Passes COMMAND sh -c "exit 0")
add_test(NAME Fake.FailsOnDemand COMMAND sh -c "test \"$FAKE_PRESET\" != \"$FAKE_FAILING_SUITE\"")
add_test(NAME Fake.SkipsWithAReason COMMAND sh ${CMAKE_SOURCE_DIR}/t/skip.sh)
set_tests_properties(Fake.SkipsWithAReason PROPERTIES SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]")
add_test(NAME fake.skips_with_77 COMMAND sh ${CMAKE_SOURCE_DIR}/t/skip77.sh)
set_tests_properties(fake.skips_with_77 PROPERTIES SKIP_RETURN_CODE 77)
CM
    local p presets="" tests=""
    for p in ci asan; do
        presets+="{\"name\": \"$p\", \"generator\": \"$generator\", \"binaryDir\": \"\${sourceDir}/build/$p\"},"
        tests+="{\"name\": \"$p\", \"configurePreset\": \"$p\", \"environment\": {\"FAKE_PRESET\": \"$p\"}},"
    done
    printf '{"version": 3, "configurePresets": [%s], "testPresets": [%s]}\n' \
        "${presets%,}" "${tests%,}" >"$repo/CMakePresets.json"
}

# run_test_sh [ARGS...]: runs the fake checkout's test.sh; sets `out` and `rc`.
run_test_sh() {
    rc=0
    out=$("$work/repo/scripts/test.sh" "$@" 2>&1) || rc=$?
}

expect() {
    grep -Eq -- "$1" <<<"$out" || fail "no line matching '$1' in test.sh's output:
$out"
}

# 1. The ci suite and the asan build fail: the asan build still runs, the stages after it are
#    "not run", every stage has its line, the skipped test is listed with its reason.
export FAKE_FAILING_SUITE=ci FAKE_FAILING_BUILD=asan
make_repo
run_test_sh
[ "$rc" != 0 ] || fail "test.sh exited 0 with failing stages"
expect '^   ci build +passed +[0-9]+m[0-9]{2}s$'
expect '^   ci suite +FAILED +[0-9]+m[0-9]{2}s  1 passed, 1 failed, 2 skipped \(of 4\)$'
expect '^   Fake\.SkipsWithAReason: the fake tool is not installed \(Debian package fake-tool\)$'
expect '^   fake\.skips_with_77: the fake module was not built \(a sanitizer build\)$'
expect '^   asan build +FAILED +[0-9]+m[0-9]{2}s  \(exit 2\)$'
expect '^   asan suite +not run +0m00s  \(the asan build failed\)$'
expect '^   fuzz +not run +0m00s  \(the asan build failed\)$'
expect '^== test.sh: FAILED: ci suite FAILED, asan build FAILED, asan suite not run, fuzz not run$'
[ "$(cat "$work/repo/ran")" = "$(printf 'build ci\nbuild asan')" ] ||
    fail "the stages that ran: $(cat "$work/repo/ran")"

# 2. Nothing fails: exit 0, the asan suite and fuzzing summarised.
unset FAKE_FAILING_SUITE FAKE_FAILING_BUILD
make_repo
run_test_sh
[ "$rc" = 0 ] || fail "test.sh exited $rc with every stage passing:
$out"
expect '^   ci suite +passed .* 2 passed, 0 failed, 2 skipped \(of 4\)$'
expect '^   asan suite +passed .* 2 passed, 0 failed, 2 skipped \(of 4\)$'
expect '^   fuzz +passed +[0-9]+m[0-9]{2}s  4321 runs, no crash$'
expect '^== test.sh: every stage passed$'

# 3. The ci build fails and ctest's arguments are passed on: the asan stages still run.
export FAKE_FAILING_BUILD=ci
make_repo
run_test_sh -R Passes
[ "$rc" != 0 ] || fail "test.sh exited 0 with a failed build"
expect '^   ci build +FAILED'
expect '^   ci suite +not run +0m00s  \(the ci build failed\)$'
expect '^   asan suite +passed .* 1 passed, 0 failed, 0 skipped \(of 1\)$'
expect '^   fuzz +passed'
[ "$(cat "$work/repo/ran")" = "$(printf 'build ci\nbuild asan\nfuzz')" ] ||
    fail "the stages that ran: $(cat "$work/repo/ran")"
echo "scripts/test.sh: every scenario behaved"
