# Install rules: headers, the library, the CMake package (Lantern::lantern) and a pkg-config
# file. A consumer writes find_package(Lantern CONFIG REQUIRED) and links Lantern::lantern.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS lantern EXPORT LanternTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Lantern::glfw (the GLFW window convenience) when GLFW was found.
set(LANTERN_HAS_GLFW OFF)
if(TARGET lantern_glfw)
    set(LANTERN_HAS_GLFW ON)
    install(TARGETS lantern_glfw EXPORT LanternTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/lantern
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/engine/include/lantern/Version.h
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lantern)
if(TARGET lantern_cli)
    install(TARGETS lantern_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

set(LANTERN_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Lantern)
install(EXPORT LanternTargets NAMESPACE Lantern:: DESTINATION ${LANTERN_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/LanternConfig.cmake.in
    ${PROJECT_BINARY_DIR}/LanternConfig.cmake INSTALL_DESTINATION ${LANTERN_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/LanternConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/LanternConfig.cmake ${PROJECT_BINARY_DIR}/LanternConfigVersion.cmake
    DESTINATION ${LANTERN_CMAKE_DIR})

# pkg-config: a static libLantern needs its private dependencies on the link line too.
set(LANTERN_PC_LIBS_PRIVATE "-lvulkan -lOpenEXR-3_1 -lImath-3_1 -lIex-3_1 -lIlmThread-3_1 -ltinygltf -lstb -lpthread")
configure_file(${PROJECT_SOURCE_DIR}/cmake/lantern.pc.in ${PROJECT_BINARY_DIR}/lantern.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/lantern.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
