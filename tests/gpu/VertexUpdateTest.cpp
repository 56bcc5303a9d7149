// Renderer::updateVertices: the host moves a prepared scene's vertices in its Scene
// and the next render draws them where they now are, on the same renderer and upload; edits it
// cannot take are refused naming the primitive.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

namespace {

using namespace lantern;

// The coverage-weighted mean column of the picture (alpha is coverage on a clear background).
double centroidX(const Image& image) {
    double sum = 0.0, weight = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float a = image.pixel(x, y)[3];
            sum += a * x;
            weight += a;
        }
    return weight > 0.0 ? sum / weight : -1.0;
}

class VertexUpdate : public test::GpuTest {
protected:
    // An orthographic box 4 units wide on 64 pixels: 16 pixels per unit.
    RenderOptions options(ShadingMode shading) const {
        RenderOptions o;
        o.width = o.height = 64;
        o.shading = shading;
        o.background = glm::vec4(0.0f);
        o.camera.lookAt = LookAt{{0, 0, 10}, {0, 0, 0}, {0, 1, 0}};
        o.camera.projection = Projection::makeOrtho(-2, 2, -2, 2, 0.1, 100);
        return o;
    }
};

TEST_F(VertexUpdate, MovedVerticesAreDrawnWhereTheyNowAre) {
    auto loaded = builtinScene("teapot");
    ASSERT_TRUE(loaded);
    auto scene = std::make_shared<Scene>(std::move(*loaded));
    auto prepared = renderer().prepare(scene);
    ASSERT_TRUE(prepared) << prepared.error().describe();
    int node = 0;
    while (scene->nodes[std::size_t(node)].mesh < 0) ++node;
    const int mesh = scene->nodes[std::size_t(node)].mesh;
    const double scale = scene->nodes[std::size_t(node)].scale.x;
    std::vector<glm::vec3>& positions = scene->meshes[std::size_t(mesh)].primitives[0].positions;
    const std::vector<glm::vec3> original = positions;
    for (ShadingMode shading : {ShadingMode::Gouraud, ShadingMode::Flat}) {
        auto before = renderer().render(*prepared, options(shading), 0.0);
        ASSERT_TRUE(before) << before.error().describe();
        // 0.25 world units along x: 4 pixels.
        for (glm::vec3& p : positions)
            p.x += float(0.25 / scale);
        ASSERT_TRUE(renderer().updateVertices(*prepared, mesh, 0));
        auto after = renderer().render(*prepared, options(shading), 0.0);
        ASSERT_TRUE(after) << after.error().describe();
        EXPECT_NEAR(centroidX(*after) - centroidX(*before), 4.0, 0.05);
        positions = original;
        ASSERT_TRUE(renderer().updateVertices(*prepared, mesh, 0));
        auto back = renderer().render(*prepared, options(shading), 0.0);
        ASSERT_TRUE(back);
        EXPECT_EQ(test::maxAbsDifference(*back, *before), 0.0f) << "put back, drawn as before";
    }
}

// Flat lines are drawn from per-corner streams built from the vertices (SceneBuffers'
// flat streams): those follow the moved vertices too.
TEST_F(VertexUpdate, FlatLinesFollowTheirMovedVertices) {
    test::SimpleScene simple;
    Primitive& lines = simple.primitive;
    lines.topology = Topology::Lines;
    for (int i = 0; i <= 10; ++i) {
        const float y = -1.0f + 0.2f * float(i);
        lines.positions.insert(lines.positions.end(), {{-1.0f, y, 0.0f}, {1.0f, y, 0.0f}});
        lines.normals.insert(lines.normals.end(), 2, glm::vec3(0.0f, 0.0f, 1.0f));
    }
    auto scene = std::make_shared<Scene>(simple.build());
    auto prepared = renderer().prepare(scene);
    ASSERT_TRUE(prepared) << prepared.error().describe();
    auto before = renderer().render(*prepared, options(ShadingMode::Flat), 0.0);
    ASSERT_TRUE(before) << before.error().describe();
    ASSERT_GT(test::countCovered(*before), 100u);
    for (glm::vec3& p : scene->meshes[0].primitives[0].positions)
        p.x += 0.25f;
    ASSERT_TRUE(renderer().updateVertices(*prepared, 0, 0));
    auto after = renderer().render(*prepared, options(ShadingMode::Flat), 0.0);
    ASSERT_TRUE(after) << after.error().describe();
    EXPECT_NEAR(centroidX(*after) - centroidX(*before), 4.0, 0.05);
}

TEST_F(VertexUpdate, EditsItCannotTakeAreRefusedNamingThePrimitive) {
    auto loaded = builtinScene("teapot");
    ASSERT_TRUE(loaded);
    auto scene = std::make_shared<Scene>(std::move(*loaded));
    auto prepared = renderer().prepare(scene);
    ASSERT_TRUE(prepared);
    Primitive& p = scene->meshes[0].primitives[0];
    auto missing = renderer().updateVertices(*prepared, 5, 0);
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::Usage);
    EXPECT_NE(missing.error().describe().find("mesh 5 primitive 0"), std::string::npos);
    p.positions.push_back(glm::vec3(0.0f));
    auto grown = renderer().updateVertices(*prepared, 0, 0);
    ASSERT_FALSE(grown);
    EXPECT_EQ(grown.error().code, ErrorCode::InvalidInput);
    EXPECT_NE(grown.error().describe().find("mesh 0 primitive 0"), std::string::npos)
        << grown.error().describe();
    p.positions.pop_back();
    p.positions[7].y = std::numeric_limits<float>::quiet_NaN();
    auto nan = renderer().updateVertices(*prepared, 0, 0);
    ASSERT_FALSE(nan);
    EXPECT_NE(nan.error().describe().find("not finite"), std::string::npos);
    p.positions[7].y = 0.0f;
    EXPECT_TRUE(renderer().updateVertices(*prepared, 0, 0));
}

} // namespace
