# Every LANTERN_* option in one place. Apps, tests and install default to on only when Lantern
# is the top-level project, so embedding it with add_subdirectory builds just the library.
option(LANTERN_BUILD_APPS "Build the lantern command" ${PROJECT_IS_TOP_LEVEL})
option(LANTERN_BUILD_TESTS "Build the test suite" ${PROJECT_IS_TOP_LEVEL})
option(LANTERN_INSTALL "Generate install rules and the CMake package" ${PROJECT_IS_TOP_LEVEL})
option(LANTERN_WERROR "Treat compiler warnings as errors (CI turns this on)" OFF)
option(LANTERN_SHADER_DEBUG_INFO "Compile shaders with debug info (-g)" OFF)
option(LANTERN_FUZZ "Build libFuzzer targets (needs clang)" OFF)
option(LANTERN_TESTING_HOOKS "Compile fault-injection hooks into the engine (tests only)" ${PROJECT_IS_TOP_LEVEL})
set(LANTERN_SANITIZE "" CACHE STRING "Sanitizers to build with, e.g. address;undefined")
