// What the first hostile corpus left (its "hostile remainder"): an empty --frames is a
// usage error; a background finite as a double but infinite as a float, and a camera so far out
// that its matrices overflow, are refused before anything renders; a scene at FLT_MAX renders,
// and its EXR header holds no Inf or NaN (the camera matrices are left out, with a warning).
#include "../unit/GltfTestSupport.h"

#include "io/image/ImageEncode.h"

#include <lantern/Io.h>

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lantern {
namespace {

namespace fs = std::filesystem;

bool anyFileIn(const fs::path& dir) {
    return fs::exists(dir) && fs::directory_iterator(dir) != fs::directory_iterator();
}

TEST(HostileRemainder, BadValuesAreRefusedBeforeAnythingRenders) {
    const fs::path dir = test::testOutputDir() / "out";
    struct Case {
        std::vector<std::string> args;
        int exit;
        const char* fragment;
    };
    const std::vector<Case> cases = {
        {{"--frames", ""}, 2, "--frames: needs a value"},
        {{"--frame-list", ""}, 2, "--frame-list: needs a value"},
        {{"--background", "1e39,0,0"}, 1, "beyond the float range"},
        {{"--background", "0,0,-1e39,1"}, 1, "value 3"},
        {{"--look-at", "1e300,0,0,0,0,0,0,1,0"}, 1, "beyond +-1e30"},
        {{"--look-at", "0,0,5,0,-2e30,0,0,0,1"}, 1, "value 5"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {"render", "builtin:teapot", "--width", "16", "--height",
                                         "16", "-o", (dir / "f_####.exr").string()};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const auto r = test::runLantern(args);
        EXPECT_EQ(r.exitCode, c.exit) << c.args[0] << " " << c.args[1] << "\n" << r.err;
        EXPECT_NE(r.err.find(c.fragment), std::string::npos) << r.err;
        EXPECT_FALSE(anyFileIn(dir)) << c.args[0] << " " << c.args[1] << " wrote a file";
    }
}

TEST(HostileRemainder, CameraMatricesThatOverflowFloatAreLeftOutOfTheHeader) {
    CameraMetadata camera;
    camera.viewFromWorld = glm::dmat4(1.0);
    camera.clipFromView = glm::dmat4(1.0);
    ASSERT_TRUE(io::exrCameraMatrices(camera));
    camera.viewFromWorld[3][2] = -1e30;  // far, still finite in float
    ASSERT_TRUE(io::exrCameraMatrices(camera));
    camera.viewFromWorld[3][2] = -1e39;  // finite in double, infinite in float
    EXPECT_FALSE(io::exrCameraMatrices(camera));
    camera.viewFromWorld[3][2] = -1e20;
    camera.clipFromView[2][2] = 1e20;  // each finite, their product (z) is not
    EXPECT_FALSE(io::exrCameraMatrices(camera));
}

TEST(HostileRemainder, ASceneAtFltMaxRendersWithoutNonFiniteNumbersInItsHeader) {
    test::GltfBuilder b;
    const float big = std::numeric_limits<float>::max();
    const int pos = b.addFloats({0, 0, 0, big, 0, 0, 0, big, 0}, "VEC3");
    b.addNode({{"mesh", b.addMesh({{"attributes", {{"POSITION", pos}}}})}});
    const fs::path dir = test::testOutputDir();
    const fs::path scene = b.write(dir, "fltmax");
    const fs::path out = dir / "fltmax.exr";
    const auto r = test::runLantern({"render", scene.string(), "--width", "16", "--height", "16",
                                     "-o", out.string()});
    if (r.exitCode == 3 && r.err.find("device") != std::string::npos)
        GTEST_SKIP() << "no Vulkan device: " << r.err;
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("not finite in float"), std::string::npos) << r.err;
    auto image = readExr(out);
    ASSERT_TRUE(image) << image.error().describe();
    for (float v : image->rgba) ASSERT_TRUE(std::isfinite(v));
    bool warned = false;
    for (const auto& [key, value] : image->metadata) warned |= key == "lantern:warning";
    EXPECT_TRUE(warned);
    // The header's standard camera attributes were left out; an ordinary render has them.
    Imf::InputFile file(out.c_str());
    EXPECT_FALSE(Imf::hasWorldToCamera(file.header()));
    EXPECT_FALSE(Imf::hasWorldToNDC(file.header()));
    const fs::path plain = dir / "plain.exr";
    ASSERT_EQ(test::runLantern({"render", "builtin:teapot", "--width", "16", "--height", "16",
                                "-o", plain.string()}).exitCode, 0);
    Imf::InputFile plainFile(plain.c_str());
    EXPECT_TRUE(Imf::hasWorldToCamera(plainFile.header()));
    EXPECT_TRUE(Imf::hasWorldToNDC(plainFile.header()));
}

} // namespace
} // namespace lantern
