// The installed package, as a host uses it: `cmake --install` of this build into a
// temporary prefix (then moved elsewhere), and, against that prefix only, the two example
// projects configured with find_package, built and run (the headless one writes an EXR that
// is read back; the GLFW one presents frames in a window under Xvfb), a program compiled and
// linked with nothing but `pkg-config --cflags --libs lantern`, and the Python module imported
// from the prefix's Python path.
#include "InstallSupport.h"

#if LANTERN_INSTALL_HAS_GLFW
#include "XServer.h"
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

using namespace lantern;
using namespace lantern::test;

// What the headless example wrote must be its picture: the size it renders, the depth plane
// it asks for, a ball and a floor over a transparent background, nothing non-finite.
void expectHeadlessPicture(const fs::path& exr) {
    ASSERT_TRUE(fs::exists(exr)) << exr << " was not written";
    auto image = readExr(exr);
    ASSERT_TRUE(image) << image.error().describe();
    EXPECT_EQ(image->width, 160);
    EXPECT_EQ(image->height, 120);
    EXPECT_EQ(image->depth.size(), image->pixelCount()) << "the Z plane is missing";
    EXPECT_EQ(countNonFinite(*image), 0u);
    const std::size_t covered = countCovered(*image);
    EXPECT_GT(covered, image->pixelCount() / 5) << "the floor and the ball cover too little";
    EXPECT_LT(covered, image->pixelCount()) << "no background left: not the example's picture";
    float reddest = 0.0f;  // the ball is red plastic
    for (std::size_t i = 0; i < image->pixelCount(); ++i)
        reddest = std::max(reddest, image->rgba[i * 4] - image->rgba[i * 4 + 2]);
    EXPECT_GT(reddest, 0.2f) << "no red ball in the picture";
}

class Installed : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_FALSE(m_root.path().empty()) << "cannot create a temporary folder";
        std::string failure;
        m_prefix = installBuild(binaryDir(), m_root.path(), failure);
        ASSERT_TRUE(failure.empty()) << failure;
        const fs::path lib = LANTERN_INSTALL_LIBDIR;
        for (const fs::path& f :
             {fs::path("include/lantern/Lantern.h"), fs::path("include/lantern/Version.h"),
              fs::path("include/lantern/ExternalDevice.h"), lib / "liblantern.a",
              lib / "cmake/Lantern/LanternConfig.cmake", lib / "pkgconfig/lantern.pc"})
            EXPECT_TRUE(fs::exists(m_prefix / f)) << f << " is not installed";
        EXPECT_FALSE(fs::exists(m_prefix / "include/lantern/Version.h.in"));
    }
    TempDir m_root;
    fs::path m_prefix;
};

TEST_F(Installed, HeadlessExampleBuildsAndRendersAgainstThePrefix) {
    const fs::path build = m_root.path() / "headless-build";
    const auto failure = buildExample("headless", m_prefix, build);
    ASSERT_TRUE(failure.empty()) << failure;
    // Built and checked; running it renders, which needs a device.
    LANTERN_SKIP_IF_MISSING(missingVulkanDevice());
    const fs::path exr = m_root.path() / "headless.exr";
    ProcessResult run;
    const auto ran = runStep({(build / "lantern-headless-example").string(), exr.string()}, {},
                             300.0, &run);
    ASSERT_TRUE(ran.empty()) << ran;
    EXPECT_NE(run.out.find("wrote " + exr.string()), std::string::npos) << run.out;
    expectHeadlessPicture(exr);
}

TEST_F(Installed, GlfwExampleShowsFramesInAWindow) {
#if !LANTERN_INSTALL_HAS_GLFW
    GTEST_SKIP() << "this build has no Lantern::glfw (GLFW was not found at configure time)";
#else
    ASSERT_TRUE(fs::exists(m_prefix / LANTERN_INSTALL_LIBDIR / "cmake/Lantern/LanternGlfwTargets.cmake"));
    const fs::path build = m_root.path() / "glfw-build";
    const auto failure = buildExample("glfw_window", m_prefix, build);
    ASSERT_TRUE(failure.empty()) << failure;
    // Built and checked; running it renders, which needs a device.
    LANTERN_SKIP_IF_MISSING(missingVulkanDevice());
    if (const std::string missing = XServer::missing(); !missing.empty())
        GTEST_SKIP() << missing << " (the example was built but not run)";
    std::string error;
    auto server = XServer::start(m_root.path(), error, "640x480x24");
    if (!server)
        GTEST_SKIP() << "no X display could be started here: " << error
                     << " (the example was built but not run)";
    ProcessResult run;
    const auto ran = runStep({(build / "lantern-glfw-example").string(), "--frames", "5",
                              "--size", "160x120"},
                             server->environment(), 300.0, &run);
    ASSERT_TRUE(ran.empty()) << ran;
    EXPECT_NE(run.out.find("presented 5 frames"), std::string::npos) << run.out;
#endif
}

// The man pages and the completions land where man and the shells look for them, and
// `man lantern` finds the page through the prefix's MANPATH.
TEST_F(Installed, ManPagesAndCompletionsAreWhereManAndTheShellsLook) {
    for (const char* f : {"share/man/man1/lantern.1.gz", "share/man/man1/lantern-render.1.gz",
                          "share/man/man1/lantern-bench-accuracy.1.gz",
                          "share/bash-completion/completions/lantern",
                          "share/zsh/vendor-completions/_lantern",
                          "share/fish/vendor_completions.d/lantern.fish"})
        EXPECT_TRUE(fs::exists(m_prefix / f)) << f << " is not installed";
    if (runProcess({"sh", "-c", "command -v man"}).exitCode != 0) {
        std::cout << "man is not installed: the page was not opened\n";
        return;
    }
    const auto man = runProcess({"man", "-P", "cat", "lantern-render"},
                                {"MANPATH=" + (m_prefix / "share/man").string(), "MANWIDTH=80"});
    EXPECT_EQ(man.exitCode, 0) << man.err;
    EXPECT_NE(man.out.find("--shading"), std::string::npos) << man.out.substr(0, 400);
}

