// Points and lines (glTF POINTS, LINES, LINE_LOOP, LINE_STRIP; GL_POINTS, GL_LINES) on the GPU
// against the CPU reference: lit when they carry normals, in phong, gouraud, flat and GL-flat
// shading; unlit (material colour times COLOR_0) when they do not; the point size and line
// width options; and every one of glTF's seven modes, indexed and not, loaded from files this
// test writes, drawn where the reference says.
#include "GltfTestBuilder.h"
#include "LightingCompare.h"

#include <lantern/Io.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

// The edges of a UV sphere's triangles as a line list, or its vertices as points; normals
// (radial) kept unless `unlit`, and a colour per vertex.
Primitive wireSphere(Topology topology, bool unlit) {
    const Primitive sphere = makeSphere(1.0, 12, 6);
    Primitive p;
    p.topology = topology;
    p.positions = sphere.positions;
    if (!unlit) p.normals = sphere.normals;
    for (const glm::vec3& v : sphere.positions)
        p.colors.emplace_back(0.5f + 0.5f * v.x, 0.5f + 0.5f * v.y, 0.8f, 1.0f);
    if (topology == Topology::Lines)
        for (std::size_t t = 0; t + 2 < sphere.indices.size(); t += 3)
            for (int e = 0; e < 3; ++e)
                p.indices.insert(p.indices.end(),
                                 {sphere.indices[t + std::size_t(e)], sphere.indices[t + std::size_t((e + 1) % 3)]});
    return p;
}

Scene linesAndPoints(bool unlit) {
    LitScene s;
    const Material shiny = test::phongMaterial({0.1, 0.1, 0.1}, {0.7, 0.6, 0.5, 1.0}, {0.8, 0.8, 0.8}, 20.0);
    s.objects.push_back({wireSphere(Topology::Lines, unlit), shiny, test::translation({-1.1, 0, 0})});
    s.objects.push_back({wireSphere(Topology::Points, unlit), shiny, test::translation({1.1, 0, 0})});
    s.lights.push_back({test::makeLight(LightType::Point), test::translation({2, 2, 3})});
    return s.build();
}

class PointsLines : public GpuTest {};

TEST_F(PointsLines, LitLinesAndPointsAgreeWithTheReferenceInEveryShadingMode) {
    const Scene scene = linesAndPoints(false);
    ASSERT_TRUE(scene.validate());
    struct Mode {
        ShadingMode shading;
        bool glCompat;
    };
    for (Mode m : {Mode{ShadingMode::Phong, false}, Mode{ShadingMode::Gouraud, false},
                   Mode{ShadingMode::Flat, false}, Mode{ShadingMode::Flat, true}}) {
        const std::string name = std::string("lines_points_") + toString(m.shading) + (m.glCompat ? "_gl" : "");
        SCOPED_TRACE(name);
        RenderOptions o = test::optionsFor(128, 64, m.shading);
        o.glCompat = m.glCompat;
        const test::ReferenceComparison c = test::compareWithReference(device(), scene, o);
        EXPECT_GT(c.compared, 500u);
        EXPECT_LE(c.worst, 2.0 / 255.0) << c.describe(name);
        EXPECT_EQ(c.frame.readback.nonFinite, 0u);
        // Lit: the brightest line pixel is well above the darkest (the light has a side).
        float lo = 1e9f, hi = 0.0f;
        for (std::size_t i = 0; i < c.frame.readback.ids.size() / 2; ++i)
            if (c.frame.readback.ids[i * 2] != 0) {
                const float* px = c.frame.readback.image.pixel(int(i % 128), int(i / 128));
                lo = std::min(lo, px[0]);
                hi = std::max(hi, px[0]);
            }
        EXPECT_GT(hi, lo + 0.3f) << "lines and points look unlit";
    }
}

TEST_F(PointsLines, WithoutNormalsTheyAreUnlitMaterialColourTimesVertexColour) {
    const Scene scene = linesAndPoints(true);
    ASSERT_TRUE(scene.validate());
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
        const std::string name = std::string("unlit_lines_points_") + toString(mode);
        SCOPED_TRACE(name);
        const test::ReferenceComparison c = test::compareWithReference(device(), scene, test::optionsFor(128, 64, mode));
        EXPECT_GT(c.compared, 500u);
        EXPECT_LE(c.worst, 2.0 / 255.0) << c.describe(name);
        // The blue channel is the material's 0.5 times COLOR_0's 0.8 wherever anything is
        // drawn, whatever the light: nothing is lit, nothing is black.
        for (std::size_t i = 0; i < c.frame.readback.ids.size() / 2; ++i)
            if (c.frame.readback.ids[i * 2] != 0) {
                const float* px = c.frame.readback.image.pixel(int(i % 128), int(i / 128));
                ASSERT_NEAR(px[2], 0.4f, 1e-5f) << "pixel " << i;
            }
        EXPECT_TRUE(c.reports[c.worstY * 128 + c.worstX].unlit);
    }
}

