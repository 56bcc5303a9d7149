# lantern_warnings: an INTERFACE target carrying the warning flags; linked privately by every
# Lantern target, never exported to consumers.
add_library(lantern_warnings INTERFACE)
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(lantern_warnings INTERFACE
        -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
        -Woverloaded-virtual -Wimplicit-fallthrough
        # `VkFooInfo info{VK_STRUCTURE_TYPE_FOO}` zero-fills the other members on purpose.
        -Wno-missing-field-initializers
        $<$<BOOL:${LANTERN_WERROR}>:-Werror>)
endif()