// The thumbnailer entry as a file manager uses it: its Exec line, with %s, %i and %o replaced,
// run with the prefix's bin on PATH, writes the PNG.
TEST_F(Installed, TheThumbnailerEntryRunsAsAFileManagerRunsIt) {
    const fs::path entry = m_prefix / "share/thumbnailers/lantern.thumbnailer";
    ASSERT_TRUE(fs::exists(entry)) << entry;
    std::ifstream in(entry);
    std::string line, exec, mime;
    while (std::getline(in, line)) {
        if (line.rfind("Exec=", 0) == 0) exec = line.substr(5);
        if (line.rfind("MimeType=", 0) == 0) mime = line.substr(9);
    }
    EXPECT_NE(mime.find("model/gltf-binary;"), std::string::npos) << mime;
    EXPECT_NE(mime.find("model/gltf+json;"), std::string::npos) << mime;
    ASSERT_FALSE(exec.empty()) << "no Exec line";
    LANTERN_SKIP_IF_MISSING(missingVulkanDevice());
    const fs::path input = sharedDir() / "assets/gltf-samples/Box/glTF-Binary/Box.glb";
    const fs::path output = m_root.path() / "thumb.png";
    std::vector<std::string> args;
    std::istringstream words(exec);
    for (std::string w; words >> w;)
        args.push_back(w == "%s" ? "64" : w == "%i" ? input.string() : w == "%o" ? output.string() : w);
    ASSERT_EQ(args.front(), "lantern");
    args.front() = (m_prefix / "bin" / "lantern").string();
    const auto run = runProcess(args);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_TRUE(fs::exists(output)) << "the thumbnail was not written";
}

TEST_F(Installed, PkgConfigAloneCompilesAndLinksAHost) {
    const std::vector<std::string> env = {"PKG_CONFIG_PATH=" + (m_prefix / LANTERN_INSTALL_LIBDIR / "pkgconfig").string()};
    ProcessResult flags;
    auto failure = runStep({"pkg-config", "--cflags", "--libs", "lantern"}, env, 60.0, &flags);
    ASSERT_TRUE(failure.empty()) << failure;
    EXPECT_NE(flags.out.find(m_prefix.string()), std::string::npos)
        << "the flags do not point into the prefix: " << flags.out;
#if LANTERN_INSTALL_HAS_GLFW
    failure = runStep({"pkg-config", "--cflags", "--libs", "lantern-glfw"}, env, 60.0);
    EXPECT_TRUE(failure.empty()) << failure;
#endif

    // The headless example's source, compiled and linked with those flags only.
    const fs::path exe = m_root.path() / "headless-pkg-config";
    std::vector<std::string> compile = {cxxCompiler(),
                                        (sourceDir() / "apps/examples/headless/main.cpp").string(),
                                        "-o", exe.string()};
    const auto tool = toolchainFlags();
    compile.insert(compile.end(), tool.begin(), tool.end());
    std::istringstream words(flags.out);
    for (std::string w; words >> w;) compile.push_back(w);
    failure = runStep(compile, {}, 600.0);
    ASSERT_TRUE(failure.empty()) << failure;
    // Built and checked; running it renders, which needs a device.
    LANTERN_SKIP_IF_MISSING(missingVulkanDevice());
    const fs::path exr = m_root.path() / "pkg-config.exr";
    failure = runStep({exe.string(), exr.string()}, {}, 300.0);
    ASSERT_TRUE(failure.empty()) << failure;
    expectHeadlessPicture(exr);
}

TEST_F(Installed, PythonModuleImportsAndRendersFromThePrefix) {
#if !LANTERN_INSTALL_HAS_PYTHON
    GTEST_SKIP() << "this build has no Python module (LANTERN_BUILD_PYTHON is OFF: python3-dev or "
                    "pybind11-dev missing, or a sanitizer build)";
#else
    const fs::path packages = m_prefix / LANTERN_INSTALL_PYTHONDIR;
    for (const char* f : {"__init__.py", "_picture.py", "_pool.py", "__init__.pyi", "py.typed"})
        EXPECT_TRUE(fs::exists(packages / "lantern" / f)) << f << " is not installed in " << packages;
    const char* script = R"(
import lantern, sys
print(lantern.__file__)
print(lantern.build_info()["version"])
try:
    renderer = lantern.Renderer()
except lantern.Error as e:
    print("no device:", e)
    sys.exit(0)
rgba = renderer.render(lantern.load("builtin:teapot"), width=32, height=24)
print(rgba.shape, rgba.dtype, type(rgba).__name__, rgba._repr_png_()[:4])
)";
    ProcessResult run;
    const auto ran = runStep({LANTERN_INSTALL_PYTHON, "-c", script},
                             {"PYTHONPATH=" + packages.string(), "PYTHONDONTWRITEBYTECODE=1"},
                             300.0, &run);
    ASSERT_TRUE(ran.empty()) << ran;
    EXPECT_EQ(run.out.rfind((packages / "lantern" / "__init__.py").string() + "\n", 0), 0u)
        << "not the installed module: " << run.out;
    EXPECT_NE(run.out.find(std::string("\n") + versionString() + "\n"), std::string::npos)
        << run.out;
    if (run.out.find("no device:") == std::string::npos) {
        EXPECT_NE(run.out.find("(24, 32, 4) float32 Picture b'\\x89PNG'"), std::string::npos) << run.out;
    }
#endif
}

} // namespace
