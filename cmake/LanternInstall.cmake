# Install rules: the public headers, the library (static, or shared with -DBUILD_SHARED_LIBS=ON),
# the CMake package and pkg-config files. A consumer writes
#   find_package(Lantern CONFIG REQUIRED)            # COMPONENTS glfw for Lantern::glfw
#   target_link_libraries(app PRIVATE Lantern::lantern)
# Shaders are embedded in the library, so nothing else is installed for run time.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

get_target_property(_lantern_type lantern TYPE)
if(_lantern_type STREQUAL "SHARED_LIBRARY")
    set(LANTERN_SHARED ON)
    set(LANTERN_LIBRARY_KIND "shared")
else()
    set(LANTERN_SHARED OFF)
    set(LANTERN_LIBRARY_KIND "static")
endif()

# Installed programs find a shared libLantern in the prefix wherever the prefix is moved:
# RUNPATH $ORIGIN/../lib for executables, $ORIGIN for libLantern_glfw (RUNPATH is not inherited
# by a library's own dependencies).
file(RELATIVE_PATH _lantern_bin_to_lib "${CMAKE_INSTALL_FULL_BINDIR}" "${CMAKE_INSTALL_FULL_LIBDIR}")
if(LANTERN_SHARED)
    if(TARGET lantern_cli)
        set_target_properties(lantern_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${_lantern_bin_to_lib}")
    endif()
    if(TARGET lantern_glfw)
        set_target_properties(lantern_glfw PROPERTIES INSTALL_RPATH "$ORIGIN")
    endif()
endif()

set(LANTERN_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Lantern)

# (Lantern::lantern's include directory is its INSTALL_INTERFACE, engine/CMakeLists.txt.)
install(TARGETS lantern EXPORT LanternTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT LanternTargets NAMESPACE Lantern:: DESTINATION ${LANTERN_CMAKE_DIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/lantern
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h" PATTERN "glfw" EXCLUDE)
install(FILES ${PROJECT_BINARY_DIR}/engine/include/lantern/Version.h
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lantern)

# Lantern::glfw (the GLFW window convenience), when GLFW was found: the package's `glfw`
# component, in an export set of its own so that only hosts asking for it need GLFW.
set(LANTERN_HAS_GLFW OFF)
if(TARGET lantern_glfw)
    set(LANTERN_HAS_GLFW ON)
    install(TARGETS lantern_glfw EXPORT LanternGlfwTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    install(EXPORT LanternGlfwTargets NAMESPACE Lantern:: DESTINATION ${LANTERN_CMAKE_DIR})
    install(FILES ${PROJECT_SOURCE_DIR}/engine/include/lantern/glfw/GlfwWindow.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lantern/glfw)
endif()
if(TARGET lantern_cli)
    install(TARGETS lantern_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    # The accuracy plot (matplotlib), run by `lantern bench accuracy`.
    install(PROGRAMS ${PROJECT_SOURCE_DIR}/benchmarks/plot_accuracy.py
        DESTINATION ${CMAKE_INSTALL_DATADIR}/lantern)
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/LanternConfig.cmake.in
    ${PROJECT_BINARY_DIR}/LanternConfig.cmake INSTALL_DESTINATION ${LANTERN_CMAKE_DIR})
# Before 1.0 a minor version may break the API, as the shared library's SONAME (0.MINOR) says.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/LanternConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/LanternConfig.cmake ${PROJECT_BINARY_DIR}/LanternConfigVersion.cmake
    DESTINATION ${LANTERN_CMAKE_DIR})

# pkg-config. The files locate the prefix from their own folder (${pcfiledir}), so they stay
# right under `cmake --install --prefix` and DESTDIR. A static libLantern needs its
# dependencies on every link line, so they are in Requires/Libs (a plain
# `pkg-config --cflags --libs lantern` links); a shared one names them itself (NEEDED).
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
    set(LANTERN_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
    file(RELATIVE_PATH LANTERN_PC_PREFIX "/x/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/x")
    string(REGEX REPLACE "/$" "" LANTERN_PC_PREFIX "${LANTERN_PC_PREFIX}")
    set(LANTERN_PC_PREFIX "\${pcfiledir}/${LANTERN_PC_PREFIX}")
endif()
if(LANTERN_SHARED)
    set(LANTERN_PC_REQUIRES "glm vulkan")
    set(LANTERN_PC_LIBS "")
    set(LANTERN_PC_GLFW_REQUIRES "lantern")
else()
    # meshoptimizer installs no pkg-config file: its library goes on the Libs line.
    set(LANTERN_PC_REQUIRES "glm vulkan OpenEXR tinygltf stb libpng libwebp draco tinyobjloader")
    set(LANTERN_PC_LIBS " -lmeshoptimizer -pthread")
    set(LANTERN_PC_GLFW_REQUIRES "lantern glfw3")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/lantern.pc.in ${PROJECT_BINARY_DIR}/lantern.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/lantern.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
if(LANTERN_HAS_GLFW)
    configure_file(${PROJECT_SOURCE_DIR}/cmake/lantern-glfw.pc.in ${PROJECT_BINARY_DIR}/lantern-glfw.pc @ONLY)
    install(FILES ${PROJECT_BINARY_DIR}/lantern-glfw.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endif()
