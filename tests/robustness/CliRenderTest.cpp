// `lantern render` end to end: writes the EXR and PNG it names, prints their paths, and the
// EXR is what other tools read.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace {

using namespace lantern;
using lantern::test::runLantern;
using lantern::test::testOutputDir;

TEST(CliRender, WritesExrAndPngAndPrintsTheirPaths) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto out = testOutputDir();
    const auto exr = out / "spheres.exr", png = out / "spheres.png";
    std::vector<std::string> args = {"render", "builtin:spheres", "--width", "80", "--height",
                                     "48", "-o", exr.string(), "-o", png.string()};
    for (const std::string& flag : lantern::test::validationFlag()) args.push_back(flag);
    const auto r = runLantern(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out, exr.string() + "\n" + png.string() + "\n");
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << "validation messages: " << r.err;
    auto img = readExr(exr);
    ASSERT_TRUE(img) << img.error().describe();
    EXPECT_EQ(img->width, 80);
    EXPECT_EQ(img->height, 48);
    EXPECT_GT(std::filesystem::file_size(png), 100u);
    bool hasShading = false;
    for (const auto& [k, v] : img->metadata) hasShading |= k == "lantern:shading" && v == "phong";
    EXPECT_TRUE(hasShading);
}

TEST(CliRender, AovChannelsAndHalf) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto out = testOutputDir();
    const auto exr = out / "aov.exr";
    const auto r = runLantern({"render", "builtin:spheres", "--width", "64", "--height", "40", "--aov",
                               "depth,normal", "--half", "-o", exr.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readExr(exr);
    ASSERT_TRUE(img);
    ASSERT_EQ(img->depth.size(), img->pixelCount());
    ASSERT_EQ(img->normal.size(), img->pixelCount() * 3);
    // The centre pixel hits the middle sphere, facing the camera.
    const std::size_t c = std::size_t(20) * 64 + 32;
    EXPECT_GT(img->depth[c], 5.0f);
    EXPECT_LT(img->depth[c], 12.0f);
    EXPECT_GT(img->normal[c * 3 + 2], 0.5f);
    if (std::system("command -v oiiotool >/dev/null 2>&1") == 0) {
        const auto info = test::runProcess({"oiiotool", "--info", "-v", exr.string()});
        // Colour as half, AOVs as float, in the canonical order other tools expect.
        EXPECT_NE(info.out.find("R (half), G (half), B (half), A (half), Z (float), N.X (float), "
                                "N.Y (float), N.Z (float)"),
                  std::string::npos)
            << info.out;
    }
}

TEST(CliRender, InfoDescribesTheScene) {
    const auto r = runLantern({"info", "builtin:spheres"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("lights: 2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("cameras: 1"), std::string::npos) << r.out;
}

} // namespace
