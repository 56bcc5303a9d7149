# Every LANTERN_* option in one place. Apps, tests and install default to on only when Lantern
# is the top-level project, so embedding it with add_subdirectory builds just the library.
option(LANTERN_BUILD_APPS "Build the lantern command" ${PROJECT_IS_TOP_LEVEL})
# The test suite looks inside the engine, which a shared libLantern hides (it exports only the
# public API), so tests build against the static library; a shared build installs and is
# checked by the install test (tests/install).
if(BUILD_SHARED_LIBS)
    set(_lantern_tests_default OFF)
else()
    set(_lantern_tests_default ${PROJECT_IS_TOP_LEVEL})
endif()
option(LANTERN_BUILD_TESTS "Build the test suite (static library only)" ${_lantern_tests_default})
if(LANTERN_BUILD_TESTS AND BUILD_SHARED_LIBS)
    message(FATAL_ERROR "LANTERN_BUILD_TESTS needs a static libLantern (the tests look inside "
                        "the engine); configure a shared build with -DLANTERN_BUILD_TESTS=OFF")
endif()
option(LANTERN_INSTALL "Generate install rules and the CMake package" ${PROJECT_IS_TOP_LEVEL})
option(LANTERN_WERROR "Treat compiler warnings as errors (CI turns this on)" OFF)
option(LANTERN_SHADER_DEBUG_INFO "Compile shaders with debug info (-g)" OFF)
option(LANTERN_FUZZ "Build libFuzzer targets (needs clang)" OFF)
option(LANTERN_TESTING_HOOKS "Compile fault-injection hooks into the engine (tests only)" ${LANTERN_BUILD_TESTS})
set(LANTERN_SANITIZE "" CACHE STRING "Sanitizers to build with, e.g. address;undefined")
# The Python module (apps/python): on when the apps are built and Python's headers (Debian:
# python3-dev) and pybind11 (pybind11-dev) are found. Off in sanitizer builds: an instrumented
# extension cannot be loaded by an uninstrumented interpreter.
set(_lantern_python_default OFF)
if(LANTERN_BUILD_APPS)
    set(PYBIND11_FINDPYTHON ON)
    # Debian's interpreter, whose python3-numpy, python3-pytest and python3-matplotlib the
    # module and its tests use, rather than whichever python3 comes first on PATH (pyenv's
    # shims, a virtualenv). -DPython_EXECUTABLE=... chooses another.
    if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
        set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python the module is built for")
    endif()
    find_package(Python 3.7 COMPONENTS Interpreter Development.Module QUIET)
    if(Python_FOUND)
        find_package(pybind11 2.6 CONFIG QUIET)
    endif()
    if(Python_FOUND AND pybind11_FOUND AND NOT LANTERN_SANITIZE)
        set(_lantern_python_default ON)
    endif()
endif()
option(LANTERN_BUILD_PYTHON "Build the Python module (needs python3-dev and pybind11-dev)"
    ${_lantern_python_default})
if(LANTERN_BUILD_PYTHON AND NOT (Python_FOUND AND pybind11_FOUND))
    message(FATAL_ERROR "LANTERN_BUILD_PYTHON needs Python's headers and pybind11 (Debian: "
                        "python3-dev pybind11-dev), which were not found")
endif()
