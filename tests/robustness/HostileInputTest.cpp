// HostileInputTest: the hostile corpus of docs/robustness.md, generated here (none of it is a
// file in the tree): planted symlinks and dot-files beside outputs, names at the file system's limit,
// URIs that escape the scene's folder through symlinks or name folders and FIFOs, small files
// that ask for gigabytes, numbers that would become infinite, integers that are not, deep
// and wide node graphs, and command-line values out of range. Each case states its expected
// outcome: a refusal naming the file, the object and the problem (exit 1 from the command), or
// success without harm; never a crash, hang, escape or silent change.
#include "../unit/GltfTestSupport.h"

#include "io/AtomicFile.h"
#include "io/gltf/GltfInternal.h"

#include <lantern/Io.h>
#include <lantern/Scene.h>
#include <lantern/Sequence.h>

#include <gtest/gtest.h>

#include <chrono>
#include <climits>
#include <fstream>
#include <set>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace lantern {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::GltfBuilder;
using test::loadCapturing;
using test::refusedWith;

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeText(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

// The PID of a process that has ended (a reaped child), for "stale" temporaries.
long deadPid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return long(child);
}

Image smallImage() {
    Image img(4, 2);
    for (float& v : img.rgba) v = 0.5f;
    return img;
}

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// --- Temporary files ---------------------------------------------------------------------

TEST(HostileOutput, APlantedSymlinkAtTheTemporaryNameIsNeverFollowed) {
    const fs::path dir = test::testOutputDir();
    const fs::path victim = dir / "victim.txt";
    writeText(victim, "precious");
    const fs::path out = dir / "out.png";
    io::AtomicFile file(out);
    // The attacker knows the name (here: asks for it) and plants a link there before open().
    fs::create_symlink(victim, file.temporaryPath());
    const fs::path planted = file.temporaryPath();
    // And at the name the old scheme predicted.
    fs::create_symlink(victim, dir / (".out.png.tmp-" + std::to_string(::getpid()) + "-0"));
    const std::string bytes = "new image bytes";
    ASSERT_TRUE(file.writeAll(bytes.data(), bytes.size()));
    ASSERT_TRUE(file.commit());
    EXPECT_EQ(readText(victim), "precious") << "the planted link was followed";
    EXPECT_EQ(readText(out), bytes);
    EXPECT_TRUE(fs::is_symlink(planted)) << "a file Lantern did not create was removed";
    EXPECT_NE(file.temporaryPath(), planted);
}

TEST(HostileOutput, TemporaryNamesAreUnpredictable) {
    std::set<std::string> names;
    for (int i = 0; i < 100; ++i) names.insert(io::AtomicFile("x/out.exr").temporaryPath().string());
    EXPECT_EQ(names.size(), 100u);
}

TEST(HostileOutput, CleanupRemovesOnlyLanternsOwnStaleTemporaries) {
    const fs::path dir = test::testOutputDir();
    const fs::path victim = dir / "victim.txt";
    writeText(victim, "precious");
    const long dead = deadPid();
    // A user's own files whose names contain ".tmp-" (the old pattern removed them).
    const std::vector<std::string> users = {
        ".notes.tmp-1", ".out.exr.tmp-" + std::to_string(dead) + "-0", ".bashrc.tmp-x",
        io::temporaryName("out.exr", dead, 0x1234) + "x", // not exactly the pattern
    };
    for (const auto& n : users) writeText(dir / n, "mine");
    // A symlink with exactly Lantern's pattern: not a regular file, never touched.
    const std::string link = io::temporaryName("out.exr", dead, 0xabcdef);
    fs::create_symlink(victim, dir / link);
    // A temporary of a live writer (this process).
    const std::string live = io::temporaryName("out.exr", ::getpid(), 0x42);
    writeText(dir / live, "in progress");
    // A real stale one: Lantern's pattern, a dead writer.
    const std::string stale = io::temporaryName("out.exr", dead, 0x5555);
    writeText(dir / stale, "left by a killed run");

    EXPECT_EQ(io::removeStaleTemporariesIn(dir), 1u);
    EXPECT_FALSE(fs::exists(dir / stale));
    for (const auto& n : users) EXPECT_TRUE(fs::exists(dir / n)) << n << " was deleted";
    EXPECT_TRUE(fs::is_symlink(dir / link));
    EXPECT_TRUE(fs::exists(dir / live));
    EXPECT_EQ(readText(victim), "precious");
}

