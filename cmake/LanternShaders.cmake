# Build-time shader compilation: glslangValidator turns each GLSL entry point into SPIR-V words
# in a generated header (--vn), and lantern_shader_registry() writes one C++ file that embeds
# them all behind an enum, so nothing is looked up on disk at run time.
find_program(LANTERN_GLSLANG_VALIDATOR glslangValidator REQUIRED)

# lantern_add_shader(<id> SOURCE <file> [DEFINES A=1 B ...] [TARGET_ENV vulkan1.2])
# TARGET_ENV (default vulkan1.3): compute shaders use vulkan1.2, whose SPIR-V states the
# workgroup size as LocalSize (vulkan1.3's LocalSizeId needs the maintenance4 feature, which a
# host's device need not enable).
# Appends the compiled header to the LANTERN_SHADER_HEADERS / LANTERN_SHADER_IDS globals.
function(lantern_add_shader id)
    cmake_parse_arguments(ARG "" "SOURCE;TARGET_ENV" "DEFINES" ${ARGN})
    if(NOT ARG_TARGET_ENV)
        set(ARG_TARGET_ENV vulkan1.3)
    endif()
    cmake_path(ABSOLUTE_PATH ARG_SOURCE BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" OUTPUT_VARIABLE src)
    set(out "${CMAKE_CURRENT_BINARY_DIR}/spv/${id}.h")
    set(defs "")
    foreach(d IN LISTS ARG_DEFINES)
        list(APPEND defs "-D${d}")
    endforeach()
    set(dbg "")
    if(LANTERN_SHADER_DEBUG_INFO)
        set(dbg "-g")
    endif()
    # The folder exists before any generator runs the command (Ninja creates output folders
    # itself, Unix Makefiles does not). glslangValidator exits 0 when it cannot write its
    # output: the old header is removed first (a stale one must not be embedded) and its
    # absence afterwards fails the build with a message naming the shader.
    file(MAKE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/spv")
    add_custom_command(
        OUTPUT "${out}"
        COMMAND "${CMAKE_COMMAND}" -E rm -f "${out}"
        COMMAND "${LANTERN_GLSLANG_VALIDATOR}" -V --target-env ${ARG_TARGET_ENV} --quiet ${dbg}
                -I${CMAKE_CURRENT_SOURCE_DIR}/include ${defs}
                --depfile "${out}.d" --vn lantern_spv_${id} -o "${out}" "${src}"
        COMMAND "${CMAKE_COMMAND}" "-DOUTPUT=${out}" "-DSOURCE=${src}"
                -P "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/CheckShaderOutput.cmake"
        DEPENDS "${src}"
        DEPFILE "${out}.d"
        COMMENT "glslang: ${ARG_SOURCE} -> ${id}"
        VERBATIM)
    set_property(GLOBAL APPEND PROPERTY LANTERN_SHADER_HEADERS "${out}")
    set_property(GLOBAL APPEND PROPERTY LANTERN_SHADER_IDS "${id}")
endfunction()

# lantern_shader_registry(<target>): an OBJECT library embedding every shader added so far.
function(lantern_shader_registry target)
    get_property(headers GLOBAL PROPERTY LANTERN_SHADER_HEADERS)
    get_property(ids GLOBAL PROPERTY LANTERN_SHADER_IDS)
    set(gen "${CMAKE_CURRENT_BINARY_DIR}/gen")
    set(enum_entries "")
    set(includes "")
    set(table "")
    foreach(id IN LISTS ids)
        string(APPEND enum_entries "    ${id},\n")
        string(APPEND includes "#include \"spv/${id}.h\"\n")
        string(APPEND table "    {\"${id}\", lantern_spv_${id}, sizeof(lantern_spv_${id}) / 4},\n")
    endforeach()
    list(LENGTH ids count)
    configure_file("${CMAKE_CURRENT_FUNCTION_LIST_DIR}/ShaderBlobs.h.in" "${gen}/ShaderBlobs.h" @ONLY)
    configure_file("${CMAKE_CURRENT_FUNCTION_LIST_DIR}/ShaderBlobs.cpp.in" "${gen}/ShaderBlobs.cpp" @ONLY)
    add_library(${target} OBJECT "${gen}/ShaderBlobs.cpp" ${headers})
    target_include_directories(${target} PUBLIC "${gen}" PRIVATE "${CMAKE_CURRENT_BINARY_DIR}")
    target_compile_features(${target} PUBLIC cxx_std_20)
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON
        CXX_VISIBILITY_PRESET hidden)
endfunction()
