// A shared libLantern (BUILD_SHARED_LIBS=ON), as a host gets it: the library and
// libLantern_glfw built from this checkout in a build tree of their own (a stable path under
// this build, so ccache makes repeated runs cheap), installed into a temporary prefix, and
// the headless example built against it: the example needs libLantern's SONAME and none of
// Lantern's private dependencies, runs, and writes its picture; the libraries export the
// lantern namespace and nothing else.
#include "InstallSupport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

using namespace lantern;
using namespace lantern::test;

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream s(text);
    for (std::string l; std::getline(s, l);) out.push_back(l);
    return out;
}

// The NEEDED entries of an ELF file (readelf -d).
std::vector<std::string> needed(const fs::path& elf, std::string& failure) {
    ProcessResult r;
    failure = runStep({"readelf", "-d", elf.string()}, {}, 60.0, &r);
    std::vector<std::string> out;
    for (const std::string& l : lines(r.out)) {
        const auto open = l.find("(NEEDED)");
        const auto lb = l.find('['), rb = l.find(']');
        if (open != std::string::npos && lb != std::string::npos && rb > lb)
            out.push_back(l.substr(lb + 1, rb - lb - 1));
    }
    return out;
}

bool anyStartsWith(const std::vector<std::string>& names, const std::string& prefix) {
    for (const std::string& n : names)
        if (n.rfind(prefix, 0) == 0) return true;
    return false;
}

class Seconds {
public:
    double elapsed() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    }

private:
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

TEST(SharedLibrary, HeadlessExampleLinksTheSharedLibraryWhichExportsOnlyTheApi) {
    TempDir root;
    ASSERT_FALSE(root.path().empty());
    const fs::path build = binaryDir() / "tests" / "install" / "shared-build";
    std::vector<std::string> configure = {LANTERN_INSTALL_CMAKE,
                                          "-S",
                                          sourceDir().string(),
                                          "-B",
                                          build.string(),
                                          "-DCMAKE_BUILD_TYPE=Release",
                                          "-DBUILD_SHARED_LIBS=ON",
                                          "-DLANTERN_BUILD_TESTS=OFF",
                                          "-DLANTERN_BUILD_APPS=OFF"};
    const auto tool = toolchainArgs();
    configure.insert(configure.end(), tool.begin(), tool.end());
    Seconds clock;
    auto failure = runStep(configure);
    ASSERT_TRUE(failure.empty()) << failure;
    std::vector<std::string> targets = {LANTERN_INSTALL_CMAKE, "--build", build.string(),
                                        "--target", "lantern"};
#if LANTERN_INSTALL_HAS_GLFW
    targets.push_back("lantern_glfw");
#endif
    failure = runStep(targets, {}, 1800.0);
    ASSERT_TRUE(failure.empty()) << failure;
    std::cout << "shared libLantern configured and built in " << clock.elapsed() << " s\n";

    const fs::path prefix = installBuild(build, root.path(), failure);
    ASSERT_TRUE(failure.empty()) << failure;
    const fs::path lib = prefix / LANTERN_INSTALL_LIBDIR;
    EXPECT_TRUE(fs::exists(lib / "liblantern.so.0.1")) << "no versioned shared library";
    EXPECT_FALSE(fs::exists(lib / "liblantern.a"));

    // The libraries export namespace lantern (functions, and the type information, vtables
    // and guard variables of its types) and nothing else.
    std::vector<fs::path> libraries = {lib / "liblantern.so"};
#if LANTERN_INSTALL_HAS_GLFW
    libraries.push_back(lib / "liblantern_glfw.so");
#endif
    for (const fs::path& so : libraries) {
        SCOPED_TRACE(so.filename().string());
        ProcessResult symbols;
        failure = runStep({"nm", "-D", "--defined-only", "-C", so.string()}, {}, 60.0, &symbols);
        ASSERT_TRUE(failure.empty()) << failure;
        std::size_t exported = 0;
        for (const std::string& l : lines(symbols.out)) {
            // "ADDRESS TYPE NAME"
            std::istringstream words(l);
            std::string address, type, name;
            words >> address >> type;
            std::getline(words >> std::ws, name);
            if (name.empty()) continue;
            ++exported;
            bool ours = false;
            for (const char* p : {"lantern::", "typeinfo for lantern::", "typeinfo name for lantern::",
                                  "vtable for lantern::", "VTT for lantern::",
                                  "guard variable for lantern::", "non-virtual thunk to lantern::",
                                  "virtual thunk to lantern::"})
                ours |= name.rfind(p, 0) == 0;
            EXPECT_TRUE(ours) << "exports " << name;
        }
        // (libLantern_glfw's API is one class and one function.)
        EXPECT_GT(exported, so.filename() == "liblantern.so" ? 50u : 5u)
            << "the public API is not exported";
    }

    // The host: built against the prefix, it needs libLantern and none of its private
    // dependencies (OpenEXR, tinygltf, stb live inside libLantern's own NEEDED list).
    const fs::path exampleBuild = root.path() / "headless-build";
    failure = buildExample("headless", prefix, exampleBuild);
    ASSERT_TRUE(failure.empty()) << failure;
    const fs::path exe = exampleBuild / "lantern-headless-example";
    const auto deps = needed(exe, failure);
    ASSERT_TRUE(failure.empty()) << failure;
    EXPECT_TRUE(anyStartsWith(deps, "liblantern.so.0.1")) << "the example does not need libLantern";
    for (const char* privateDep : {"libOpenEXR", "libtinygltf", "libstb", "libIex"})
        EXPECT_FALSE(anyStartsWith(deps, privateDep)) << "the example needs " << privateDep;
    ProcessResult ldd;
    failure = runStep({"ldd", exe.string()}, {}, 60.0, &ldd);
    ASSERT_TRUE(failure.empty()) << failure;
    EXPECT_NE(ldd.out.find((lib / "liblantern.so.0.1").string()), std::string::npos)
        << "the example does not load the prefix's libLantern:\n" << ldd.out;

    // Built and checked; running it renders, which needs a device.
    LANTERN_SKIP_IF_MISSING(missingVulkanDevice());
    const fs::path exr = root.path() / "headless.exr";
    failure = runStep({exe.string(), exr.string()}, {}, 300.0);
    ASSERT_TRUE(failure.empty()) << failure;
    auto image = readExr(exr);
    ASSERT_TRUE(image) << image.error().describe();
    EXPECT_EQ(image->width, 160);
    EXPECT_GT(countCovered(*image), image->pixelCount() / 5);
    std::cout << "shared variant, everything: " << clock.elapsed() << " s\n";
}

} // namespace
