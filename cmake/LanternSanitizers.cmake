# lantern_sanitizers: an INTERFACE target applying LANTERN_SANITIZE (e.g. "address;undefined")
# to every Lantern target that links it.
add_library(lantern_sanitizers INTERFACE)
if(LANTERN_SANITIZE)
    list(JOIN LANTERN_SANITIZE "," _lantern_san)
    target_compile_options(lantern_sanitizers INTERFACE
        -fsanitize=${_lantern_san} -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
    target_link_options(lantern_sanitizers INTERFACE -fsanitize=${_lantern_san})
endif()