TEST(HostileOutput, OutputNamesUpToTheFileSystemLimitWork) {
    const fs::path dir = test::testOutputDir();
    const long limit = ::pathconf(dir.c_str(), _PC_NAME_MAX);
    ASSERT_GT(limit, 10);
    for (std::size_t length : {std::size_t(200), std::size_t(250), std::size_t(limit)}) {
        const std::string name = std::string(length - 4, 'n') + ".png";
        EXPECT_LE(io::temporaryName(name, 4194304, ~0ull).size(), std::size_t(NAME_MAX));
        const fs::path out = dir / name;
        auto written = writeImage(out, smallImage());
        ASSERT_TRUE(written) << length << ": " << written.error().describe();
        EXPECT_TRUE(fs::is_regular_file(out)) << length;
        // The matching cleanup recognises its (shortened) temporary names.
        const std::string tmp = io::temporaryName(name, deadPid(), 7);
        writeText(dir / tmp, "stale");
        EXPECT_EQ(io::removeStaleTemporaries(out), 1u) << length;
    }
    auto tooLong = writeImage(dir / (std::string(std::size_t(limit) + 1, 'n') + ".png"), smallImage());
    ASSERT_FALSE(tooLong);
    EXPECT_NE(tooLong.error().message.find("longer than the file system allows"), std::string::npos)
        << tooLong.error().describe();
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos)
            << "left behind: " << e.path();
}

// --- Frame patterns and ranges -------------------------------------------------------------

TEST(HostileSequence, LongHashRunsGiveDistinctFullLengthNames) {
    const std::string pattern = "out/f_" + std::string(40, '#') + ".exr";
    std::set<std::string> names;
    for (int frame : {0, 1, 2, 99, INT_MAX}) {
        const std::string name = expandFramePattern(pattern, frame);
        EXPECT_EQ(name.size(), pattern.size()) << name;
        names.insert(name);
    }
    EXPECT_EQ(names.size(), 5u);
    EXPECT_EQ(expandFramePattern("f_##", 12345), "f_12345");
}

TEST(HostileSequence, RangesNearIntMaxAreBoundedAndEnd) {
    const auto start = std::chrono::steady_clock::now();
    auto huge = parseFrameRange("0-2147483647");
    ASSERT_FALSE(huge);
    EXPECT_NE(huge.error().message.find("more than"), std::string::npos) << huge.error().describe();
    auto top = parseFrameRange("2147483600-2147483647");
    ASSERT_TRUE(top);
    EXPECT_EQ(shardFrames(*top, Shard{}).size(), 48u);
    EXPECT_EQ(shardFrames(*top, Shard{1, 2}).size(), 24u);
    // Built by hand past the parser: still bounded, still ends.
    EXPECT_EQ(shardFrames(FrameRange{0, INT_MAX}, Shard{0, 1 << 20}).size(),
              std::size_t(kMaxSequenceFrames) >> 20);
    EXPECT_FALSE(parseFrameList("0-2147483647"));
    EXPECT_LT(secondsSince(start), 10.0);
}

// --- Scene graphs: linear passes -----------------------------------------------------------

Scene chainScene(std::size_t n) {
    Scene s;
    s.nodes.resize(n);
    for (std::size_t i = 0; i + 1 < n; ++i) s.nodes[i].children = {int(i + 1)};
    s.roots.push_back(SceneRoot{"chain", {0}, std::nullopt});
    return s;
}

