// The camera options of `lantern render`: every refusal of the camera issue exits 1 with one
// line naming the option and the problem (usage mistakes exit 2); extreme but valid values
// render without NaN or Inf; --depth, --default-camera, --viewport with a camera per view and
// --layout quad produce exactly the images the API renders for the same cameras.
#include "CameraTestSupport.h"
#include "TestSupport.h"

#include <cmath>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::runLantern;
using lantern::test::testOutputDir;

std::vector<std::string> spheres(std::vector<std::string> extra) {
    std::vector<std::string> args{"render",   "builtin:spheres",
                                  "--width",  "32",
                                  "--height", "32",
                                  "-o",       (testOutputDir() / "refused.exr").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

TEST(CameraCli, RefusesBadCameraValuesWithExit1) {
    LANTERN_SKIP_IF_MISSING(lantern::test::missingVulkanDevice());
    struct Row {
        std::vector<std::string> args;
        std::string option, mention;
    };
    const Row rows[] = {
        {{"--look-at", "1,2,3,1,2,3,0,1,0"}, "--look-at", "same point"},
        {{"--look-at", "0,0,5,0,0,0,0,0,0"}, "--look-at", "zero length"},
        {{"--look-at", "0,0,5,0,0,0,0,0,1"}, "--look-at", "parallel"},
        {{"--look-at", "0,0,5,0,0,0,0,0,-2"}, "--look-at", "parallel"},
        {{"--look-at", "0,0,nan,0,0,0,0,1,0"}, "--look-at", "not finite"},
        {{"--look-at", "0,0,inf,0,0,0,0,1,0"}, "--look-at", "must be finite"},
        {{"--look-at", "-1e308,0,0,1e308,0,0,0,1,0"}, "--look-at", "beyond +-1e30"},
        {{"--perspective", "60,1,0,10"}, "--perspective", "near"},
        {{"--perspective", "60,1,-1,10"}, "--perspective", "near"},
        {{"--frustum", "-1,1,-1,1,0,10"}, "--frustum", "near"},
        {{"--frustum", "-1,1,-1,1,-0.5,10"}, "--frustum", "near"},
        {{"--perspective", "60,1,1,1"}, "--perspective", "far"},
        {{"--frustum", "-1,1,-1,1,2,2"}, "--frustum", "far"},
        {{"--ortho", "-1,1,-1,1,2,2"}, "--ortho", "far == near"},
        {{"--ortho", "1,1,-1,1,-1,1"}, "--ortho", "left == right"},
        {{"--frustum", "1,1,-1,1,1,2"}, "--frustum", "left == right"},
        {{"--ortho", "-1,1,2,2,-1,1"}, "--ortho", "bottom == top"},
        {{"--frustum", "-1,1,2,2,1,2"}, "--frustum", "bottom == top"},
        {{"--perspective", "0,1,0.1,10"}, "--perspective", "fovy"},
        {{"--perspective", "180,1,0.1,10"}, "--perspective", "fovy"},
        {{"--perspective", "-5,1,0.1,10"}, "--perspective", "fovy"},
        {{"--perspective", "200,1,0.1,10"}, "--perspective", "fovy"},
        {{"--perspective", "60,0,0.1,10"}, "--perspective", "aspect"},
        {{"--perspective", "60,-2,0.1,10"}, "--perspective", "aspect"},
        {{"--perspective", "60,1,0.1,nan"}, "--perspective", "not finite"},
        {{"--perspective", "inf,1,0.1,10"}, "--perspective", "must be finite"},
        {{"--perspective", "60,1,inf,10"}, "--perspective", "must be finite"},
        {{"--ortho", "-1,1,-1,1,0,inf"}, "--ortho", "must be finite"},
        {{"--frustum", "-1,1,-1,1,1,1e999"}, "--frustum", "not finite"},
        {{"--frustum", "-1,1,-1,1,1,-inf"}, "--frustum", "not finite"},
        {{"--ortho", "-1e308,1e308,-1,1,0,1"}, "--ortho", "too large"},
        {{"--frustum", "0,1e-40,-1,1,1,2"}, "--frustum", "single precision"},
        {{"--perspective", "60,1,1e-40,10"}, "--perspective", "single precision"},
        {{"--perspective", "60,1,0.1"}, "--perspective", "expected 4"},
        {{"--viewport", "0,0,0,10"}, "--viewport", "empty"},
        {{"--viewport", "0,0,10.5,10"}, "--viewport", "whole pixels"},
        {{"--viewport", "0,0,nan,10"}, "--viewport", "not finite"},
        {{"--viewport", "20,20,20,20"}, "--viewport", "outside"},
    };
    for (const Row& r : rows) {
        const auto result = runLantern(spheres(r.args));
        const std::string what = r.args[0] + " " + r.args[1];
        EXPECT_EQ(result.exitCode, 1) << what << ": " << result.err;
        EXPECT_NE(result.err.find(r.option), std::string::npos) << what << ": " << result.err;
        EXPECT_NE(result.err.find(r.mention), std::string::npos)
            << what << ": expected \"" << r.mention << "\" in: " << result.err;
        EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
    }
    EXPECT_FALSE(std::filesystem::exists(testOutputDir() / "refused.exr"));
}

TEST(CameraCli, CameraUsageMistakesExitWith2) {
    const std::vector<std::string> rows[] = {
        {"--camera", "0", "--default-camera"},
        {"--layout", "quad", "--viewport", "0,0,16,16"},
        {"--perspective", "60,1,1,2", "--frustum", "-1,1,-1,1,1,2"},
        {"--viewport", "0,0,16,16", "--camera", "0", "--camera", "0"},
        {"--view", "top", "--camera", "0"},
        {"--view", "top", "--default-camera"},
    };
    for (const auto& args : rows) {
        const auto r = runLantern(spheres(args));
        EXPECT_EQ(r.exitCode, 2) << args[0] << " " << args[1] << ": " << r.err;
        EXPECT_FALSE(r.err.empty()) << args[0];
    }
    // A value outside an option's choices is a bad option value: refused input (1).
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"--depth", "reverse"}, {"--layout", "triple"}, {"--view", "diagonal"}}) {
        const auto r = runLantern(spheres(args));
        EXPECT_EQ(r.exitCode, 1) << args[0] << " " << args[1] << ": " << r.err;
        EXPECT_NE(r.err.find(args[0]), std::string::npos) << r.err;
    }
}

