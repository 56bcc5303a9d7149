// `lantern compare` and `lantern render --compare`: exit statuses (0 pass or warn, 1 fail or
// refused input, 2 usage), mismatched and broken inputs, and the --diff and --json outputs read
// back.
#include "TestSupport.h"

#include <lantern/Compare.h>
#include <lantern/Io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <limits>

namespace {

using namespace lantern;
using lantern::test::runLantern;
using lantern::test::testOutputDir;

Image pattern(int w, int h) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.pixel(x, y);
            p[0] = float(x) / float(w);
            p[1] = float(y) / float(h);
            p[2] = float((x / 4 + y / 4) % 2) * 0.5f;
            p[3] = 1.0f;
        }
    return img;
}

// testOutputDir() empties the test's folder: each test takes it once and writes there.
std::string write(const Image& img, const std::filesystem::path& dir, const std::string& name) {
    const auto path = dir / name;
    auto r = writeImage(path, img);
    EXPECT_TRUE(r) << r.error().describe();
    return path.string();
}

TEST(CompareCli, IdenticalImagesPassWithExit0) {
    const auto dir = testOutputDir();
    const std::string a = write(pattern(40, 30), dir, "cli_a.exr"), b = write(pattern(40, 30), dir, "cli_b.exr");
    const auto r = runLantern({"compare", a, b});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("pass:"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("FLIP (HDR"), std::string::npos) << r.out;
    const std::string pa = write(pattern(40, 30), dir, "cli_a.png"), pb = write(pattern(40, 30), dir, "cli_b.png");
    const auto p = runLantern({"compare", pa, pb});
    EXPECT_EQ(p.exitCode, 0) << p.err;
    EXPECT_NE(p.out.find("FLIP (LDR"), std::string::npos) << p.out;
}

TEST(CompareCli, ThresholdsDecideTheExitStatus) {
    const auto dir = testOutputDir();
    Image img = pattern(40, 30);
    const std::string a = write(img, dir, "thr_a.exr");
    // 12 of 1200 pixels (1%) off by 0.1.
    for (int i = 0; i < 12; ++i) img.pixel(i * 3, i * 2)[0] += 0.1f;
    const std::string b = write(img, dir, "thr_b.exr");
    auto r = runLantern({"compare", a, b});
    EXPECT_EQ(r.exitCode, 1) << r.out;  // idiff's default: any pixel over 1e-6 fails
    EXPECT_NE(r.out.find("fail:"), std::string::npos) << r.out;
    r = runLantern({"compare", a, b, "--fail", "0.05", "--fail-percent", "2"});
    EXPECT_EQ(r.exitCode, 0) << r.out;
    r = runLantern({"compare", a, b, "--fail", "0.05", "--fail-percent", "0.5"});
    EXPECT_EQ(r.exitCode, 1) << r.out;
    r = runLantern({"compare", a, b, "--fail", "0.05", "--fail-percent", "2", "--warn", "0.05"});
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warn:"), std::string::npos) << r.out;
    r = runLantern({"compare", a, b, "--metric", "psnr", "--fail", "20", "--quiet"});
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    r = runLantern({"compare", a, b, "--metric", "psnr", "--fail", "80"});
    EXPECT_EQ(r.exitCode, 1) << r.out;
    r = runLantern({"compare", a, b, "--metric", "flip-mean", "--fail", "0.5"});
    EXPECT_EQ(r.exitCode, 0) << r.out;
    r = runLantern({"compare", a, b, "--metric", "ssim", "--fail", "0.999999"});
    EXPECT_EQ(r.exitCode, 1) << r.out;
}

TEST(CompareCli, UsageErrorsExit2) {
    const auto dir = testOutputDir();
    const std::string a = write(pattern(8, 8), dir, "use_a.exr");
    EXPECT_EQ(runLantern({"compare", a}).exitCode, 2);
    auto r = runLantern({"compare", a, a, "--metric", "rmse"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("--metric"), std::string::npos) << r.err;
    EXPECT_EQ(runLantern({"compare", a, a, "--flip", "maybe"}).exitCode, 2);
    EXPECT_EQ(runLantern({"compare", a, a, "--diff", "heat.tif"}).exitCode, 2);
    EXPECT_EQ(runLantern({"compare", a, a, "--fail-percent", "120"}).exitCode, 2);
    EXPECT_EQ(runLantern({"compare", a, a, "--fail", "abc"}).exitCode, 1) << "a bad value: refused input";
}

TEST(CompareCli, MismatchedOrBrokenInputsFailClearly) {
    const auto dir = testOutputDir();
    const std::string a = write(pattern(40, 30), dir, "mm_a.exr"), small = write(pattern(40, 20), dir, "mm_small.exr");
    auto r = runLantern({"compare", a, small});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("sizes differ"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("40x20"), std::string::npos) << r.err;
    Image withZ = pattern(40, 30);
    withZ.depth.assign(withZ.pixelCount(), 2.0f);
    const std::string z = write(withZ, dir, "mm_z.exr");
    r = runLantern({"compare", a, z});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("channels differ"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("R,G,B,A,Z"), std::string::npos) << r.err;
    const std::string png = write(pattern(40, 30), dir, "mm.png");
    r = runLantern({"compare", a, png});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("encodings differ"), std::string::npos) << r.err;
    r = runLantern({"compare", a, (dir / "nothing-here.exr").string()});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("nothing-here.exr"), std::string::npos) << r.err;
    const auto junk = dir / "junk.exr";
    std::ofstream(junk) << "not an exr at all";
    r = runLantern({"compare", a, junk.string()});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("junk.exr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not a readable OpenEXR file"), std::string::npos) << r.err;
}

