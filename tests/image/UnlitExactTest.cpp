// --unlit-exact (docs/aovs.md): label colours written in a glTF come back bit for bit, through
// the API and through an EXR written by the command, although the scene is lit, metallic and
// emissive; colours no 8-bit code or short decimal holds included. Anti-aliasing is refused.
#include "GltfTestBuilder.h"
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <cstring>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::GltfBuilder;
using nlohmann::json;

// The label colours, as the file writes them (doubles; the renderer's value is the nearest float).
const std::vector<std::array<double, 3>> kLabels = {
    {0.1, 0.2, 0.3},
    {1.0 / 3.0, 2.0 / 7.0, 0.123456789},
    {0.7, 1e-6, 0.999999},
    {1e-30, 0.5000001, 0.00392156862745098},  // the last is 1/255 in double
};

// Four quads side by side (x from -4 to 4, one unit gaps), each with its label material; the
// first three are metallic-roughness materials (one emissive), the last is KHR_materials_unlit;
// a directional light shines on them.
std::filesystem::path writeLabels(const std::filesystem::path& dir) {
    GltfBuilder b;
    b.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_unlit"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "directional"}, {"intensity", 3.0}, {"color", {1.0, 0.9, 0.8}}}};
    for (std::size_t i = 0; i < kLabels.size(); ++i) {
        const auto& c = kLabels[i];
        json m = {{"pbrMetallicRoughness",
                   {{"baseColorFactor", {c[0], c[1], c[2], 1.0}},
                    {"metallicFactor", i == 0 ? 1.0 : 0.3},
                    {"roughnessFactor", 0.4}}}};
        if (i == 1) m["emissiveFactor"] = {0.2, 0.1, 0.0};
        if (i == 3) m["extensions"]["KHR_materials_unlit"] = json::object();
        b.doc["materials"].push_back(m);
        const float x0 = -4.0f + 2.0f * float(i), x1 = x0 + 1.5f;
        json prim = {{"attributes",
                      {{"POSITION", b.addFloats({x0, -1, 0, x1, -1, 0, x1, 1, 0, x0, 1, 0}, "VEC3")},
                       {"NORMAL", b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")}}},
                     {"indices", b.addIndices({0, 1, 2, 0, 2, 3})},
                     {"material", int(i)}};
        b.addNode({{"mesh", b.addMesh(prim)}});
    }
    b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
               {"rotation", {-0.3826834, 0.0, 0.0, 0.9238795}}});
    return b.write(dir, "labels");
}

RenderOptions labelOptions() {
    RenderOptions o;
    o.width = 128;
    o.height = 32;
    o.unlitExact = true;
    o.camera.lookAt = LookAt{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
    o.camera.projection = Projection::makeOrtho(-4.0, 4.0, -1.0, 1.0, 0.5, 10.0);
    return o;
}

// Each label's quad, read at its centre pixel: every channel the float nearest the file's
// number, bit for bit, and alpha 1.
void expectExactLabels(const Image& image) {
    ASSERT_EQ(image.width, 128);
    for (std::size_t i = 0; i < kLabels.size(); ++i) {
        // Quad i spans x in [-4 + 2i, -2.5 + 2i] of [-4, 4]: its centre column.
        const double centre = -4.0 + 2.0 * double(i) + 0.75;
        const int x = int((centre + 4.0) / 8.0 * image.width);
        for (int y : {8, 16, 23}) {
            const float* p = image.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const float want = float(kLabels[i][std::size_t(c)]);
                EXPECT_EQ(std::memcmp(&p[c], &want, 4), 0)
                    << "label " << i << " channel " << c << " at " << x << "," << y << ": "
                    << p[c] << " (bits differ from " << want << ")";
            }
            EXPECT_EQ(p[3], 1.0f);
        }
    }
}

class UnlitExact : public GpuTest {};

TEST_F(UnlitExact, LabelColoursComeBackBitForBitThroughTheApi) {
    auto scene = loadScene(writeLabels(test::testOutputDir()).string());
    ASSERT_TRUE(scene) << scene.error().describe();
    auto image = renderer().render(*scene, labelOptions(), 0.0);
    ASSERT_TRUE(image) << image.error().describe();
    expectExactLabels(*image);
    // Lit, the same scene is not its labels: the test would see lighting.
    RenderOptions lit = labelOptions();
    lit.unlitExact = false;
    auto shaded = renderer().render(*scene, lit, 0.0);
    ASSERT_TRUE(shaded);
    EXPECT_NE(shaded->pixel(12, 16)[0], float(kLabels[0][0]));
    // Anti-aliasing blends labels: refused.
    RenderOptions msaa = labelOptions();
    msaa.msaa = 4;
    auto refused = renderer().render(*scene, msaa, 0.0);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().describe().find("--msaa 1"), std::string::npos);
}

TEST_F(UnlitExact, LabelColoursComeBackBitForBitThroughAnExr) {
    const auto dir = test::testOutputDir();
    const auto scene = writeLabels(dir);
    const auto out = dir / "labels.exr";
    const auto r = test::runLantern({"render", scene.string(), "-o", out.string(), "--width",
                                     "128", "--height", "32", "--unlit-exact", "--look-at",
                                     "0,0,5,0,0,0,0,1,0", "--ortho", "-4,4,-1,1,0.5,10"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto image = readExr(out);
    ASSERT_TRUE(image) << image.error().describe();
    expectExactLabels(*image);
    const auto msaa = test::runLantern({"render", scene.string(), "-o", (dir / "x.exr").string(),
                                        "--unlit-exact", "--msaa", "4"});
    EXPECT_EQ(msaa.exitCode, 2) << msaa.err;
    EXPECT_NE(msaa.err.find("--unlit-exact"), std::string::npos) << msaa.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));
}

} // namespace
