// Sequences: frame ranges and shards, deterministic bytes across runs and shard layouts,
// clean stops on SIGINT/SIGTERM (complete files only), metadata, and bounded memory.
#include "TestSupport.h"

#include <lantern/Sequence.h>

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <map>
#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace {

using namespace lantern;
using lantern::test::runLantern;
using lantern::test::testOutputDir;

std::string bytes(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

std::vector<std::string> listing(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

TEST(SequenceParsing, RangesShardsAndPatterns) {
    auto r = parseFrameRange("3-7");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->first, 3);
    EXPECT_EQ(r->count(), 5);
    EXPECT_TRUE(parseFrameRange("4"));
    for (const char* bad : {"7-3", "-1-2", "a-b", "", "3-", "1-2-3"}) EXPECT_FALSE(parseFrameRange(bad)) << bad;
    auto s = parseShard("1/3");
    ASSERT_TRUE(s);
    EXPECT_EQ(shardFrames({0, 9}, *s), (std::vector<int>{1, 4, 7}));
    for (const char* bad : {"3/3", "-1/2", "1/0", "1", "a/b"}) EXPECT_FALSE(parseShard(bad)) << bad;
    EXPECT_EQ(expandFramePattern("out/f_####.exr", 7), "out/f_0007.exr");
    EXPECT_EQ(expandFramePattern("a#b##c", 12345), "a12345b12345c");
    EXPECT_FALSE(hasFramePattern("out/x.exr"));
    // Every frame of a range belongs to exactly one shard.
    for (int n = 1; n <= 5; ++n) {
        std::vector<int> all;
        for (int i = 0; i < n; ++i) {
            const auto f = shardFrames({2, 13}, {i, n});
            all.insert(all.end(), f.begin(), f.end());
        }
        std::sort(all.begin(), all.end());
        EXPECT_EQ(all.size(), 12u);
        EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());
    }
}

const std::vector<std::string> kSequence = {"render", "builtin:spheres-animated", "--frames", "0-7",
                                             "--fps", "6", "--width", "64", "--height", "48"};

std::vector<std::string> withOutput(std::vector<std::string> args, const std::string& out) {
    args.push_back("-o");
    args.push_back(out);
    return args;
}

TEST(Sequence, ShardsTogetherAreByteIdenticalToOneRun) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    std::filesystem::create_directories(dir / "single");
    std::filesystem::create_directories(dir / "again");
    std::filesystem::create_directories(dir / "shards");
    ASSERT_EQ(runLantern(withOutput(kSequence, (dir / "single" / "f_##.exr").string())).exitCode, 0);
    ASSERT_EQ(runLantern(withOutput(kSequence, (dir / "again" / "f_##.exr").string())).exitCode, 0);
    for (const char* shard : {"0/3", "1/3", "2/3"}) {
        auto args = withOutput(kSequence, (dir / "shards" / "f_##.exr").string());
        args.insert(args.end(), {"--shard", shard});
        const auto r = runLantern(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    const auto names = listing(dir / "single");
    ASSERT_EQ(names.size(), 8u);
    EXPECT_EQ(listing(dir / "shards"), names);
    for (const std::string& n : names) {
        const std::string a = bytes(dir / "single" / n);
        EXPECT_EQ(a, bytes(dir / "again" / n)) << n << " differs from run to run";
        EXPECT_EQ(a, bytes(dir / "shards" / n)) << n << " differs between shard layouts";
    }
    // The frames really animate.
    EXPECT_NE(bytes(dir / "single" / "f_00.exr"), bytes(dir / "single" / "f_04.exr"));
}

TEST(Sequence, MetadataNamesTheFrameAndTheCamera) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    ASSERT_EQ(runLantern(withOutput(kSequence, (dir / "f_##.exr").string())).exitCode, 0);
    auto img = readExr(dir / "f_03.exr");
    ASSERT_TRUE(img);
    std::map<std::string, std::string> md(img->metadata.begin(), img->metadata.end());
    EXPECT_EQ(md["lantern:frame"], "3");
    EXPECT_EQ(md["lantern:time"], "0.5");
    EXPECT_EQ(md["lantern:shading"], "phong");
    EXPECT_FALSE(md["lantern:viewFromWorld"].empty());
    EXPECT_FALSE(md["lantern:version"].empty());
    if (std::system("command -v oiiotool >/dev/null 2>&1") == 0) {
        const auto info = test::runProcess({"oiiotool", "--info", "-v", (dir / "f_03.exr").string()});
        // The standard attributes compositors read (OpenEXR's camera looks down +Z).
        EXPECT_NE(info.out.find("worldToCamera: 1, 0, 0, 0,"), std::string::npos) << info.out;
        EXPECT_NE(info.out.find("worldToNDC:"), std::string::npos) << info.out;
        EXPECT_NE(info.out.find("framesPerSecond: 6/1"), std::string::npos) << info.out;
    }
}

