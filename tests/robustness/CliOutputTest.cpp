// What `lantern render` writes where: missing folders of -o are created, '#' runs are the frame
// number for one frame too (--frame N, or --time T at --fps), a sample count the device lacks is
// refused before rendering (exit 2, naming the counts it has), the background rule, a large
// PNG written in bands, and `lantern info --devices`.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace {

using namespace lantern;
using lantern::test::runLantern;
using lantern::test::testOutputDir;

class CliOutput : public lantern::test::GpuTest {};

std::string bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> small(std::vector<std::string> args) {
    args.insert(args.end(), {"--width", "24", "--height", "16"});
    return args;
}

TEST_F(CliOutput, MissingFoldersOfTheOutputAreCreated) {
    const auto dir = testOutputDir();
    const auto deep = dir / "a" / "b" / "c.png";
    const auto r = runLantern(small({"render", "builtin:spheres", "-o", deep.string(), "-o",
                                     (dir / "d" / "e.exr").string()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(deep));
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "d" / "e.exr"));
    // A folder that cannot be made (its parent is a file) is an output failure: exit 3.
    std::ofstream(dir / "file") << "x";
    const auto bad = runLantern(small({"render", "builtin:spheres", "-o",
                                       (dir / "file" / "x.png").string()}));
    EXPECT_EQ(bad.exitCode, 3) << bad.err;
    EXPECT_NE(bad.err.find("cannot create the folder"), std::string::npos) << bad.err;
}

TEST_F(CliOutput, HashRunsAreTheFrameNumberForOneFrame) {
    const auto dir = testOutputDir();
    const std::string pattern = (dir / "f_####.png").string();
    struct Row {
        std::vector<std::string> args;
        const char* file;
    };
    const Row rows[] = {
        {{}, "f_0000.png"},
        {{"--frame", "7"}, "f_0007.png"},
        {{"--time", "0.5"}, "f_0012.png"},               // round(0.5 x 24)
        {{"--time", "0.5", "--fps", "10"}, "f_0005.png"},
        {{"--frame", "3", "--fps", "12"}, "f_0003.png"}, // at time 0.25
    };
    for (const Row& row : rows) {
        auto args = small({"render", "builtin:spheres-animated", "-o", pattern});
        args.insert(args.end(), row.args.begin(), row.args.end());
        const auto r = runLantern(args);
        ASSERT_EQ(r.exitCode, 0) << row.file << ": " << r.err;
        EXPECT_EQ(r.out, (dir / row.file).string() + "\n");
        EXPECT_TRUE(std::filesystem::is_regular_file(dir / row.file)) << row.file;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "f_####.png")) << "no file named with '#'";
    // --frame N is the picture at time N / fps.
    EXPECT_EQ(bytes(dir / "f_0003.png"),
              bytes((runLantern(small({"render", "builtin:spheres-animated", "--time", "0.25",
                                       "-o", (dir / "t.png").string()})),
                     dir / "t.png")));
    EXPECT_NE(bytes(dir / "f_0003.png"), bytes(dir / "f_0000.png")) << "the spheres move";
    for (const auto& bad : std::vector<std::vector<std::string>>{
             {"--frame", "2", "--time", "1"}, {"--frame", "2", "--frames", "0-3"},
             {"--time", "-1"}}) {
        auto args = small({"render", "builtin:spheres-animated", "-o", pattern});
        args.insert(args.end(), bad.begin(), bad.end());
        // Two options that cannot be combined: usage (2); a time out of range: a bad value (1).
        EXPECT_EQ(runLantern(args).exitCode, bad.size() == 2 && bad[0] == "--time" ? 1 : 2)
            << bad.front() << " " << bad.back();
    }
}

