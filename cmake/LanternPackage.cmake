# The Debian package (CPack's DEB generator): `scripts/package.sh` configures a Release build with
# the shared library and the prefix /usr, builds it and runs `cpack -G DEB`, which packs what
# `cmake --install` installs: the lantern command, libLantern and its headers, the CMake
# package and pkg-config files, the Python module, the man pages, the shell completions and
# the thumbnailer entry. Dependencies: the shared libraries the binaries link
# (CPACK_DEBIAN_PACKAGE_SHLIBDEPS, dpkg-shlibdeps), a Vulkan driver, NumPy for the Python
# module, and the development packages the installed CMake package and lantern.pc name
# (a host that builds against Lantern needs their headers). docs/packaging.md explains the
# choices and lintian's remaining tags.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lantern)
set(CPACK_PACKAGE_VENDOR "The Lantern developers")
set(CPACK_PACKAGE_CONTACT "The Lantern developers <lantern-devel@lists.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Vulkan renderer for the classic camera, light and material model")
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "Lantern renders glTF, OBJ, PLY, STL and OFF scenes with OpenGL's classic model\n(flat, Gouraud and Phong shading, Blinn-Phong, point, directional and spot\nlights) on Vulkan, on a GPU or on Mesa's CPU driver lavapipe. This package\nholds the lantern command (headless EXR and PNG rendering, a viewer, a\nthumbnailer, benchmarks), the libLantern library with its headers, CMake\npackage and pkg-config files, and the Python module.")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # lantern_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "mesa-vulkan-drivers | vulkan-icd, python3, python3-numpy, libvulkan-dev, libglm-dev")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libglfw3-dev")
set(CPACK_STRIP_FILES ON)
# The shared libraries: a shlibs file, and dpkg's ldconfig trigger (packaging/triggers); CPack
# also calls ldconfig from postinst and postrm, which the trigger makes redundant.
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/triggers
    ${PROJECT_SOURCE_DIR}/packaging/prerm)  # prerm: the module's __pycache__
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# /usr/share/doc/lantern: the copyright file and the changelog (gzipped, as Debian wants).
# (Compressed at configure time: an install of the library alone builds no custom target.)
set(_lantern_changelog ${PROJECT_BINARY_DIR}/packaging/changelog.gz)
file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/packaging)
execute_process(COMMAND gzip -9nc ${PROJECT_SOURCE_DIR}/packaging/changelog
    OUTPUT_FILE ${_lantern_changelog} COMMAND_ERROR_IS_FATAL ANY)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/packaging/changelog)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright ${_lantern_changelog}
    DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/lantern)
include(CPack)
