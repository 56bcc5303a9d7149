// Batches: one `lantern render` over many files times many views, with output
// templates, one device, finished outputs skipped, shards that partition the jobs, and files
// that fail reported without stopping the batch (docs/sequences.md, "Batches").
#include "TestSupport.h"

#include "../unit/GltfTestBuilder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using lantern::test::runLantern;
using lantern::test::testOutputDir;

std::string bytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// The names of the regular files below `dir`, relative to it, sorted.
std::set<std::string> files(const fs::path& dir) {
    std::set<std::string> names;
    if (!fs::exists(dir)) return names;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) names.insert(fs::relative(e.path(), dir).string());
    return names;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);)
        if (!l.empty()) out.push_back(l);
    return out;
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// A small glTF: a triangle seen from +Z, moved by `x` so that files differ.
fs::path triangle(const fs::path& dir, const std::string& name, float x = 0.0f) {
    lantern::test::GltfBuilder b;
    const int node = b.addTriangle();
    b.doc["nodes"][std::size_t(node)]["translation"] = {x, 0.0, 0.0};
    return b.write(dir, name);
}

fs::path box() {
    return lantern::test::sharedDir() / "assets/gltf-samples/Box/glTF-Embedded/Box.gltf";
}

std::vector<std::string> small(std::vector<std::string> args) {
    args.insert(args.end(), {"--width", "32", "--height", "32"});
    return args;
}