class CameraCliRender : public GpuTest {
protected:
    // Renders with the command line and reads the EXR back.
    Image cli(const std::string& name, std::vector<std::string> extra, int w = 64, int h = 48) {
        const std::string out = (testOutputDir() / (name + ".exr")).string();
        std::vector<std::string> args{"render",   "builtin:spheres", "--width", std::to_string(w),
                                      "--height", std::to_string(h), "-o",      out,
                                      "--background", "0,0,0,0"};  // alpha is coverage
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = runLantern(args);
        EXPECT_EQ(r.exitCode, 0) << name << ": " << r.err;
        auto image = readExr(out);
        EXPECT_TRUE(image) << name << ": " << (image ? "" : image.error().describe());
        return image ? *image : Image(w, h);
    }
    // Renders with the API.
    Image api(RenderOptions o) {
        o.background = glm::vec4(0.0f);
        auto scene = builtinScene("spheres");
        EXPECT_TRUE(scene);
        auto image = renderer().render(*scene, o, 0.0);
        EXPECT_TRUE(image) << image.error().describe();
        return image ? *image : Image(o.width, o.height);
    }
};

// A view drawn at an offset inside a larger image rounds its window coordinates differently
// from the same view alone: interpolated colours differ by up to ~1e-5 (measured 1.3e-5).
constexpr float kOffsetTolerance = 1e-4f;

// Colour (and alpha) of the rectangle `r` of `a` against all of `b` (the same size as r).
float largestDifference(const Image& a, const test::PixelRect& r, const Image& b) {
    float largest = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            for (int c = 0; c < 4; ++c)
                largest =
                    std::max(largest, std::abs(a.pixel(r.x + x, r.y + y)[c] - b.pixel(x, y)[c]));
    return largest;
}

TEST_F(CameraCliRender, ExtremeButValidValuesRenderWithoutNanOrInf) {
    const std::vector<std::string> rows[] = {
        {"--perspective", "1e-4,1,0.1,inf"},
        {"--perspective", "179.9,1,0.01,inf", "--look-at", "0,-0.5,4,0,-0.5,3,0,1,0"},
        {"--perspective", "40,1e-4,0.1,100"},
        {"--perspective", "40,1e4,0.001,100", "--look-at", "1.2,0,0,1.2,0,-1,0,1,0"},
        {"--perspective", "40,1.33,1e-6,1e12"},
        {"--frustum", "-4e-7,4e-7,-3e-7,3e-7,1e-6,inf"},
        {"--perspective", "40,1.33,1e-6,1e12", "--depth", "standard"},
    };
    int i = 0;
    for (const auto& args : rows) {
        const Image image = cli("extreme" + std::to_string(i++), args);
        EXPECT_EQ(test::countNonFinite(image), 0u) << args[0] << " " << args[1];
        EXPECT_GT(test::countCovered(image), 0u) << args[0] << " " << args[1];
    }
}

