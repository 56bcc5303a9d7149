# Builds tests/cmake/shader_project with the Unix Makefiles generator (the default one, which
# does not create output folders itself) from clean folders, and checks that
#   1. a valid shader builds,
#   2. a shader that does not compile fails the build,
#   3. a shader whose SPIR-V header is not written fails the build at that shader, with a
#      message naming it: glslangValidator exits 0 when it cannot write its output, which a
#      stand-in that writes nothing and exits 0 reproduces (root can write anywhere, so the
#      real condition cannot be staged here).
# Run with: cmake -DLANTERN_SOURCE_DIR=... -DWORK_DIR=... -P ShaderBuildTest.cmake
set(project "${LANTERN_SOURCE_DIR}/tests/cmake/shader_project")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(WRITE "${WORK_DIR}/good.frag" "#version 460\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec4(1.0); }\n")
file(WRITE "${WORK_DIR}/silent-validator.sh" "#!/bin/sh\nexit 0\n")
file(CHMOD "${WORK_DIR}/silent-validator.sh" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
file(WRITE "${WORK_DIR}/bad.frag" "#version 460\nlayout(location = 0) out vec4 c;\nvoid main() { c = vec3(1.0); }\n")

# configure_and_build(<name> <shader> <result-var> [pre-build step])
function(configure_and_build name shader result)
    set(bin "${WORK_DIR}/${name}")
    set(extra)
    if(ARGN STREQUAL "silent-validator")
        set(extra "-DLANTERN_GLSLANG_VALIDATOR=${WORK_DIR}/silent-validator.sh")
    endif()
    execute_process(COMMAND "${CMAKE_COMMAND}" -G "Unix Makefiles" -S "${project}" -B "${bin}"
                            "-DLANTERN_SOURCE_DIR=${LANTERN_SOURCE_DIR}" "-DSHADER=${shader}" ${extra}
                    RESULT_VARIABLE configured OUTPUT_VARIABLE out ERROR_VARIABLE out)
    if(NOT configured EQUAL 0)
        message(FATAL_ERROR "${name}: configure failed:\n${out}")
    endif()
    execute_process(COMMAND "${CMAKE_COMMAND}" --build "${bin}"
                    RESULT_VARIABLE built OUTPUT_VARIABLE out ERROR_VARIABLE out)
    set(${result} "${built}" PARENT_SCOPE)
    set(${result}_OUTPUT "${out}" PARENT_SCOPE)
endfunction()

configure_and_build(good "${WORK_DIR}/good.frag" good)
if(NOT good EQUAL 0)
    message(FATAL_ERROR "a valid shader failed to build with Unix Makefiles:\n${good_OUTPUT}")
endif()
if(NOT EXISTS "${WORK_DIR}/good/spv/probe_frag.h")
    message(FATAL_ERROR "the build succeeded but wrote no SPIR-V header")
endif()
configure_and_build(bad "${WORK_DIR}/bad.frag" bad)
if(bad EQUAL 0)
    message(FATAL_ERROR "a shader that does not compile did not fail the build:\n${bad_OUTPUT}")
endif()
configure_and_build(unwritten "${WORK_DIR}/good.frag" unwritten silent-validator)
if(unwritten EQUAL 0 OR NOT unwritten_OUTPUT MATCHES "wrote no SPIR-V for[ \n]+[^ ]*good.frag")
    message(FATAL_ERROR "a SPIR-V header that was not written did not fail the build:\n${unwritten_OUTPUT}")
endif()
message(STATUS "valid shader built; a compile error and an unwritten header both failed the build")
