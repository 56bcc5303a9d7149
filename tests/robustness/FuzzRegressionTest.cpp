// Every input in tests/fuzz/regressions/ (hand-made adversarial files, and any input a fuzz run
// ever crashed on, kept with its fix) goes through the loader and, when it loads, through
// everything a render does before the GPU. The expectation is no crash, no hang, no sanitizer
// report (this runs under the asan preset too), and a refusal that names the file.
#include "TestSupport.h"

#include "io/gltf/GltfLoad.h"

#include <lantern/Io.h>
#include "render/FrameRender.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace {

using namespace lantern;

TEST(FuzzRegressions, EveryInputIsRefusedOrLoadedSafely) {
    const auto dir = test::sourceDir() / "tests" / "fuzz" / "regressions";
    ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
    // Inputs named valid-* are extreme but valid (they must load); all others must be refused.
    int inputs = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        SCOPED_TRACE(entry.path().filename().string());
        std::ifstream in(entry.path(), std::ios::binary);
        std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        ++inputs;
        // Resolve external URIs in a fresh empty folder, as the fuzz target does.
        const auto folder = test::testOutputDir();
        auto scene = gltf::loadGltfBytes(bytes, folder / entry.path().filename(), LoadOptions{});
        const bool valid = entry.path().filename().string().rfind("valid-", 0) == 0;
        EXPECT_EQ(bool(scene), valid) << (scene ? "loaded" : scene.error().describe());
        if (!scene) {
            EXPECT_NE(scene.error().file.find(entry.path().filename().string()), std::string::npos)
                << scene.error().describe();
            EXPECT_EQ(scene.error().describe().find('\n'), std::string::npos) << "one line";
            continue;
        }
        RenderOptions o;
        o.width = 32;
        o.height = 32;
        for (double t : {0.0, 1.0}) (void)render::planFrame(*scene, o, t);
    }
    EXPECT_GE(inputs, 10);
}

// The command-line fuzzer's inputs (tests/fuzz/CliFuzz.cpp): arguments one per line, given to
// `lantern render builtin:spheres ... --dry-run`. Its regressions (earlier command-line
// defects, docs/robustness.md, and anything it finds) and its seeds exit 0, 1 or 2, with one
// line of error at most and no sanitizer report; the seeds are valid, so they exit 0.
TEST(FuzzRegressions, CommandLineInputsExitCleanly) {
    int inputs = 0;
    for (const char* folder : {"cli-regressions", "cli-seeds"}) {
        const auto dir = test::sourceDir() / "tests" / "fuzz" / folder;
        ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
        for (const auto& entry : std::filesystem::directory_iterator(dir)) {
            SCOPED_TRACE(entry.path().filename().string());
            std::ifstream in(entry.path());
            std::vector<std::string> args{"render", "builtin:spheres"};
            for (std::string line; std::getline(in, line);)
                if (!line.empty()) args.push_back(line);
            args.push_back("--dry-run");
            // Run in the test's own (empty) folder: relative outputs would land there, and a
            // dry run writes none.
            std::vector<std::string> inFolder{"sh", "-c", "cd \"$0\" && exec \"$@\"",
                                              test::testOutputDir().string(),
                                              test::cliPath().string()};
            inFolder.insert(inFolder.end(), args.begin(), args.end());
            const auto run = test::runProcess(inFolder, {}, 60.0);
            ++inputs;
            EXPECT_GE(run.exitCode, 0) << run.err;
            EXPECT_LE(run.exitCode, std::string(folder) == "cli-seeds" ? 0 : 2) << run.err;
            EXPECT_EQ(run.err.find("Sanitizer"), std::string::npos) << run.err;
            EXPECT_EQ(run.err.find("terminate"), std::string::npos) << run.err;
            EXPECT_TRUE(std::filesystem::is_empty(test::testOutputDir()))
                << "a dry run wrote into its folder";
        }
    }
    EXPECT_GE(inputs, 10);
}

// The mesh fuzzers' regressions (tests/fuzz/mesh-regressions/: refused, or loaded when named
// valid-*) and seeds (tests/fuzz/mesh-seeds/FORMAT/: all load), through loadScene as files: an
// OBJ input's part after a "#MTL" line is its library m.mtl, as the OBJ fuzzer writes it.
TEST(FuzzRegressions, MeshInputsAreRefusedOrLoadedSafely) {
    const auto fuzz = test::sourceDir() / "tests" / "fuzz";
    std::vector<std::pair<std::filesystem::path, bool>> inputs;  // (file, must load)
    for (const auto& e : std::filesystem::directory_iterator(fuzz / "mesh-regressions"))
        inputs.emplace_back(e.path(), e.path().filename().string().rfind("valid-", 0) == 0);
    for (const auto& e : std::filesystem::recursive_directory_iterator(fuzz / "mesh-seeds"))
        if (e.is_regular_file()) inputs.emplace_back(e.path(), true);
    const auto folder = test::testOutputDir();
    for (const auto& [path, valid] : inputs) {
        SCOPED_TRACE(path.filename().string());
        std::ifstream in(path, std::ios::binary);
        std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        const std::size_t mtl = bytes.find("\n#MTL\n");
        if (mtl != std::string::npos) {
            std::ofstream(folder / "m.mtl", std::ios::binary) << bytes.substr(mtl + 6);
            bytes.resize(mtl + 1);
        }
        std::ofstream(folder / path.filename(), std::ios::binary) << bytes;
        auto scene = loadScene((folder / path.filename()).string());
        EXPECT_EQ(bool(scene), valid) << (scene ? "loaded" : scene.error().describe());
        if (!scene) {
            EXPECT_NE(scene.error().file.find(path.filename().string()), std::string::npos);
            EXPECT_EQ(scene.error().describe().find('\n'), std::string::npos) << "one line";
            continue;
        }
        RenderOptions o;
        o.width = 32;
        o.height = 32;
        (void)render::planFrame(*scene, o, 0.0);
    }
    EXPECT_GE(inputs.size(), 20u);
}

} // namespace