// Pixels covered by anything (the id AOV).
std::size_t covered(const render::RenderedFrame& f) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < f.readback.ids.size(); i += 2) n += f.readback.ids[i] != 0 ? 1 : 0;
    return n;
}

TEST_F(PointsLines, PointSizeAndLineWidthWidenWhatIsDrawn) {
    LitScene s;
    Primitive points;
    points.topology = Topology::Points;
    points.positions = {{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}};
    Primitive lines;
    lines.topology = Topology::Lines;
    lines.positions = {{-1.0f, 0.5f, 0.0f}, {1.0f, 0.5f, 0.0f}};
    s.objects.push_back({points, Material{}, glm::dmat4(1.0)});
    s.objects.push_back({lines, Material{}, glm::dmat4(1.0)});
    const Scene scene = s.build();
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    auto thin = test::renderWithIds(device(), scene, o);
    ASSERT_TRUE(thin) << thin.error().describe();
    o.pointSize = 5.0;
    o.lineWidth = 3.0;
    auto wide = test::renderWithIds(device(), scene, o);
    ASSERT_TRUE(wide) << wide.error().describe();
    // A 2-unit line across a 64-pixel view of height 2 tan(20 deg) 4 = 2.91 units: 44 pixels
    // long; two one-pixel points.
    const std::size_t line = 44;
    EXPECT_NEAR(double(covered(*thin)), double(line + 2), 3.0);
    EXPECT_NEAR(double(covered(*wide)), double(3 * line + 2 * 25), 12.0);
    o.pointSize = 0.5;
    EXPECT_FALSE(render::checkOptions(device(), o));
    o.pointSize = 1.0;
    o.lineWidth = 256.0;
    EXPECT_FALSE(render::checkOptions(device(), o));
}

// glTF files for each mode, indexed and not: a zigzag of 7 vertices in the z = 0 plane with
// normals facing the camera.
std::filesystem::path modeFile(const std::filesystem::path& dir, int mode, bool indexed) {
    test::GltfBuilder b;
    std::vector<float> pos, nrm;
    for (int i = 0; i < 7; ++i) {
        pos.insert(pos.end(), {-0.9f + 0.3f * float(i), i % 2 ? 0.4f : -0.4f, 0.0f});
        nrm.insert(nrm.end(), {0.0f, 0.0f, 1.0f});
    }
    nlohmann::json prim = {{"attributes", {{"POSITION", b.addFloats(pos, "VEC3")},
                                           {"NORMAL", b.addFloats(nrm, "VEC3")}}},
                           {"mode", mode}};
    if (indexed) prim["indices"] = b.addIndices({0, 1, 2, 3, 4, 5, 6});
    b.addNode({{"mesh", b.addMesh(prim)}});
    b.doc["materials"] = nlohmann::json::array({{{"doubleSided", true}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    return b.write(dir, "mode" + std::to_string(mode) + (indexed ? "i" : ""));
}

TEST_F(PointsLines, EveryGltfModeIndexedOrNotIsDrawnAsTheReferenceSays) {
    const auto dir = test::testOutputDir();
    std::size_t coverage[7] = {};
    for (int mode = 0; mode < 7; ++mode)
        for (bool indexed : {false, true}) {
            auto scene = loadGltf(modeFile(dir, mode, indexed));
            ASSERT_TRUE(scene) << scene.error().describe();
            for (ShadingMode shading : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
                const std::string name = "mode" + std::to_string(mode) + (indexed ? "_indexed_" : "_") + toString(shading);
                SCOPED_TRACE(name);
                const test::ReferenceComparison c = test::compareWithReference(device(), *scene, test::optionsFor(64, 64, shading));
                // Seven one-pixel points; anything else covers more.
                if (mode == 0)
                    EXPECT_EQ(c.compared, 7u);
                else
                    EXPECT_GT(c.compared, 20u) << "mode " << mode << " drew (almost) nothing";
                EXPECT_LE(c.worst, 2.0 / 255.0) << c.describe(name);
                if (shading == ShadingMode::Phong && !indexed) coverage[mode] = c.compared;
            }
        }
    // Points cover the fewest pixels, a loop more than a strip more than a list of lines, and
    // triangles (the list of two, the strip and the fan of five) more than any line.
    EXPECT_LT(coverage[0], coverage[1]);
    EXPECT_LT(coverage[1], coverage[3]);
    EXPECT_LT(coverage[3], coverage[2]);
    EXPECT_LT(coverage[2], coverage[4]);
    EXPECT_LT(coverage[4], coverage[5]);
}

} // namespace