TEST(Sequence, RefusesPatternlessOutputsAndUnwritableFolders) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    auto r = runLantern(withOutput(kSequence, (dir / "same.exr").string()));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("'#'"), std::string::npos) << r.err;
    // A missing folder is created (docs/cli.md); one that cannot be (a file is in the way) is
    // an I/O failure, and nothing is written.
    { std::ofstream(dir / "blocker") << "a file"; }
    r = runLantern(withOutput(kSequence, (dir / "blocker" / "f_#.exr").string()));
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_EQ(listing(dir), std::vector<std::string>{"blocker"}) << "nothing but the file in the way";
    { std::ifstream in(dir / "blocker"); std::string text; std::getline(in, text); EXPECT_EQ(text, "a file"); }
    std::filesystem::remove(dir / "blocker");
    r = runLantern({"render", "builtin:spheres", "--shard", "0/2"});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    r = runLantern({"render", "builtin:spheres", "--frames", "0-3", "--time", "1", "-o", (dir / "f#.exr").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
}

// Starts a long sequence, signals it once frames exist, and checks that it stopped cleanly.
void stopWith(int signal) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const std::string cli = test::cliPath().string();
    const std::string pattern = (dir / "f_####.exr").string();
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        const int devnull = open("/dev/null", O_WRONLY);
        dup2(devnull, 1);
        dup2(devnull, 2);
        execl(cli.c_str(), cli.c_str(), "render", "builtin:spheres-animated", "--frames", "0-5000",
              "--width", "160", "--height", "120", "-o", pattern.c_str(), (char*)nullptr);
        _exit(127);
    }
    // Wait for a few frames, then stop it.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (listing(dir).size() < 4 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    kill(pid, signal);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "killed instead of stopping";
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal);
    const auto names = listing(dir);
    EXPECT_GE(names.size(), 4u);
    EXPECT_LT(names.size(), 5000u);
    for (const std::string& n : names) {
        EXPECT_EQ(n.find(".tmp-"), std::string::npos) << "temporary file left: " << n;
        EXPECT_TRUE(readExr(dir / n)) << n << " is not a complete EXR";
    }
}

TEST(Sequence, SigintStopsCleanly) { stopWith(SIGINT); }
TEST(Sequence, SigtermStopsCleanly) { stopWith(SIGTERM); }

class SequenceApi : public test::GpuTest {};

TEST_F(SequenceApi, MemoryStaysBoundedAndProgressIsReported) {
    auto scene = builtinScene("spheres-animated");
    ASSERT_TRUE(scene);
    auto prepared = renderer().prepare(std::make_shared<const Scene>(std::move(*scene)));
    ASSERT_TRUE(prepared);
    RenderOptions o;
    o.width = 48;
    o.height = 32;
    SequenceOptions s;
    s.frames = {0, 39};
    s.fps = 10;
    s.outputs = {(testOutputDir() / "f_##.exr").string()};
    s.encoderThreads = 2;
    int calls = 0, lastWritten = 0;
    s.progress = [&](const SequenceProgress& p) {
        ++calls;
        EXPECT_GE(p.written, lastWritten);
        lastWritten = p.written;
        EXPECT_EQ(p.total, 40);
    };
    auto r = renderer().renderSequence(*prepared, o, s);
    ASSERT_TRUE(r) << r.error().describe();
    EXPECT_EQ(r->framesWritten.size(), 40u);
    EXPECT_EQ(lastWritten, 40);
    EXPECT_GT(calls, 0);
    // At most the queue (one per encoder thread) plus the frames being encoded: 2 + 2.
    EXPECT_LE(r->peakQueuedFrames, 4u);
    EXPECT_EQ(r->renderMs.size(), 40u);
    EXPECT_FALSE(r->stopped);
    // A stop request is honoured between frames.
    int polled = 0;
    lastWritten = 0;
    s.shouldStop = [&] { return ++polled > 5; };
    s.outputs = {(testOutputDir() / "g_##.png").string()};
    auto stopped = renderer().renderSequence(*prepared, o, s);
    ASSERT_TRUE(stopped);
    EXPECT_TRUE(stopped->stopped);
    EXPECT_LE(stopped->framesWritten.size(), 5u);
}

} // namespace
