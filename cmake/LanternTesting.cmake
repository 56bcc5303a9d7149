# lantern_add_test(): one GoogleTest executable, its tests discovered into CTest with a label
# (unit, gpu, image, robustness, install, window, farm), and GoogleTest skips reported as
# CTest skips rather than passes. The pipeline cache goes to the build tree, never the user's
# ~/.cache (LANTERN_CACHE_DIR).
find_package(GTest CONFIG REQUIRED)
include(GoogleTest)

set(LANTERN_SHARED_DIR "${PROJECT_SOURCE_DIR}/../shared" CACHE PATH
    "The shared/ folder beside the checkout (test assets, spec)")

# lantern_add_test(<name> LABEL <label> SOURCES <files...> [LIBS <libs...>] [TIMEOUT <s>])
function(lantern_add_test name)
    cmake_parse_arguments(ARG "" "LABEL;TIMEOUT" "SOURCES;LIBS" ${ARGN})
    if(NOT ARG_TIMEOUT)
        set(ARG_TIMEOUT 300)
    endif()
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE lantern_test_support GTest::gtest GTest::gmock
        ${ARG_LIBS} lantern_warnings lantern_sanitizers)
    gtest_discover_tests(${name}
        DISCOVERY_MODE PRE_TEST
        DISCOVERY_TIMEOUT 60
        PROPERTIES
            LABELS "${ARG_LABEL}"
            TIMEOUT ${ARG_TIMEOUT}
            SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]"
            ENVIRONMENT "LANTERN_SHARED_DIR=${LANTERN_SHARED_DIR};LANTERN_SOURCE_DIR=${PROJECT_SOURCE_DIR};LANTERN_BINARY_DIR=${PROJECT_BINARY_DIR};LANTERN_CLI=$<TARGET_FILE:lantern_cli>;XDG_RUNTIME_DIR=${PROJECT_BINARY_DIR}/xdg-runtime;LANTERN_CACHE_DIR=${PROJECT_BINARY_DIR}/tests/pipeline-cache")
endfunction()
