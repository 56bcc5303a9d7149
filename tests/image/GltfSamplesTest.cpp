// The Khronos sample models of ../shared/assets/gltf-samples through the `lantern` command:
// each renders (64x64) with exit 0, no NaN/Inf and something drawn; `lantern info` reports the
// node and primitive counts written in the file; the animated ones differ at three times.
#include "../unit/GltfTestSupport.h"

#include <lantern/Io.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <regex>

namespace {

using namespace lantern;
using lantern::test::cliPath;
using lantern::test::GpuTest;
using lantern::test::runProcess;
using lantern::test::sharedDir;
using lantern::test::testOutputDir;

struct Sample {
    const char* file;                ///< relative to assets/gltf-samples
    std::vector<std::string> args;   ///< extra render options
    std::vector<double> times;       ///< rendered instants (three for animated models)
    bool drawn;                      ///< something covers the image
    const char* why;                 ///< the reason for a non-default row
};

const Sample kSamples[] = {
    {"Triangle/glTF-Embedded/Triangle.gltf", {}, {0}, true, ""},
    {"Triangle/glTF/Triangle.gltf", {}, {0}, true, ""},
    {"TriangleWithoutIndices/glTF-Embedded/TriangleWithoutIndices.gltf", {}, {0}, true, ""},
    {"TriangleWithoutIndices/glTF/TriangleWithoutIndices.gltf", {}, {0}, true, ""},
    {"SimpleMeshes/glTF-Embedded/SimpleMeshes.gltf", {}, {0}, true, ""},
    {"Box/glTF-Binary/Box.glb", {}, {0}, true, ""},
    {"Box/glTF-Embedded/Box.gltf", {}, {0}, true, ""},
    {"BoxInterleaved/glTF-Binary/BoxInterleaved.glb", {}, {0}, true, ""},
    {"BoxVertexColors/glTF-Embedded/BoxVertexColors.gltf", {}, {0}, true, ""},
    {"BoxAnimated/glTF-Embedded/BoxAnimated.gltf", {}, {0.0, 1.0, 2.5}, true, "two animations, 0 to 3.7 s"},
    {"AnimatedCube/glTF/AnimatedCube.gltf", {}, {0.0, 0.5, 1.2}, true, "rotation over 0 to 2 s"},
    {"AnimatedTriangle/glTF-Embedded/AnimatedTriangle.gltf", {}, {0.0, 0.25, 0.6}, true, "rotation over 0 to 1 s"},
    {"InterpolationTest/glTF/InterpolationTest.gltf", {}, {0.1, 0.4, 1.3}, true, "keys every 0.5 s"},
    {"Cameras/glTF-Embedded/Cameras.gltf", {}, {0}, true, ""},
    {"Cameras/glTF/Cameras.gltf", {"--camera", "1"}, {0}, true, "the orthographic camera"},
    {"MultipleScenes/glTF-Embedded/MultipleScenes.gltf", {"--scene", "0"}, {0}, true, "the non-default scene"},
    {"OrientationTest/glTF-Binary/OrientationTest.glb", {}, {0}, true, ""},
    {"SimpleSparseAccessor/glTF-Embedded/SimpleSparseAccessor.gltf", {}, {0}, true, ""},
    {"Suzanne/glTF/Suzanne.gltf", {}, {0}, true, ""},
    {"Duck/glTF-Binary/Duck.glb", {}, {0}, true, ""},
    {"BlenderIO_01_unlit/01_unlit.gltf", {}, {0}, true, ""},
    {"BlenderIO_01_alpha_blend/01_alpha_blend.gltf", {}, {0}, true, ""},
    {"BlenderIO_01_alpha_mask/01_alpha_mask.gltf",
     {"--look-at", "0,3,3,0,0,0,0,1,0"}, {0}, true,
     "a plane at y = 0: automatic framing (along -Z) sees it edge-on"},
    {"ZgltfLights/Lights.gltf", {}, {0}, false, "lights only, no mesh: nothing can be drawn"},
};

std::filesystem::path samplesDir() { return sharedDir() / "assets" / "gltf-samples"; }

std::size_t countAfter(const std::string& text, const std::string& label) {
    std::smatch m;
    if (!std::regex_search(text, m, std::regex(label + "(\\d+)"))) return std::size_t(-1);
    return std::stoul(m[1]);
}

class GltfSamples : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        if (IsSkipped()) return;
        if (!std::filesystem::is_directory(samplesDir()))
            GTEST_SKIP() << "the shared assets are absent: " << samplesDir();
    }
};

TEST_F(GltfSamples, EachRendersAndReportsTheFilesCounts) {
    const auto out = testOutputDir();
    for (const Sample& s : kSamples) {
        SCOPED_TRACE(s.file);
        const auto path = samplesDir() / s.file;
        const nlohmann::json doc = lantern::test::fileJson(path);
        const std::size_t primitives = lantern::test::primitivesIn(doc);

        const auto info = runProcess({cliPath().string(), "info", path.string()});
        ASSERT_EQ(info.exitCode, 0) << info.err;
        EXPECT_EQ(countAfter(info.out, "nodes: "), doc.value("nodes", nlohmann::json::array()).size()) << info.out;
        EXPECT_EQ(countAfter(info.out, "meshes: \\d+ \\("), primitives) << info.out;

        std::vector<Image> frames;
        for (std::size_t i = 0; i < s.times.size(); ++i) {
            const auto exr = out / (std::filesystem::path(s.file).stem().string() + "_" + std::to_string(i) + ".exr");
            std::vector<std::string> args = {cliPath().string(), "render", path.string(), "--width", "64", "--height",
                                             "64",     "--time", std::to_string(s.times[i]), "-o", exr.string(),
                                             "--background", "0,0,0,0"};  // alpha is coverage
            args.insert(args.end(), s.args.begin(), s.args.end());
            const auto r = runProcess(args, {"LANTERN_VALIDATION=1"});
            ASSERT_EQ(r.exitCode, 0) << r.err;
            EXPECT_EQ(r.err.find("vulkan validation"), std::string::npos) << r.err;
            auto image = readExr(exr);
            ASSERT_TRUE(image) << image.error().describe();
            EXPECT_EQ(lantern::test::countNonFinite(*image), 0u);
            const std::size_t covered = lantern::test::countCovered(*image, 0.01f);
            if (s.drawn)
                EXPECT_GT(covered, 0u) << "t=" << s.times[i] << " " << exr;
            else
                EXPECT_EQ(covered, 0u) << s.why;
            frames.push_back(std::move(*image));
        }
        for (std::size_t i = 1; i < frames.size(); ++i)
            EXPECT_NE(frames[i].rgba, frames[i - 1].rgba)
                << "t=" << s.times[i - 1] << " and t=" << s.times[i] << " render the same image (" << s.why << ")";
    }
}

} // namespace
