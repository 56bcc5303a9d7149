// buildInfo(): the facts a bug report needs: version, commit, build type, compiler, library kind
// (compiled in; the commit and build type arrive as this file's own definitions, so a new
// commit recompiles only it) and the Vulkan loader found at run time.
#include <lantern/Renderer.h>
#include <lantern/Version.h>

#ifndef LANTERN_GIT_COMMIT
#define LANTERN_GIT_COMMIT "unknown"
#endif
#ifndef LANTERN_BUILD_TYPE
#define LANTERN_BUILD_TYPE "unknown"
#endif
#ifndef LANTERN_LIBRARY_KIND
#define LANTERN_LIBRARY_KIND "unknown"
#endif

namespace lantern {
namespace {

std::string compilerName() {
#if defined(__clang__)
    return "clang " __clang_version__;
#elif defined(__GNUC__)
    return "GCC " + std::to_string(__GNUC__) + "." + std::to_string(__GNUC_MINOR__) + "." +
           std::to_string(__GNUC_PATCHLEVEL__);
#elif defined(_MSC_VER)
    return "MSVC " + std::to_string(_MSC_VER);
#else
    return "unknown";
#endif
}

} // namespace

BuildInfo buildInfo() {
    BuildInfo info;
    info.version = versionString();
    info.commit = LANTERN_GIT_COMMIT;
    info.buildType = LANTERN_BUILD_TYPE;
    info.compiler = compilerName();
    info.library = LANTERN_LIBRARY_KIND;
    info.vulkanLoader = vulkanLoaderVersion();
    if (info.vulkanLoader.empty()) info.vulkanLoader = "none";
    return info;
}

} // namespace lantern