TEST(Batch, FilesTimesViewsWriteExactlyTheNamedOutputs) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto tri = triangle(dir, "tri");
    const auto out = dir / "out";
    auto r = runLantern(small({"render", "builtin:spheres", box().string(), tri.string(),
                               "--views", "orbit:3", "-o",
                               (out / "{scene}" / "{view}.png").string()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::set<std::string> expected = {
        "spheres/orbit0.png", "spheres/orbit1.png", "spheres/orbit2.png", "Box/orbit0.png",
        "Box/orbit1.png",     "Box/orbit2.png",     "tri/orbit0.png",     "tri/orbit1.png",
        "tri/orbit2.png"};
    EXPECT_EQ(files(out), expected);
    EXPECT_EQ(lines(r.out).size(), 9u) << r.out;  // each path written, once
    EXPECT_NE(r.err.find("9 rendered, 0 skipped, 0 failed of 9 jobs"), std::string::npos) << r.err;
    // The views differ, and the first view of an orbit is the three-quarter view of automatic
    // framing, the first of a turntable the front view: the same pixels.
    const std::string o0 = bytes(out / "spheres/orbit0.png");
    EXPECT_NE(o0, bytes(out / "spheres/orbit1.png"));
    EXPECT_NE(bytes(out / "spheres/orbit1.png"), bytes(out / "spheres/orbit2.png"));
    r = runLantern(small({"render", "builtin:spheres", "--views", "three-quarter,front,turntable:2",
                          "-o", (dir / "named" / "{view}.png").string()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(files(dir / "named"), (std::set<std::string>{"three-quarter.png", "front.png",
                                                           "turntable0.png", "turntable1.png"}));
    EXPECT_EQ(bytes(dir / "named/three-quarter.png"), o0);
    EXPECT_EQ(bytes(dir / "named/front.png"), bytes(dir / "named/turntable0.png"));
    EXPECT_NE(bytes(dir / "named/turntable0.png"), bytes(dir / "named/turntable1.png"));
}

TEST(Batch, AFailingFileInTheMiddleIsReportedAndTheBatchGoesOn) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto a = triangle(dir, "a"), d = triangle(dir, "d", 0.5f);
    const auto bad = lantern::test::sharedDir() / "assets/gltf-invalid/base/data/json/invalid_syntax.gltf";
    const auto missing = dir / "missing.gltf";
    const auto r = runLantern(small({"render", a.string(), bad.string(), missing.string(), d.string(),
                                     "--views", "front,top", "-o",
                                     (dir / "out" / "{scene}_{view}.exr").string()}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(files(dir / "out"), (std::set<std::string>{"a_front.exr", "a_top.exr",
                                                         "d_front.exr", "d_top.exr"}));
    // Each failing file is named with its problem once, and the summary counts the jobs.
    EXPECT_EQ(count(r.err, "lantern: error: " + bad.string()), 1u) << r.err;
    EXPECT_EQ(count(r.err, "lantern: error: " + missing.string()), 1u) << r.err;
    EXPECT_NE(r.err.find("4 rendered, 0 skipped, 4 failed of 8 jobs"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("batch: failed: " + missing.string()), std::string::npos) << r.err;
    // The files after the failures were rendered after them (the batch went on).
    EXPECT_LT(r.err.find(missing.string()), r.err.find("batch:")) << r.err;
}

TEST(Batch, ARerunSkipsFinishedOutputsAndRendersOnlyWhatIsMissing) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto args = small({"render", "builtin:spheres", triangle(dir, "tri").string(), "--views",
                             "orbit:2", "-o", (dir / "out" / "{scene}-{view}.png").string()});
    ASSERT_EQ(runLantern(args).exitCode, 0);
    const auto names = files(dir / "out");
    ASSERT_EQ(names.size(), 4u);
    std::map<std::string, fs::file_time_type> before;
    for (const auto& n : names) before[n] = fs::last_write_time(dir / "out" / n);
    auto r = runLantern(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("0 rendered, 4 skipped, 0 failed of 4 jobs"), std::string::npos) << r.err;
    for (const auto& n : names) EXPECT_EQ(fs::last_write_time(dir / "out" / n), before[n]) << n;
    // One output removed: only its job renders again.
    fs::remove(dir / "out" / "tri-orbit1.png");
    r = runLantern(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(lines(r.out), std::vector<std::string>{(dir / "out" / "tri-orbit1.png").string()});
    EXPECT_EQ(fs::last_write_time(dir / "out" / "tri-orbit0.png"), before["tri-orbit0.png"]);
    // --overwrite renders every job again.
    auto again = args;
    again.push_back("--overwrite");
    r = runLantern(again);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(lines(r.out).size(), 4u) << r.out;
}

TEST(Batch, ShardsPartitionTheJobsExactlyAndWriteTheSameBytes) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto tri = triangle(dir, "tri");
    auto args = [&](const std::string& out) {
        return small({"render", "builtin:spheres", tri.string(), "--views", "orbit:2,top", "-o",
                      (dir / out / "{scene}_{view}.exr").string()});
    };
    ASSERT_EQ(runLantern(args("all")).exitCode, 0);
    std::multiset<std::string> written;
    for (const char* shard : {"0/4", "1/4", "2/4", "3/4"}) {
        auto a = args("shards");
        a.insert(a.end(), {"--shard", shard});
        const auto r = runLantern(a);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        // 6 jobs over 4 shards: positions k with k mod 4 == I.
        EXPECT_EQ(lines(r.out).size(), shard[0] < '2' ? 2u : 1u) << shard << r.out;
        for (const auto& l : lines(r.out)) written.insert(fs::path(l).filename().string());
    }
    const auto names = files(dir / "all");
    ASSERT_EQ(names.size(), 6u);
    EXPECT_EQ(std::set<std::string>(written.begin(), written.end()), names);
    EXPECT_EQ(written.size(), 6u) << "a job rendered by two shards";
    for (const auto& n : names) EXPECT_EQ(bytes(dir / "all" / n), bytes(dir / "shards" / n)) << n;
}

// --processes N runs N processes of the same command, each with its own device, splitting the
// jobs by position (within --shard when one is given): the same files, byte for byte, every
// path printed once as a whole line; a file that fails in one process fails the command; a
// sequence splits its frames the same way; one picture stays one process.
TEST(Batch, ProcessesSplitTheJobsAndWriteTheSameBytes) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto tri = triangle(dir, "tri");
    auto args = [&](const std::string& out, std::vector<std::string> more) {
        auto a = small({"render", "builtin:spheres", tri.string(), "--views", "orbit:2,top", "-o",
                        (dir / out / "{scene}_{view}.exr").string()});
        a.insert(a.end(), more.begin(), more.end());
        return a;
    };
    ASSERT_EQ(runLantern(args("one", {})).exitCode, 0);
    const auto r = runLantern(args("two", {"--processes", "2"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::set<std::string> printed;
    for (const auto& l : lines(r.out)) {
        EXPECT_TRUE(fs::is_regular_file(l)) << "not a whole path: " << l;
        EXPECT_TRUE(printed.insert(fs::path(l).filename().string()).second) << "printed twice: " << l;
    }
    const auto names = files(dir / "one");
    ASSERT_EQ(names.size(), 6u);
    EXPECT_EQ(printed, names);
    EXPECT_EQ(files(dir / "two"), names);
    for (const auto& n : names) EXPECT_EQ(bytes(dir / "one" / n), bytes(dir / "two" / n)) << n;
    EXPECT_EQ(count(r.err, "lantern: batch: "), 2u) << "one tally per process: " << r.err;
    EXPECT_NE(r.err.find("2 processes done"), std::string::npos) << r.err;

    // Within a shard: the shard's jobs, split again.
    ASSERT_EQ(runLantern(args("half1", {"--shard", "1/2"})).exitCode, 0);
    const auto half = runLantern(args("half2", {"--shard", "1/2", "--processes", "3"}));
    ASSERT_EQ(half.exitCode, 0) << half.err;
    EXPECT_EQ(files(dir / "half1").size(), 3u);
    EXPECT_EQ(files(dir / "half2"), files(dir / "half1"));

    // A bad file in the middle: the others are written, the command fails.
    { std::ofstream(dir / "bad.gltf") << "{ not json"; }
    const auto bad = runLantern(small({"render", "builtin:spheres", (dir / "bad.gltf").string(),
                                       tri.string(), "--processes", "2", "-o",
                                       (dir / "bad" / "{scene}.exr").string()}));
    EXPECT_EQ(bad.exitCode, 1) << bad.err;
    EXPECT_EQ(files(dir / "bad"), (std::set<std::string>{"spheres.exr", "tri.exr"}));

    // A sequence: its frames split over the processes, the same bytes.
    auto sequence = [&](const std::string& out, const char* processes) {
        return runLantern(small({"render", "builtin:spheres-animated", "--frames", "0-4", "-o",
                                 (dir / out / "f_##.exr").string(), "--processes", processes}));
    };
    ASSERT_EQ(sequence("seq1", "1").exitCode, 0);
    const auto seq = sequence("seq2", "2");
    ASSERT_EQ(seq.exitCode, 0) << seq.err;
    EXPECT_EQ(lines(seq.out).size(), 5u) << seq.out;
    ASSERT_EQ(files(dir / "seq1").size(), 5u);
    EXPECT_EQ(files(dir / "seq2"), files(dir / "seq1"));
    for (const auto& n : files(dir / "seq1")) EXPECT_EQ(bytes(dir / "seq1" / n), bytes(dir / "seq2" / n)) << n;

    // One picture: one process, and a warning says so.
    const auto one = runLantern(small({"render", "builtin:spheres", "-o", (dir / "single.png").string(),
                                       "--processes", "2"}));
    EXPECT_EQ(one.exitCode, 0) << one.err;
    EXPECT_NE(one.err.find("one picture renders in one process"), std::string::npos) << one.err;
    EXPECT_EQ(lines(one.out).size(), 1u) << one.out;
}

TEST(Batch, CollidingOrUnknownTemplatesAreRefusedBeforeRendering) {
    const auto dir = testOutputDir();
    fs::create_directories(dir / "x");
    fs::create_directories(dir / "y");
    const auto a = triangle(dir / "x", "same"), b = triangle(dir / "y", "same");
    const auto out = dir / "out";
    struct Case {
        std::vector<std::string> args;
        std::string says;
    };
    const std::vector<Case> cases = {
        {{"builtin:spheres", "--views", "orbit:2", "-o", (out / "{scene}.png").string()}, "twice"},
        {{a.string(), b.string(), "-o", (out / "{scene}.png").string()}, "twice"},
        {{"builtin:spheres", "--views", "front", "-o", (out / "{scene}.png").string(), "-o",
          (out / "{scene}.png").string()},
         "twice"},
        {{"builtin:spheres", "builtin:teapot", "--frames", "0-1", "-o", (out / "{scene}.exr").string()},
         "twice"},
        {{"builtin:spheres", "--views", "front", "-o", (out / "{scne}.png").string()}, "{scne}"},
        {{"builtin:spheres", "--views", "orbit:0"}, "orbit:0"},
        {{"builtin:spheres", "--views", "sideways"}, "sideways"},
        {{"builtin:spheres", "--views", "front", "--look-at", "0,0,5,0,0,0,0,1,0"}, "--views"},
        {{"builtin:spheres", "builtin:teapot", "--compare", "ref.exr"}, "--compare"},
        {{(dir / "nothing*.gltf").string()}, "matches no"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {"render"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const auto r = runLantern(args);
        EXPECT_EQ(r.exitCode, 2) << c.says << ": " << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << c.says << ": something was written";
    }
    // {index} (the scene's position) tells files of the same name apart.
    const auto r = runLantern({"render", a.string(), b.string(), "--dry-run", "-o",
                               (out / "{index}_{scene}.png").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("would write " + (out / "0_same.png").string()), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("would write " + (out / "1_same.png").string()), std::string::npos) << r.out;
}

TEST(Batch, OneDeviceRendersTheWholeBatch) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto r = runLantern(small({"render", "builtin:spheres", triangle(dir, "a").string(),
                                     triangle(dir, "b", 0.3f).string(), "--views", "front,top",
                                     "-v", "-o", (dir / "{scene}_{view}.png").string()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(lines(r.out).size(), 6u);
    // The engine logs each Vulkan device it creates ("info: device: NAME"); the command names
    // the one it renders on ("lantern: device:").
    EXPECT_EQ(count(r.err, "info: device: "), 1u) << r.err;
    EXPECT_EQ(count(r.err, "lantern: device: "), 1u) << r.err;
}

TEST(Batch, APoseFileRendersWhatTheSameLookAtRendersAlone) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    // The same pose twice: as a look_at, and as the camera_to_world of a camera at (0,0,6)
    // looking down -Z (the identity rotation).
    std::ofstream(dir / "poses.json") << R"([
        {"name": "near", "look_at": {"eye": [0, 0, 6], "center": [0, 0, 0], "up": [0, 1, 0]}},
        {"name": "matrix", "camera_to_world": [1,0,0,0, 0,1,0,0, 0,0,1,6, 0,0,0,1]},
        {"look_at": {"eye": [4, 3, 4], "center": [0, 0, 0]}, "yfov_deg": 30, "near": 0.5, "far": 50}
    ])";
    auto r = runLantern(small({"render", "builtin:spheres", "--views", (dir / "poses.json").string(),
                               "-o", (dir / "b" / "{view}.exr").string()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(files(dir / "b"), (std::set<std::string>{"near.exr", "matrix.exr", "pose2.exr"}));
    r = runLantern(small({"render", "builtin:spheres", "--look-at", "0,0,6,0,0,0,0,1,0",
                          "--perspective", "45,1,0.01,inf", "-o", (dir / "alone.exr").string()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto alone = lantern::readExr(dir / "alone.exr");
    auto near = lantern::readExr(dir / "b" / "near.exr");
    auto matrix = lantern::readExr(dir / "b" / "matrix.exr");
    ASSERT_TRUE(alone && near && matrix);
    EXPECT_EQ(lantern::test::maxAbsDifference(*alone, *near), 0.0f);
    EXPECT_EQ(lantern::test::maxAbsDifference(*alone, *matrix), 0.0f);
    EXPECT_GT(lantern::test::countCovered(*near), 0u);
    // A pose that is not rigid, or that lacks a camera, is refused naming the pose.
    std::ofstream(dir / "bad.json") << R"([{"name": "s", "camera_to_world": [2,0,0,0, 0,1,0,0, 0,0,1,6, 0,0,0,1]}])";
    r = runLantern(small({"render", "builtin:spheres", "--views", (dir / "bad.json").string(),
                          "-o", (dir / "c" / "{view}.exr").string()}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("[0].camera_to_world: must be a rigid transform"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "c"));
}

TEST(Batch, GlobsAndListsAreExpandedInOrderAndConfinedToTheirFolder) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    const auto dir = testOutputDir();
    const auto scenes = dir / "scenes";
    fs::create_directories(scenes);
    fs::create_directories(dir / "elsewhere");
    triangle(scenes, "c");
    triangle(scenes, "a", 0.2f);
    triangle(scenes, "b", 0.4f);
    std::ofstream(scenes / "notes.txt") << "not a scene";
    triangle(dir / "elsewhere", "secret");
    fs::create_symlink(dir / "elsewhere" / "secret.gltf", scenes / "link.gltf");
    // The glob: the .gltf files sorted; the link leading outside the folder fails at its turn.
    auto r = runLantern(small({"render", (scenes / "*.gltf").string(), "-o",
                               (dir / "g" / "{scene}.png").string()}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    std::vector<std::string> order;
    for (const auto& l : lines(r.out)) order.push_back(fs::path(l).stem().string());
    EXPECT_EQ(order, (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_NE(r.err.find("link.gltf: " + (scenes / "*.gltf").string() + ": leads outside"),
              std::string::npos) << r.err;
    // A list: paths relative to its folder, in its order, comments and blank lines skipped;
    // ".." and paths out of the folder are refused unless --allow-folder admits them.
    std::ofstream(scenes / "list.txt") << "# the batch\nc.gltf\n\n  a.gltf\nbuiltin:spheres\n"
                                       << "../elsewhere/secret.gltf\n" << (scenes / "b.gltf").string() << "\n";
    r = runLantern(small({"render", "@" + (scenes / "list.txt").string(), "-o",
                          (dir / "l" / "{scene}.png").string()}));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    order.clear();
    for (const auto& l : lines(r.out)) order.push_back(fs::path(l).stem().string());
    EXPECT_EQ(order, (std::vector<std::string>{"c", "a", "spheres", "b"}));
    EXPECT_NE(r.err.find("list.txt:6: leads outside"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("4 rendered, 0 skipped, 1 failed of 5 jobs"), std::string::npos) << r.err;
    r = runLantern(small({"render", "--list", (scenes / "list.txt").string(), "--allow-folder",
                          dir.string(), "-o", (dir / "l" / "{scene}.png").string()}));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(lines(r.out), std::vector<std::string>{(dir / "l" / "secret.png").string()});
    // A list that is missing, or a folder, is refused input (exit 1) naming it; nothing runs.
    for (const fs::path& bad : {scenes / "missing.txt", scenes}) {
        r = runLantern(small({"render", "@" + bad.string(), "-o", (dir / "m" / "{scene}.png").string()}));
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find(bad.string() + ": --list: "), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "m"));
    }
}

TEST(Batch, AMillionJobsAreRefusedBeforeThePlan) {
    // 2 scenes x 3600 views x 16 000 001 frames: refused at once, not planned (it used to run
    // out of memory); 4 x 65 536 jobs is the most a batch plans.
    const auto dir = testOutputDir();
    auto r = runLantern({"render", "builtin:spheres", "builtin:teapot", "--views", "orbit:3600",
                         "--frames", "0-16000000", "--dry-run", "-o",
                         (dir / "{scene}_{view}_{frame}.png").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("the batch has 2 scenes x 3600 views x 16000001 frames, more than 262144 "
                         "jobs"),
              std::string::npos) << r.err;
    const std::vector<std::string> four{"render",   "builtin:spheres", "builtin:teapot",
                                        "builtin:teapots", "builtin:default", "--dry-run",
                                        "-o", (dir / "{scene}_{frame}.png").string(),
                                        "--frames"};
    auto args = four;
    args.push_back("0-65536");
    r = runLantern(args);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    args.back() = "1-65536";
    r = runLantern(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("dry run: batch of 262144 jobs"), std::string::npos);
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Batch, ADryRunListsTheJobsAndWritesNothing) {
    const auto dir = testOutputDir();
    const auto r = runLantern(small({"render", "builtin:spheres", "builtin:teapot", "--views",
                                     "orbit:4", "--shard", "1/3", "--dry-run", "-o",
                                     (dir / "out" / "{scene}_{view}.png").string()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // 8 jobs; shard 1/3 takes positions 1, 4 and 7.
    EXPECT_NE(r.out.find("batch of 3 jobs (2 scenes x 4 views x 1 frames, shard 1/3)"),
              std::string::npos) << r.out;
    for (const char* name : {"spheres_orbit1.png", "teapot_orbit0.png", "teapot_orbit3.png"})
        EXPECT_NE(r.out.find(name), std::string::npos) << name << r.out;
    EXPECT_FALSE(fs::exists(dir / "out"));
    // '#' runs of the template are the frame; a '#' in a file name stays.
    const auto h = runLantern({"render", (dir / "a#1.gltf").string(), "--frames", "2-3",
                               "--dry-run", "-o", (dir / "out" / "{scene}_##.png").string()});
    ASSERT_EQ(h.exitCode, 0) << h.err;
    EXPECT_NE(h.out.find("would write " + (dir / "out" / "a#1_03.png").string()), std::string::npos) << h.out;
}

}  // namespace
