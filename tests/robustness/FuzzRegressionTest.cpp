// Every input in tests/fuzz/regressions/ (hand-made adversarial files, and any input a fuzz run
// ever crashed on, kept with its fix) goes through the loader and, when it loads, through
// everything a render does before the GPU. The expectation is no crash, no hang, no sanitizer
// report (this runs under the asan preset too), and a refusal that names the file.
#include "TestSupport.h"

#include "io/GltfLoad.h"
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

} // namespace
