// `lantern thumbnail`, the freedesktop thumbnailer: a SIZE x SIZE PNG with a transparent
// background from the three-quarter view; and, since a file manager runs it on whatever a user
// browses past, hostile files refused within its budgets, fast, with no output: a 1 GB file,
// an accessor of four billion elements, a graph 100,000 nodes deep, a render past the time
// budget, a process held to a small address space.
#include "TestSupport.h"

#include <gtest/gtest.h>
#include <lantern/Io.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;
using lantern::test::runLantern;

fs::path sample() {
    return lantern::test::sharedDir() / "assets/gltf-samples/Box/glTF-Binary/Box.glb";
}

struct Timed {
    lantern::test::ProcessResult result;
    double seconds = 0.0;
};

Timed thumbnail(std::vector<std::string> args) {
    args.insert(args.begin(), "thumbnail");
    const auto t0 = std::chrono::steady_clock::now();
    Timed t;
    t.result = runLantern(args);
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return t;
}

// Refused: exit non-zero within `seconds`, the message naming the file and `why`, no output.
void expectRefused(const Timed& t, const fs::path& input, const fs::path& output, const char* why,
                   double seconds) {
    EXPECT_NE(t.result.exitCode, 0) << t.result.err;
    EXPECT_LT(t.seconds, seconds) << t.result.err;
    EXPECT_NE(t.result.err.find(input.string()), std::string::npos) << t.result.err;
    EXPECT_NE(t.result.err.find(why), std::string::npos) << t.result.err;
    EXPECT_FALSE(fs::exists(output)) << "a thumbnail was written";
    for (const auto& e : fs::directory_iterator(output.parent_path()))
        EXPECT_EQ(e.path().filename().string().find(".tmp-lantern-"), std::string::npos)
            << "a temporary file was left: " << e.path();
}

TEST(Thumbnail, IsASquarePngOfTheThreeQuarterViewOnTransparency) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = lantern::test::testOutputDir();
    const auto out = dir / "box.png";
    const Timed t = thumbnail({"-s", "96", sample().string(), out.string()});
    ASSERT_EQ(t.result.exitCode, 0) << t.result.err;
    auto image = lantern::readCompareImage(out);
    ASSERT_TRUE(image) << image.error().describe();
    ASSERT_EQ(image->width, 96);
    ASSERT_EQ(image->height, 96);
    ASSERT_EQ(image->channels.back(), "A");
    const std::size_t c = image->channels.size();
    auto alpha = [&](int x, int y) { return image->values[(std::size_t(y) * 96 + std::size_t(x)) * c + c - 1]; };
    EXPECT_EQ(alpha(0, 0), 0.0f) << "the background is transparent";
    EXPECT_EQ(alpha(95, 95), 0.0f);
    EXPECT_EQ(alpha(48, 48), 1.0f) << "the box fills the middle";
    // The three-quarter view sees three faces of the box: its picture is render's default view.
    const auto same = dir / "render.png";
    ASSERT_EQ(runLantern({"render", sample().string(), "--view", "three-quarter", "--width", "96",
                          "--height", "96", "--background", "0,0,0,0", "-o", same.string()})
                  .exitCode,
              0);
    std::ifstream a(out, std::ios::binary), b(same, std::ios::binary);
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b)))
        << "not the picture `lantern render --view three-quarter` makes";
}

TEST(Thumbnail, HostileFilesAreRefusedFastWithinTheBudgets) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = lantern::test::testOutputDir();
    const auto out = dir / "out" / "t.png";
    fs::create_directories(out.parent_path());

    const auto big = dir / "big.glb";  // 1 GB, sparse: refused by its size, before reading
    { std::ofstream(big, std::ios::binary).flush(); }
    fs::resize_file(big, std::uintmax_t(1) << 30);
    expectRefused(thumbnail({big.string(), out.string()}), big, out, "--max-size", 2.0);
    fs::remove(big);

    const auto huge = dir / "huge.gltf";  // four billion positions in a 12-byte buffer
    std::ofstream(huge) << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":12,
        "uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAA"}],
        "bufferViews":[{"buffer":0,"byteLength":12}],"accessors":[{"bufferView":0,
        "componentType":5126,"count":4000000000,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],
        "scenes":[{"nodes":[0]}]})";
    expectRefused(thumbnail({huge.string(), out.string()}), huge, out, "accessors[0]", 2.0);

    const auto deep = dir / "deep.gltf";  // a chain of 100,000 nodes: over the load budget
    {
        std::ofstream f(deep);
        f << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)";
        for (int i = 0; i < 99999; ++i) f << "{\"children\":[" << i + 1 << "]},";
        f << "{}]}";
    }
    expectRefused(thumbnail({deep.string(), out.string()}), deep, out, "--max-size", 5.0);
    // Within a larger budget the same chain is drawn (nothing to see) without a crash.
    const auto drawn = thumbnail({"--max-size", "1000000000", deep.string(), out.string()});
    EXPECT_EQ(drawn.result.exitCode, 0) << drawn.result.err;
    fs::remove(out);

    // The time budget: the device alone takes longer than a hundredth of a second.
    expectRefused(thumbnail({"--time-limit", "0.01", sample().string(), out.string()}), sample(),
                  out, "--time-limit", 3.0);
}

TEST(Thumbnail, AProcessHeldToASmallAddressSpaceFailsCleanly) {
#if defined(LANTERN_ASAN) || defined(LANTERN_TSAN)
    GTEST_SKIP() << "a sanitizer build reserves terabytes of shadow memory: the thumbnailer does "
                    "not apply --memory-limit there";
#else
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = lantern::test::testOutputDir();
    const auto out = dir / "t.png";
    expectRefused(thumbnail({"--memory-limit", "64", sample().string(), out.string()}), sample(),
                  out, "--memory-limit 64 MiB", 5.0);
    const auto fits = thumbnail({"--memory-limit", "1024", "-s", "64", sample().string(), out.string()});
    EXPECT_EQ(fits.result.exitCode, 0) << "an ordinary file fits the budget: " << fits.result.err;
#endif
}

} // namespace