TEST(HostileGraph, AMillionNodeChainAndFlatSceneValidateInSeconds) {
    constexpr std::size_t n = 1'000'000;
    Scene chain = chainScene(n);
    auto t = std::chrono::steady_clock::now();
    auto valid = chain.validate();
    const double chainSeconds = secondsSince(t);
    EXPECT_TRUE(valid) << valid.error().describe();
    Scene flat;
    flat.nodes.resize(n);
    SceneRoot root;
    for (std::size_t i = 0; i < n; ++i) root.nodes.push_back(int(i));
    flat.roots.push_back(root);
    t = std::chrono::steady_clock::now();
    valid = flat.validate();
    const double flatSeconds = secondsSince(t);
    EXPECT_TRUE(valid) << valid.error().describe();
    std::cout << "validate: 1,000,000-node chain " << chainSeconds << " s, flat " << flatSeconds
              << " s\n";
    EXPECT_LT(chainSeconds, 5.0);
    EXPECT_LT(flatSeconds, 5.0);
    // A cycle at the end of the long chain is still found.
    chain.nodes[n - 1].children = {int(n / 2)};
    chain.roots[0].nodes = {0};
    auto cyclic = chain.validate();
    ASSERT_FALSE(cyclic);
    EXPECT_NE(cyclic.error().describe().find("already has parent"), std::string::npos)
        << cyclic.error().describe();
    // A pure cycle (no node reaches a root): every node has one parent.
    Scene ring = chainScene(1000);
    ring.nodes[999].children = {0};
    ring.roots.clear();
    ring.roots.push_back(SceneRoot{"none", {}, std::nullopt});
    auto ringValid = ring.validate();
    ASSERT_FALSE(ringValid);
    EXPECT_NE(ringValid.error().message.find("cycle"), std::string::npos) << ringValid.error().describe();
}

TEST(HostileGraph, AMillionNodeChainGltfLoadsInSeconds) {
    constexpr int n = 1'000'000;
    const fs::path dir = test::testOutputDir();
    std::string text = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)";
    for (int i = 0; i < n; ++i) {
        text += i + 1 < n ? R"({"children":[)" + std::to_string(i + 1) + "]}," : "{}";
    }
    text += "]}";
    writeText(dir / "chain.gltf", text);
    const auto t = std::chrono::steady_clock::now();
    auto loaded = loadCapturing(dir / "chain.gltf");
    const double seconds = secondsSince(t);
    ASSERT_TRUE(loaded.scene) << loaded.scene.error().describe();
    EXPECT_EQ(loaded.scene->nodes.size(), std::size_t(n));
    std::cout << "load: 1,000,000-node chain glTF (" << text.size() << " bytes) " << seconds << " s\n";
    EXPECT_LT(seconds, 60.0);
}

// --- The scene's folder ----------------------------------------------------------------------

// scene/ holds scene.gltf whose buffer (or image) URI is `uri`; outside/ holds a secret.
struct Confined {
    fs::path dir, scene, outside;
    explicit Confined(const fs::path& root) : dir(root / "scene"), outside(root / "outside") {
        fs::create_directories(dir);
        fs::create_directories(outside);
        writeText(outside / "secret.bin", "SECRET-BYTES-0123456789AB");
    }
    fs::path writeWithBufferUri(const std::string& uri) {
        GltfBuilder b;
        b.addTriangle();
        json doc = b.doc;
        doc["buffers"] = json::array({json{{"uri", uri}, {"byteLength", 24}}});
        scene = dir / "scene.gltf";
        writeText(scene, doc.dump());
        return scene;
    }
};