TEST_F(CliOutput, AnMsaaTheDeviceLacksIsRefusedNamingTheOnesItHas) {
    const auto& counts = renderer().device().msaaSampleCounts;
    int missing = 0;
    for (int m : {2, 8})
        if (std::find(counts.begin(), counts.end(), m) == counts.end()) missing = m;
    if (!missing) GTEST_SKIP() << renderer().device().name << " supports 1, 2, 4 and 8";
    std::string supported;
    for (int c : counts)
        supported += (supported.empty() ? "" : ", ") + std::to_string(c);
    const auto dir = testOutputDir();
    for (const std::vector<std::string>& command :
         {std::vector<std::string>{"render", "builtin:spheres", "-o", (dir / "x.png").string()},
          std::vector<std::string>{"bench", "frame", "builtin:spheres", "--runs", "1"}}) {
        auto args = small(command);
        args.insert(args.end(), {"--msaa", std::to_string(missing)});
        const auto r = runLantern(args);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("supports " + supported), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("--msaa"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png")) << "nothing rendered";
}

TEST_F(CliOutput, TheBackgroundIsOpaqueBlackUnlessAsked) {
    const auto dir = testOutputDir();
    ASSERT_EQ(runLantern(small({"render", "builtin:spheres", "-o", (dir / "a.exr").string()}))
                  .exitCode,
              0);
    ASSERT_EQ(runLantern(small({"render", "builtin:spheres", "--background", "0,0,0,0", "-o",
                                (dir / "b.exr").string()}))
                  .exitCode,
              0);
    auto opaque = readExr(dir / "a.exr");
    auto clear = readExr(dir / "b.exr");
    ASSERT_TRUE(opaque && clear);
    EXPECT_EQ(opaque->pixel(0, 0)[3], 1.0f) << "the default, as in view and RenderOptions";
    EXPECT_EQ(clear->pixel(0, 0)[3], 0.0f);
    EXPECT_EQ(RenderOptions().background, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

// A PNG-only picture of 2^20 pixels is rendered and written in bands (four of 256 rows here,
// BandRows.TheAutomaticHeightWeighsPixelsAgainstVertices): two outputs of it are the same file,
// and it is the picture written beside an EXR (one whole frame) but for rounding: no channel
// more than 1 of 255 apart, and not one pixel in ten thousand that much.
TEST_F(CliOutput, ALargePngOnlyPictureIsWrittenInBands) {
    const auto dir = testOutputDir();
    const std::vector<std::string> size{"--width", "1024", "--height", "1024"};
    auto args = [&](std::vector<std::string> a) {
        a.insert(a.end(), size.begin(), size.end());
        for (const std::string& flag : lantern::test::validationFlag()) a.push_back(flag);
        return a;
    };
    const auto banded = runLantern(args({"render", "builtin:spheres", "-o", (dir / "bands.png").string(),
                                         "-o", (dir / "again.png").string()}));
    ASSERT_EQ(banded.exitCode, 0) << banded.err;
    EXPECT_EQ(banded.err.find("validation"), std::string::npos) << "validation messages: " << banded.err;
    ASSERT_EQ(runLantern(args({"render", "builtin:spheres", "-o", (dir / "whole.png").string(),
                               "-o", (dir / "whole.exr").string()}))
                  .exitCode,
              0);
    EXPECT_GT(bytes(dir / "bands.png").size(), 1000u);
    EXPECT_EQ(bytes(dir / "bands.png"), bytes(dir / "again.png"));
    const auto compared = runLantern({"compare", (dir / "whole.png").string(),
                                      (dir / "bands.png").string(), "--no-ssim", "--fail",
                                      "0.0040", "--fail-percent", "0.01"});
    EXPECT_EQ(compared.exitCode, 0) << compared.out << compared.err;
}

TEST_F(CliOutput, InfoDevicesNamesTheChosenDeviceAndWhy) {
    const auto r = runLantern({"info", "--devices"}, {"DISPLAY=", "WAYLAND_DISPLAY="});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string name = renderer().device().name;
    // "  * [i] NAME": the chosen one, numbered as --device and LANTERN_DEVICE take it.
    const std::size_t chosenAt = r.out.find("  * [");
    ASSERT_NE(chosenAt, std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("] " + name + "\n", chosenAt), r.out.find(']', chosenAt)) << r.out;
    EXPECT_NE(r.out.find("chosen: " + name + ": the best-ranked usable device"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("Vulkan loader: " + buildInfo().vulkanLoader), std::string::npos);
    // The suite's cache folder (LANTERN_CACHE_DIR, set for every test), never ~/.cache.
    const char* cacheDir = std::getenv("LANTERN_CACHE_DIR");
    ASSERT_TRUE(cacheDir && *cacheDir);
    EXPECT_NE(r.out.find(std::string("pipeline cache: ") + cacheDir + "/pipelines-"),
              std::string::npos)
        << r.out;
    const auto off = runLantern({"info", "--devices"}, {"LANTERN_PIPELINE_CACHE=0"});
    EXPECT_NE(off.out.find("pipeline cache: in memory only (LANTERN_PIPELINE_CACHE=0; "
                           "pipelines are compiled again by each run)"),
              std::string::npos)
        << off.out;
    EXPECT_NE(r.out.find("display for `lantern view`: none"), std::string::npos) << r.out;
    const auto none = runLantern({"info", "--devices", "--device", "no-such-device"});
    EXPECT_EQ(none.exitCode, 3) << none.out;
    EXPECT_NE(none.out.find("chosen: none"), std::string::npos) << none.out;
    EXPECT_EQ(runLantern({"info"}).exitCode, 2) << "neither a scene nor --devices";
}

// A second process finds the pipeline cache the first one wrote, and `info --devices` says
// where it is and how big.
TEST_F(CliOutput, ASecondProcessLoadsThePipelineCache) {
    const auto dir = testOutputDir();
    const std::vector<std::string> env = {"LANTERN_CACHE_DIR=" + (dir / "cache").string()};
    const auto before = runLantern({"info", "--devices"}, env);
    EXPECT_NE(before.out.find((dir / "cache").string() + "/pipelines-"), std::string::npos)
        << before.out;
    EXPECT_NE(before.out.find(" (not written yet)\n"), std::string::npos) << before.out;
    for (int run = 0; run < 2; ++run) {
        SCOPED_TRACE("run " + std::to_string(run));
        const auto r = runLantern(
            small({"render", "builtin:spheres", "--verbose", "-o", (dir / "a.png").string()}), env);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("bytes loaded from " + (dir / "cache").string() + "/pipelines-") !=
                      std::string::npos,
                  run == 1)
            << r.err;
    }
    const auto after = runLantern({"info", "--devices"}, env);
    EXPECT_NE(after.out.find(" bytes)\n"), std::string::npos) << after.out;
}

} // namespace
