// The `lantern` command's failure paths: exit codes (1 refused, 2 usage, 3 renderer failed),
// clear messages naming what is wrong, and nothing half-written.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

using lantern::test::runLantern;
using lantern::test::testOutputDir;

std::size_t entries(const std::filesystem::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}

TEST(CliFailure, NoVulkanDeviceExitsWith3) {
    const auto out = testOutputDir();
    const auto r = runLantern({"render", "builtin:spheres", "--width", "32", "--height", "32", "-o",
                               (out / "x.exr").string()},
                              {"VK_ICD_FILENAMES=/nonexistent/none.json",
                               "VK_DRIVER_FILES=/nonexistent/none.json"});
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("Vulkan"), std::string::npos) << r.err;
    EXPECT_EQ(entries(out), 0u);
}

TEST(CliFailure, UnwritableOutputExitsWith3AndLeavesNothing) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto out = testOutputDir();
    // (A missing folder is created: CliOutput.MissingFoldersOfTheOutputAreCreated.)
    for (const std::string& path : {std::string("/proc/lantern.exr"), std::string("/proc/lantern.png"),
                                    std::string("/proc/lantern/x.png")}) {
        const auto r = runLantern({"render", "builtin:spheres", "--width", "32", "--height", "32", "-o", path});
        EXPECT_EQ(r.exitCode, 3) << path << ": " << r.err;
        EXPECT_NE(r.err.find(std::filesystem::path(path).filename().string()), std::string::npos) << r.err;
    }
    EXPECT_EQ(entries(out), 0u);
}

// The command opens the device before it checks some values against the device's limits.
TEST(CliFailure, RefusedInputExitsWith1AndNamesTheOption) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    struct Case {
        std::vector<std::string> args;
        std::string mention;
    };
    const Case cases[] = {
        {{"render", "builtin:nope"}, "builtin:nope"},
        {{"render", "builtin:spheres", "--look-at", "0,0,0,0,0,0,0,1,0"}, "--look-at"},
        {{"render", "builtin:spheres", "--look-at", "0,0,5,0,0,0,0,0,1"}, "parallel"},
        {{"render", "builtin:spheres", "--perspective", "180,1,0.1,10"}, "fovy"},
        {{"render", "builtin:spheres", "--perspective", "60,0,0.1,10"}, "aspect"},
        {{"render", "builtin:spheres", "--frustum", "-1,1,-1,1,0,10"}, "near"},
        {{"render", "builtin:spheres", "--ortho", "1,1,-1,1,-1,1"}, "left == right"},
        {{"render", "builtin:spheres", "--ortho", "-1,1,-1,1,2,2"}, "far == near"},
        {{"render", "builtin:spheres", "--perspective", "60,1,0.1,nan"}, "--perspective"},
        {{"render", "builtin:spheres", "--camera", "5"}, "camera 5"},
        {{"render", "builtin:spheres", "--width", "100000"}, "not in range 1 to 16384"},
        {{"render", "builtin:spheres", "-o", "x.tiff"}, "tiff"},
        {{"render", "builtin:spheres", "--aov", "albedo"}, "albedo"},
        {{"render", "builtin:spheres", "--viewport", "0,0,5000,10"}, "--viewport"},
    };
    for (const Case& c : cases) {
        const auto r = runLantern(c.args);
        EXPECT_EQ(r.exitCode, 1) << c.args.back() << ": " << r.err;
        EXPECT_NE(r.err.find(c.mention), std::string::npos) << "expected \"" << c.mention << "\" in: " << r.err;
        EXPECT_EQ(r.err.find("\n"), r.err.size() - 1) << "one line: " << r.err;
    }
}

TEST(CliFailure, UsageErrorsExitWith2) {
    EXPECT_EQ(runLantern({}).exitCode, 2);
    EXPECT_EQ(runLantern({"render"}).exitCode, 2);
    EXPECT_EQ(runLantern({"render", "builtin:spheres", "--shading", "toon"}).exitCode, 1)
        << "a value outside the choices is a bad option value (docs/cli.md: 1)";
    EXPECT_EQ(runLantern({"render", "builtin:spheres", "--perspective", "60,1,1,2", "--ortho", "1,2,1,2,1,2"}).exitCode, 2);
    EXPECT_EQ(runLantern({"render", "--help"}).exitCode, 0);
}

} // namespace