TEST(CompareCli, NanInTheTestFailsWithoutACrash) {
    const auto dir = testOutputDir();
    Image img = pattern(16, 16);
    const std::string a = write(img, dir, "nan_a.exr");
    img.pixel(3, 4)[1] = std::numeric_limits<float>::quiet_NaN();
    img.pixel(9, 9)[0] = std::numeric_limits<float>::infinity();
    const std::string b = write(img, dir, "nan_b.exr");
    const auto json = (dir / "nan.json").string();
    const auto r = runLantern({"compare", a, b, "--fail", "1", "--json", json});
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
    EXPECT_NE(r.out.find("2 pixels hold NaN or Inf"), std::string::npos) << r.out;
    const auto j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["non_finite_mismatch"], 2);
    EXPECT_EQ(j["channels"][1]["non_finite_test"], 1);
    EXPECT_EQ(j["status"], "fail");
}

TEST(CompareCli, DiffAndJsonAreWrittenAndReadBack) {
    const auto dir = testOutputDir();
    Image img = pattern(32, 24);
    const std::string a = write(img, dir, "out_a.exr");
    img.pixel(10, 6)[2] += 0.4f;
    img.pixel(20, 12)[0] += 0.1f;
    const std::string b = write(img, dir, "out_b.exr");
    const auto diff = (dir / "heat.exr").string(), json = (dir / "report.json").string();
    const auto r = runLantern({"compare", a, b, "--diff", diff, "--json", json, "--fail", "0.2"});
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;  // 1 pixel of 768 over 0.2
    auto heat = readExr(diff);
    ASSERT_TRUE(heat) << heat.error().describe();
    ASSERT_EQ(heat->width, 32);
    ASSERT_EQ(heat->height, 24);
    EXPECT_FLOAT_EQ(heat->pixel(10, 6)[1], 1.0f);  // the largest error: white
    EXPECT_FLOAT_EQ(heat->pixel(0, 0)[0], 0.0f);
    EXPECT_GT(heat->pixel(20, 12)[0], 0.5f);
    const auto j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j["width"], 32);
    EXPECT_EQ(j["metric"], "abs");
    EXPECT_NEAR(j["max_abs"].get<double>(), 0.4, 1e-6);
    EXPECT_EQ(j["channels"][2]["max_at"], nlohmann::json::array({10, 6}));
    EXPECT_NEAR(j["over_share"].get<double>(), 1.0 / 768.0, 1e-12);  // tolerance: --fail
    EXPECT_EQ(j["status"], "fail");
    // A PNG heat map of the FLIP map.
    const auto pngDiff = (dir / "heat.png").string();
    const auto f = runLantern({"compare", a, b, "--metric", "flip-mean", "--fail", "0.5", "--diff", pngDiff});
    EXPECT_EQ(f.exitCode, 0) << f.out << f.err;
    auto png = readCompareImage(pngDiff);
    ASSERT_TRUE(png);
    EXPECT_EQ(png->width, 32);
}

TEST(CompareCli, RenderComparesInOneStep) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto ref = (dir / "rc_ref.exr").string(), refPng = (dir / "rc_ref.png").string();
    const std::vector<std::string> base = {"render", "builtin:spheres", "--width", "64", "--height", "40"};
    auto args = base;
    args.insert(args.end(), {"-o", ref, "-o", refPng});
    ASSERT_EQ(runLantern(args).exitCode, 0);
    args = base;
    args.insert(args.end(), {"-o", (dir / "rc_test.exr").string(), "--compare", ref});
    auto r = runLantern(args);
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("pass:"), std::string::npos) << r.out;
    args = base;
    args.insert(args.end(), {"-o", (dir / "rc_test.png").string(), "--compare", refPng});
    r = runLantern(args);
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    // A different background is a different picture.
    args = base;
    args.insert(args.end(), {"-o", (dir / "rc_bg.exr").string(), "--background", "1,0,0", "--compare", ref,
                             "--json", (dir / "rc.json").string()});
    r = runLantern(args);
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
    const auto j = nlohmann::json::parse(std::ifstream(dir / "rc.json"));
    EXPECT_GT(j["over_share"].get<double>(), 0.1);
    // Other sizes: a clear failure.
    args = {"render", "builtin:spheres", "--width", "32", "--height", "20", "-o", (dir / "rc_s.exr").string(),
            "--compare", ref};
    r = runLantern(args);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("sizes differ"), std::string::npos) << r.err;
    // A bad metric is refused before rendering; --compare with --frames is a usage error.
    args = base;
    args.insert(args.end(), {"--compare", ref, "--metric", "nope"});
    EXPECT_EQ(runLantern(args).exitCode, 2);
    args = base;
    args.insert(args.end(), {"--frames", "0-1", "-o", (dir / "rc_####.exr").string(), "--compare", ref});
    EXPECT_EQ(runLantern(args).exitCode, 2);
}

} // namespace
