// Hostile glTF input: every file of ../shared/assets/gltf-invalid (the Khronos glTF-Validator's
// negative cases) is either refused with a message naming the file, the object and the problem
// (exit 1 from `lantern info`), or loaded safely; never a crash, hang or uncaught exception.
// The table says which, and why, for each file.
#include "GltfInvalidCases.h"
#include "TestSupport.h"

#include <lantern/Io.h>
#include <lantern/Renderer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

namespace {

using namespace lantern;
using lantern::test::InvalidCase;
using lantern::test::kInvalidCases;
using lantern::test::sharedDir;

std::filesystem::path invalidDir() { return sharedDir() / "assets" / "gltf-invalid"; }

std::vector<std::string> invalidFiles() {
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(invalidDir())) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb"))
            files.push_back(e.path().lexically_relative(invalidDir()).generic_string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

class GltfInvalid : public ::testing::Test {
protected:
    void SetUp() override {
        if (!std::filesystem::is_directory(invalidDir()))
            GTEST_SKIP() << "the shared assets are absent: " << invalidDir();
    }
};

TEST_F(GltfInvalid, TheTableCoversEveryFile) {
    const auto files = invalidFiles();
    EXPECT_EQ(files.size(), 151u);
    std::set<std::string> rows;
    for (const InvalidCase& c : kInvalidCases) EXPECT_TRUE(rows.insert(c.file).second) << "duplicate row " << c.file;
    for (const std::string& f : files) EXPECT_TRUE(rows.count(f)) << "no row for " << f;
    EXPECT_EQ(rows.size(), files.size());
}

TEST_F(GltfInvalid, EachFileIsRefusedWithItsReasonOrLoadedSafely) {
    std::map<std::string, const InvalidCase*> table;
    for (const InvalidCase& c : kInvalidCases) table[c.file] = &c;
    for (const std::string& file : invalidFiles()) {
        const auto path = invalidDir() / file;
        std::vector<std::string> warnings;
        LoadOptions options;
        options.log = [&](LogLevel, std::string_view m) { warnings.emplace_back(m); };
        const Result<Scene> scene = loadGltf(path, options);
        auto it = table.find(file);
        if (it == table.end()) {
            ADD_FAILURE() << "no row for " << file << ": "
                          << (scene ? std::string("loaded") : scene.error().describe());
            continue;
        }
        const InvalidCase& c = *it->second;
        SCOPED_TRACE(file);
        if (c.refused) {
            ASSERT_FALSE(scene) << "loaded; expected a refusal at " << c.object;
            const Error& e = scene.error();
            EXPECT_EQ(e.code, ErrorCode::InvalidInput) << e.describe();
            EXPECT_EQ(e.file, path.string());
            EXPECT_EQ(e.object, c.object) << e.describe();
            EXPECT_NE(e.message.find(c.fragment), std::string::npos)
                << "expected \"" << c.fragment << "\" in: " << e.describe();
            EXPECT_EQ(e.describe().find('\n'), std::string::npos) << e.describe();
        } else {
            ASSERT_TRUE(scene) << scene.error().describe();
            if (std::string_view(c.fragment) == lantern::test::kDrawsNothing) {
                EXPECT_TRUE(nothingToDraw(*scene)) << "the file draws something";
            } else if (*c.fragment) {
                const bool warned = std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) {
                    return w.find(c.fragment) != std::string::npos && w.find(path.string()) == 0;
                });
                EXPECT_TRUE(warned) << "expected a warning with \"" << c.fragment << "\"";
            }
            // Loaded safely: posing, bounds and frame planning work on it at several times.
            for (double t : {0.0, 0.5, 100.0}) {
                const Pose pose = evaluatePose(*scene, -1, t);
                (void)computeBounds(*scene, pose);
                auto report = explainScene(*scene, RenderOptions{}, t);
                EXPECT_TRUE(report) << report.error().describe();
            }
        }
    }
}

TEST_F(GltfInvalid, TheCommandExitsWith1AndNamesTheFileOrLoads) {
    for (const InvalidCase& c : kInvalidCases) {
        const auto path = invalidDir() / c.file;
        const auto r = lantern::test::runProcess({lantern::test::cliPath().string(), "info", path.string()}, {}, 60.0);
        SCOPED_TRACE(c.file);
        // Under the sanitizers a report also exits with 1: look for one explicitly.
        EXPECT_EQ(r.err.find("Sanitizer"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("runtime error"), std::string::npos) << r.err;
        if (c.refused) {
            EXPECT_EQ(r.exitCode, 1) << r.err;
            const std::string line = "lantern: error: " + path.string() + ": ";
            EXPECT_NE(r.err.find(line), std::string::npos) << r.err;
            EXPECT_TRUE(r.out.empty()) << r.out;
        } else {
            EXPECT_EQ(r.exitCode, 0) << r.err;
            EXPECT_NE(r.out.find("features:"), std::string::npos) << r.out;
        }
    }
}

} // namespace
