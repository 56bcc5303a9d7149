# lantern_sanitizers: an INTERFACE target applying LANTERN_SANITIZE (e.g. "address;undefined")
# to every Lantern target that links it.
add_library(lantern_sanitizers INTERFACE)
if(LANTERN_SANITIZE)
    list(JOIN LANTERN_SANITIZE "," _lantern_san)
    target_compile_options(lantern_sanitizers INTERFACE
        -fsanitize=${_lantern_san} -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
    target_link_options(lantern_sanitizers INTERFACE -fsanitize=${_lantern_san})
    # GCC announces AddressSanitizer with __SANITIZE_ADDRESS__, clang 14 only through
    # __has_feature: one macro of our own for every target that links this one.
    if("address" IN_LIST LANTERN_SANITIZE)
        target_compile_definitions(lantern_sanitizers INTERFACE LANTERN_ASAN=1)
    endif()
    if("thread" IN_LIST LANTERN_SANITIZE)
        target_compile_definitions(lantern_sanitizers INTERFACE LANTERN_TSAN=1)
    endif()
endif()
