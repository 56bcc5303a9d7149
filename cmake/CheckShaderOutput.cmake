# Fails (with a message naming the file) when glslangValidator wrote no SPIR-V header: it
# exits 0 when it cannot write its output. Run by the shader rule of LanternShaders.cmake:
#   cmake -DOUTPUT=<header> -DSOURCE=<shader> -P CheckShaderOutput.cmake
if(NOT EXISTS "${OUTPUT}" OR IS_DIRECTORY "${OUTPUT}")
    message(FATAL_ERROR "glslangValidator wrote no SPIR-V for ${SOURCE}: ${OUTPUT} is missing")
endif()