TEST_F(CameraCliRender, DepthOptionSelectsTheScheme) {
    const Image reversed = cli("reversed", {"--depth", "reversed"});
    const Image standard = cli("standard", {"--depth", "standard"});
    const Image byDefault = cli("default", {});
    EXPECT_EQ(reversed.rgba, byDefault.rgba) << "reversed-Z is the default";
    // At 9 units with near 0.1 both schemes resolve every surface of the scene: the same
    // picture away from silhouette edges.
    const auto d = test::compareAwayFromEdges(standard, reversed, 1.0f / 255.0f);
    EXPECT_EQ(d.differing, 0u) << "largest " << d.largest;
    const auto explain =
        runLantern({"render", "builtin:spheres", "--width", "16", "--height", "16", "--depth",
                    "standard", "--explain", "-o", (testOutputDir() / "explain.exr").string()});
    EXPECT_EQ(explain.exitCode, 0) << explain.err;
    EXPECT_NE(explain.out.find("standard-z"), std::string::npos) << explain.out;
}

TEST_F(CameraCliRender, DefaultCameraIsTheGlUnitCube) {
    const Image image = cli("gl-default", {"--default-camera"}, 64, 64);
    RenderOptions o;
    o.width = o.height = 64;
    o.camera.source = CameraSpec::Source::GlDefault;
    EXPECT_EQ(largestDifference(image, {0, 0, 64, 64}, api(o)), 0.0f);
    // The unit sphere at the origin exactly fills the 2 x 2 view: pi/4 of the pixels.
    EXPECT_NEAR(double(test::countCovered(image)) / image.pixelCount(), 3.14159265 / 4, 0.02);
}

// --view frames from the named side whatever camera the scene has (builtin:spheres has one):
// the same image as the API's CameraSpec::framed, and a different one for each view.
TEST_F(CameraCliRender, ViewNamesTheSideTheFramingLooksFrom) {
    std::vector<Image> images;
    for (ViewDirection v : kViewDirections) {
        const Image image = cli(std::string("view-") + toString(v), {"--view", toString(v)}, 32, 32);
        RenderOptions o;
        o.width = o.height = 32;
        o.camera = CameraSpec::framed(v);
        EXPECT_EQ(largestDifference(image, {0, 0, 32, 32}, api(o)), 0.0f) << toString(v);
        EXPECT_GT(test::countCovered(image), 0u) << toString(v);
        for (const Image& other : images) EXPECT_NE(image.rgba, other.rgba) << toString(v);
        images.push_back(image);
    }
    EXPECT_NE(images[0].rgba, cli("scene-camera", {}, 32, 32).rgba)
        << "without --view the scene's own camera wins";
}

TEST_F(CameraCliRender, ViewportsEachWithItsOwnCamera) {
    // Two views of different sizes in a 96 x 64 image (GL's bottom-left origin), one --camera
    // each (the built-in scene has one camera; views with different cameras are covered by
    // CameraProjection): each must equal a whole-image render of its size.
    const Image image = cli(
        "viewports",
        {"--viewport", "0,0,48,64", "--viewport", "48,16,48,48", "--camera", "0", "--camera", "0"},
        96, 64);
    RenderOptions o;
    o.camera.source = CameraSpec::Source::SceneCamera;
    o.camera.sceneCamera = 0;
    o.width = 48, o.height = 64;
    EXPECT_LT(largestDifference(image, {0, 0, 48, 64}, api(o)), kOffsetTolerance);
    o.width = 48, o.height = 48;
    EXPECT_LT(largestDifference(image, {48, 0, 48, 48}, api(o)), kOffsetTolerance);
    // Below the second view (image rows 48..63 of the right half) nothing is drawn.
    for (int y = 48; y < 64; ++y)
        for (int x = 48; x < 96; ++x)
            ASSERT_EQ(image.pixel(x, y)[3], 0.0f) << x << ", " << y;
}

TEST_F(CameraCliRender, QuadLayoutIsTopFrontSideAndPerspective) {
    const int w = 128, h = 96;
    const Image image = cli("layout", {"--layout", "quad"}, w, h);
    auto framed = [](glm::dvec3 direction) {
        CameraSpec s;
        s.source = CameraSpec::Source::Framing;
        s.framingDirection = direction;
        s.framingOrthographic = true;
        return s;
    };
    struct Quadrant {
        const char* name;
        test::PixelRect rect; ///< in the image (top-left origin)
        CameraSpec camera;
    };
    const Quadrant quadrants[] = {
        {"top view, top left", {0, 0, w / 2, h / 2}, framed({0, -1, 0})},
        {"front view, top right", {w / 2, 0, w / 2, h / 2}, framed({0, 0, -1})},
        {"side view, bottom left", {0, h / 2, w / 2, h / 2}, framed({-1, 0, 0})},
        {"perspective camera, bottom right", {w / 2, h / 2, w / 2, h / 2}, CameraSpec{}},
    };
    for (const Quadrant& q : quadrants) {
        RenderOptions o;
        o.width = q.rect.width;
        o.height = q.rect.height;
        o.camera = q.camera;
        const Image alone = api(o);
        EXPECT_GT(test::countCovered(alone), 0u) << q.name;
        EXPECT_LT(largestDifference(image, q.rect, alone), kOffsetTolerance) << q.name;
    }
}

} // namespace