TEST(HostileFolder, ASymlinkLeadingOutsideIsRefusedAndNoByteQuoted) {
    Confined c(test::testOutputDir());
    fs::create_symlink(c.outside / "secret.bin", c.dir / "data.bin");
    auto o = loadCapturing(c.writeWithBufferUri("data.bin"));
    EXPECT_TRUE(refusedWith(o, "buffers[0].uri", "leads outside the scene's folder"));
    if (!o.scene) {
        EXPECT_EQ(o.scene.error().describe().find("SECRET"), std::string::npos);
    }
    // Through a symlinked folder as well.
    fs::create_directory_symlink(c.outside, c.dir / "sub");
    auto viaFolder = loadCapturing(c.writeWithBufferUri("sub/secret.bin"));
    EXPECT_TRUE(refusedWith(viaFolder, "buffers[0].uri", "leads outside the scene's folder"));
    // A symlink that stays inside the folder is fine.
    GltfBuilder inside;
    inside.addTriangle();
    const fs::path real = inside.write(c.dir, "real", GltfBuilder::Storage::External);
    fs::rename(c.dir / "real.bin", c.dir / "target.bin");
    fs::create_symlink("target.bin", c.dir / "real.bin");
    auto ok = loadCapturing(real);
    EXPECT_TRUE(ok.scene) << (ok.scene ? "" : ok.scene.error().describe());
}

TEST(HostileFolder, AnAllowedFolderAdmitsParentUrisAndLinksIntoItAndNothingElse) {
    const fs::path root = test::testOutputDir();
    const fs::path shared = root / "shared", dir = root / "scene", other = root / "other";
    for (const fs::path& d : {shared, dir, other}) fs::create_directories(d);
    GltfBuilder b;
    b.addTriangle();
    const fs::path written = b.write(shared, "tri", GltfBuilder::Storage::External);
    fs::copy_file(shared / "tri.bin", other / "tri.bin");
    fs::create_symlink(shared / "tri.bin", dir / "link.bin");
    auto sceneWithUri = [&](const std::string& uri) {
        json doc = json::parse(readText(written));
        doc["buffers"][0]["uri"] = uri;
        writeText(dir / "scene.gltf", doc.dump());
        return dir / "scene.gltf";
    };
    LoadOptions allow;
    allow.allowedFolders = {shared};
    // By default neither "../" nor a link may leave the scene's folder.
    EXPECT_TRUE(refusedWith(loadCapturing(sceneWithUri("../shared/tri.bin")), "buffers[0].uri", "contains \"..\""));
    EXPECT_TRUE(refusedWith(loadCapturing(sceneWithUri("link.bin")), "buffers[0].uri", "leads outside"));
    // Allowed: both reach the shared folder.
    for (const char* uri : {"../shared/tri.bin", "link.bin"}) {
        auto loaded = loadGltf(sceneWithUri(uri), allow);
        EXPECT_TRUE(loaded) << uri << ": " << (loaded ? "" : loaded.error().describe());
    }
    // ... and nowhere else: not a sibling folder, not through "..", not the secret of Confined.
    auto sibling = loadGltf(sceneWithUri("../other/tri.bin"), allow);
    ASSERT_FALSE(sibling);
    EXPECT_NE(sibling.error().message.find("leads outside the scene's folder and the allowed folders"), std::string::npos)
        << sibling.error().describe();
    EXPECT_FALSE(loadGltf(sceneWithUri("../shared/../other/tri.bin"), allow));
    EXPECT_FALSE(loadGltf(sceneWithUri("/etc/hostname"), allow)) << "absolute paths stay refused";
    // The command line: --allow-folder on render, view and info.
    const fs::path scene = sceneWithUri("../shared/tri.bin");
    EXPECT_EQ(test::runLantern({"info", scene.string()}).exitCode, 1);
    const auto r = test::runLantern({"info", scene.string(), "--allow-folder", shared.string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(test::runLantern({"info", scene.string(), "--allow-folder", (root / "missing").string()}).exitCode, 1);
}

TEST(HostileFolder, AFolderSwappedForALinkBetweenTheCheckAndTheReadIsNotFollowed) {
    // The race a stranger with write access to the scene's folder could win: the URI
    // "sub/data.bin" is checked while sub/ is a real folder, then sub/ is replaced by a link
    // to a folder outside holding a secret data.bin. Opening the checked real path (even with
    // O_NOFOLLOW, which guards only the last component) would read the secret; the confined
    // read opens each component without following links and refuses.
    const fs::path root = test::testOutputDir();
    fs::create_directories(root / "scene" / "sub");
    fs::create_directories(root / "outside");
    writeText(root / "scene" / "sub" / "data.bin", "inside");
    writeText(root / "outside" / "data.bin", "SECRET");
    auto checked = io::resolveConfined(root / "scene", "sub/data.bin", 1 << 20);
    ASSERT_TRUE(checked) << checked.error().describe();
    auto before = io::readConfinedFile(*checked, 1 << 20);
    ASSERT_TRUE(before) << before.error().describe();
    EXPECT_EQ(std::string(before->begin(), before->end()), "inside");

    fs::rename(root / "scene" / "sub", root / "scene" / "old");
    fs::create_directory_symlink(root / "outside", root / "scene" / "sub");
    // What the previous code did: the checked real path, O_NOFOLLOW on its last component.
    auto naive = io::readRegularFile(checked->real(), 1 << 20, true);
    ASSERT_TRUE(naive) << "the swap must make the naive read reach the secret";
    EXPECT_EQ(std::string(naive->begin(), naive->end()), "SECRET");
    auto after = io::readConfinedFile(*checked, 1 << 20);
    ASSERT_FALSE(after) << "read " << std::string(after->begin(), after->end());
    EXPECT_NE(after.error().message.find("a symbolic link appeared in its path"), std::string::npos)
        << after.error().describe();
    // The file itself swapped for a link is refused the same way.
    fs::remove(root / "scene" / "sub");
    fs::rename(root / "scene" / "old", root / "scene" / "sub");
    fs::remove(root / "scene" / "sub" / "data.bin");
    fs::create_symlink(root / "outside" / "data.bin", root / "scene" / "sub" / "data.bin");
    EXPECT_FALSE(io::readConfinedFile(*checked, 1 << 20));
}

TEST(HostileFolder, FoldersFifosAndDevicesAreRefusedWithoutWaiting) {
    Confined c(test::testOutputDir());
    fs::create_directory(c.dir / "folder.bin");
    ASSERT_EQ(::mkfifo((c.dir / "fifo.bin").c_str(), 0600), 0);
    fs::create_symlink("/dev/zero", c.dir / "zero.bin");
    const auto start = std::chrono::steady_clock::now();
    EXPECT_TRUE(refusedWith(loadCapturing(c.writeWithBufferUri("folder.bin")), "buffers[0].uri",
                            "is a folder, not a regular file"));
    EXPECT_TRUE(refusedWith(loadCapturing(c.writeWithBufferUri("fifo.bin")), "buffers[0].uri",
                            "is a FIFO, not a regular file"));
    EXPECT_TRUE(refusedWith(loadCapturing(c.writeWithBufferUri("zero.bin")), "buffers[0].uri",
                            "leads outside the scene's folder"));
    // The scene file itself named as a FIFO or a folder.
    auto fifoScene = loadCapturing(c.dir / "fifo.bin");
    ASSERT_FALSE(fifoScene.scene);
    EXPECT_NE(fifoScene.scene.error().message.find("is a FIFO"), std::string::npos)
        << fifoScene.scene.error().describe();
    auto folderScene = loadCapturing(c.dir);
    ASSERT_FALSE(folderScene.scene);
    EXPECT_NE(folderScene.scene.error().message.find("is a folder"), std::string::npos);
    EXPECT_LT(secondsSince(start), 10.0);
}

TEST(HostileFolder, MessagesQuoteUrisPrintably) {
    Confined c(test::testOutputDir());
    auto o = loadCapturing(c.writeWithBufferUri(std::string("a\x01\x1b[2Jb") + std::string(300, 'z')));
    ASSERT_FALSE(o.scene);
    const std::string text = o.scene.error().describe();
    for (char ch : text) EXPECT_TRUE(ch >= 32 && ch < 127) << "raw byte " << int(ch) << " in " << text;
    EXPECT_LT(text.size(), 400u) << text;
}

// --- Memory from a small file ------------------------------------------------------------------

TEST(HostileMemory, ManyLargeAccessorsFromATinyFileExceedTheTotalBudget) {
    // Accessors without a buffer view are zeros the loader allocates: each one fits the
    // bound alone (2M x 12 bytes < 64 MiB), together they would not (at the default bound of
    // 1 GiB, the same file with counts of 80M asks for 3.8 GB).
    GltfBuilder b;
    b.doc["accessors"] = json::array();
    for (int i = 0; i < 4; ++i)
        b.doc["accessors"].push_back(json{{"componentType", 5126},
                                          {"count", 2'000'000},
                                          {"type", "VEC3"},
                                          {"min", {0, 0, 0}},
                                          {"max", {0, 0, 0}}});
    json prims = json::array();
    for (int i = 0; i < 4; ++i) prims.push_back(json{{"attributes", {{"POSITION", i}}}});
    b.doc["meshes"] = json::array({json{{"primitives", prims}}});
    b.doc["nodes"] = json::array({json{{"mesh", 0}}});
    b.doc["scenes"][0]["nodes"] = {0};
    const fs::path file = b.write(test::testOutputDir(), "tiny");
    const auto size = fs::file_size(file);
    EXPECT_LT(size, 2048u);
    auto o = loadCapturing(file, std::uint64_t(64) << 20);
    ASSERT_FALSE(o.scene);
    EXPECT_NE(o.scene.error().message.find("budget"), std::string::npos) << o.scene.error().describe();
    EXPECT_NE(o.scene.error().object.find("accessors["), std::string::npos) << o.scene.error().describe();
}

// A PNG whose header declares `side` x `side` RGBA pixels (the rest is no valid image data:
// the refusal must come from the header, before decoding).
std::vector<unsigned char> pngHeader(std::uint32_t side) {
    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13,
                                      'I', 'H', 'D', 'R'};
    for (int k = 3; k >= 0; --k) png.push_back((side >> (8 * k)) & 0xff);
    for (int k = 3; k >= 0; --k) png.push_back((side >> (8 * k)) & 0xff);
    for (int v : {8, 6, 0, 0, 0}) png.push_back(static_cast<unsigned char>(v));
    for (int i = 0; i < 4; ++i) png.push_back(0); // CRC (stb does not check it)
    for (int v : {0, 0, 0, 0, int('I'), int('E'), int('N'), int('D'), 0xae, 0x42, 0x60, 0x82}) png.push_back(static_cast<unsigned char>(v));
    return png;
}

TEST(HostileMemory, AnImageDeclaringSixteenKSquaredIsRefusedFromItsHeader) {
    const fs::path dir = test::testOutputDir();
    const auto png = pngHeader(16384);
    std::ofstream(dir / "huge.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    GltfBuilder b;
    b.addTriangle();
    b.doc["images"] = json::array({json{{"uri", "huge.png"}}});
    b.doc["textures"] = json::array({json{{"source", 0}}});
    b.doc["materials"] =
        json::array({json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    auto o = loadCapturing(b.write(dir, "huge"));
    EXPECT_TRUE(refusedWith(o, "images[0]", "16384x16384"));
}

// --- Numbers ------------------------------------------------------------------------------------

struct NumberCase {
    const char* name;
    std::function<void(json&)> edit;
    const char* object;
    const char* fragment;
};

TEST(HostileNumbers, IntegersOutOfRangeAndHugeValuesAreRefusedWithTheObjectNamed) {
    const std::vector<NumberCase> cases = {
        {"mesh 2^32", [](json& d) { d["nodes"][0]["mesh"] = 4294967296ull; }, "nodes[0].mesh",
         "more than the largest index"},
        {"mesh 0.5", [](json& d) { d["nodes"][0]["mesh"] = 0.5; }, "nodes[0].mesh", "not an integer"},
        {"byteOffset -4", [](json& d) { d["bufferViews"][0]["byteOffset"] = -4; },
         "bufferViews[0].byteOffset", "must be 0 or more"},
        {"child 1.5", [](json& d) { d["nodes"][0]["children"] = {1.5}; }, "nodes[0].children[0]",
         "not an integer"},
        {"attribute -1", [](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = -1; },
         "meshes[0].primitives[0].attributes.POSITION", "must be 0 or more"},
        {"translation 1e300", [](json& d) { d["nodes"][0]["translation"] = {1e300, 0, 0}; },
         "nodes[0].translation[0]", "infinite"},
        {"scale 1e300", [](json& d) { d["nodes"][0]["scale"] = {1, 1e300, 1}; }, "nodes[0].scale[1]",
         "infinite"},
        {"emissive 1e300",
         [](json& d) {
             d["materials"] = json::array({json{{"emissiveFactor", {1e300, 0, 0}}}});
             d["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "materials[0].emissiveFactor[0]", "infinite"},
        {"light 1e300",
         [](json& d) {
             d["extensionsUsed"] = {"KHR_lights_punctual"};
             d["extensions"]["KHR_lights_punctual"]["lights"] =
                 json::array({json{{"type", "point"}, {"intensity", 1e300}}});
         },
         "extensions.KHR_lights_punctual.lights[0].intensity", "infinite"},
        {"aspectRatio 0",
         [](json& d) {
             d["cameras"] = json::array(
                 {json{{"type", "perspective"},
                       {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", 0}}}}});
         },
         "cameras[0].perspective.aspectRatio", "greater than 0"},
    };
    const fs::path dir = test::testOutputDir();
    for (const auto& c : cases) {
        GltfBuilder b;
        b.addTriangle();
        c.edit(b.doc);
        auto o = loadCapturing(b.write(dir, "case"));
        EXPECT_TRUE(refusedWith(o, c.object, c.fragment)) << c.name;
    }
    // And the same file unedited loads (the cases fail for their edit alone).
    GltfBuilder b;
    b.addTriangle();
    auto plain = loadCapturing(b.write(dir, "plain"));
    EXPECT_TRUE(plain.scene) << plain.scene.error().describe();
}

// --- The command line ----------------------------------------------------------------------------

TEST(HostileCli, NumericOptionsOutOfRangeExitOneAndTheHelpStatesTheRange) {
    const std::string out = (test::testOutputDir() / "f_####.exr").string();
    struct Case {
        std::vector<std::string> args;
        const char* fragment;
    };
    const std::vector<Case> cases = {
        {{"render", "builtin:spheres", "--encoder-threads", "1000000000", "--frames", "0-1", "-o", out},
         "--encoder-threads"},
        {{"render", "builtin:spheres", "--frames", "0-2147483647", "-o", out}, "more than"},
        {{"render", "builtin:spheres", "--frames", "2147483000-2147483647", "--shard", "0/1", "-o",
          out, "--width", "0"},
         "--width"},
        {{"render", "builtin:spheres", "--max-size", "-1"}, "--max-size"},
        {{"info", "builtin:spheres", "--max-size", "18446744073709551615"}, "--max-size"},
        {{"render", "builtin:spheres", "--width", "99999999999"}, "--width"},
        {{"render", "builtin:spheres", "--time", "nan"}, "--time"},
    };
    for (const auto& c : cases) {
        const auto start = std::chrono::steady_clock::now();
        const auto r = test::runLantern(c.args);
        std::string line;
        for (const auto& a : c.args) line += a + " ";
        EXPECT_EQ(r.exitCode, 1) << line << "\n" << r.err;
        EXPECT_NE(r.err.find(c.fragment), std::string::npos) << line << "\n" << r.err;
        EXPECT_LT(secondsSince(start), 30.0) << line;
    }
    const auto help = test::runLantern({"render", "--help"});
    EXPECT_NE(help.out.find("0 to 256"), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("1 to 16384"), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("1 to 68719476736"), std::string::npos) << help.out;
}

TEST(HostileCli, AMissingSceneExitsOneNamingThePathOnce) {
    const std::string missing = (test::testOutputDir() / "no-such-scene.gltf").string();
    const auto r = test::runLantern({"info", missing});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    const std::size_t first = r.err.find(missing);
    ASSERT_NE(first, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(missing, first + 1), std::string::npos) << "path printed twice: " << r.err;
    EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
}

} // namespace
} // namespace lantern
