// Flat shading lit once per triangle (gpu/FlatLight.h): the per-corner streams are never built
// for triangles, every triangle of a flat draw goes to the pre-pass once, and every pixel is
// the reference's colour for its triangle (the equation at
// the centroid with the face normal). The pre-pass skips triangles outside the view and
// back-facing ones; a skipped triangle the rasteriser drew would show whatever its record held
// before, so these frames first fill the records with a glaring colour.
#include "LightingCompare.h"

#include "gpu/SceneBuffers.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

Material plastic(glm::dvec3 diffuse) {
    Material m = test::phongMaterial(diffuse * 0.25, glm::dvec4(diffuse, 1.0), {0.8, 0.8, 0.8}, 20.0);
    m.front.emission = {0.02, 0.01, 0.0};
    return m;
}

// Two spheres, each half outside the view (left and right edges), the right one mirrored (its
// clockwise triangles face the camera), lit by a directional and a point light.
// `emission`: added to both materials (the glaring colour of the poisoning frames).
Scene edgeSpheres(const glm::dvec3& emission = glm::dvec3(0.0)) {
    LitScene s;
    Material left = plastic({0.8, 0.6, 0.4}), right = plastic({0.3, 0.6, 0.9});
    left.front.emission += emission;
    right.front.emission += emission;
    s.objects.push_back({makeSphere(1.0, 32, 16), left, test::translation({-1.6, 0.3, 0.0})});
    s.objects.push_back({makeSphere(1.0, 32, 16), right,
                         glm::scale(test::translation({1.6, -0.3, 0.0}), glm::dvec3(-1.0, 1.0, 1.0))});
    s.lights.push_back({test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -1})});
    Light point = test::makeLight(LightType::Point);
    point.attenuation = {1.0, 0.1, 0.02};
    s.lights.push_back({point, test::translation({0.5, 1.5, 3.0})});
    return s.build();
}

std::uint64_t triangleCount(const Scene& scene) {
    std::uint64_t n = 0;
    for (const Mesh& m : scene.meshes)
        for (const Primitive& p : m.primitives) n += p.elementCount();
    return n;
}

class FlatPerTriangle : public GpuTest {};

TEST_F(FlatPerTriangle, EachTriangleGoesToThePassOnceAndNoCornerStreamsAreBuilt) {
    const Scene scene = edgeSpheres();
    RenderOptions o = test::optionsFor(96, 64, ShadingMode::Flat);
    auto buffers = device().upload(std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &scene));
    ASSERT_TRUE(buffers) << buffers.error().describe();
    FrameStats stats;
    auto frame = render::renderFrame(device(), *buffers, scene, o, 0.0, stats);
    ASSERT_TRUE(frame) << frame.error().describe();
    // Each object is one draw of one primitive: every triangle given to the pass once.
    EXPECT_EQ(frame->readback.flatTriangles, triangleCount(scene));
    EXPECT_EQ((*buffers)->flatGeometryBytes(), 0u) << "the per-corner streams were built";
    EXPECT_GT(test::brightestColour(frame->readback.image), 0.1f);

    // Gouraud and phong give nothing to the pass.
    o.shading = ShadingMode::Gouraud;
    auto gouraud = render::renderFrame(device(), *buffers, scene, o, 0.0, stats);
    ASSERT_TRUE(gouraud) << gouraud.error().describe();
    EXPECT_EQ(gouraud->readback.flatTriangles, 0u);
}

TEST_F(FlatPerTriangle, EveryPixelIsItsTrianglesReferenceColourAndNoSkippedTriangleShows) {
    for (const int msaa : {1, 4}) {
        RenderOptions o = test::optionsFor(96, 64, ShadingMode::Flat);
        o.msaa = msaa;
        // Fill every slot's records with a glaring colour: the same triangles with an emission
        // of 50, where the scene below stays under 3.
        for (std::uint32_t k = 0; k < device().slotCount(); ++k) {
            auto poison = test::renderWithIds(device(), edgeSpheres({50.0, 0.0, 50.0}), o);
            ASSERT_TRUE(poison) << poison.error().describe();
        }
        const Scene scene = edgeSpheres();
        const test::ReferenceComparison c = test::compareWithReference(device(), scene, o);
        const std::string name = "flat_per_triangle_msaa" + std::to_string(msaa);
        EXPECT_EQ(c.frame.readback.flatTriangles, triangleCount(scene)) << name;
        EXPECT_EQ(c.frame.readback.nonFinite, 0u) << name;
        EXPECT_GT(c.compared, 1500u) << name;
        // Under MSAA a pixel on an edge resolves the samples of two triangles (two flat
        // colours), which the reference of one triangle does not model: there only the stale
        // colour is looked for (below, and in the separate AOV pass's ids).
        if (msaa == 1) {
            EXPECT_LE(c.worst, 1.0 / 255) << c.describe(name);
        }
        EXPECT_LT(test::brightestColour(c.frame.readback.image), 10.0f)
            << name << ": a skipped triangle's stale record was shown";
    }
}

// The same triangles without an index list: the pass and the draw's vertex stage take the
// vertices in order, and every pixel is still its triangle's reference colour.
TEST_F(FlatPerTriangle, TrianglesWithoutAnIndexListAreTakenInOrder) {
    Scene scene = edgeSpheres();
    for (Mesh& m : scene.meshes)
        for (Primitive& p : m.primitives) {
            ASSERT_FALSE(p.indices.empty());
            Primitive loose;
            for (const std::uint32_t v : p.indices) {
                loose.positions.push_back(p.positions[v]);
                loose.normals.push_back(p.normals[v]);
            }
            p = loose;
        }
    const RenderOptions o = test::optionsFor(96, 64, ShadingMode::Flat);
    const test::ReferenceComparison c = test::compareWithReference(device(), scene, o);
    EXPECT_EQ(c.frame.readback.flatTriangles, triangleCount(scene));
    EXPECT_GT(c.compared, 1500u);
    EXPECT_LE(c.worst, 1.0 / 255) << c.describe("flat_per_triangle_unindexed");
}

// Flat points and lines keep the per-corner streams, built for them alone.
TEST_F(FlatPerTriangle, LinesKeepTheirCornerStreamsAndTrianglesGetNone) {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 16, 8), plastic({0.7, 0.7, 0.7}), glm::dmat4(1.0)});
    Primitive lines;
    lines.topology = Topology::Lines;
    lines.positions = {{-1.5f, -1.2f, 0.5f}, {1.5f, -1.2f, 0.5f}, {-1.5f, 1.2f, 0.5f}, {1.5f, 1.2f, 0.5f}};
    lines.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    s.objects.push_back({lines, plastic({0.2, 0.9, 0.2}), glm::dmat4(1.0)});
    s.lights.push_back({test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {0, 0, -1})});
    const Scene scene = s.build();
    RenderOptions o = test::optionsFor(64, 64, ShadingMode::Flat);
    auto buffers = device().upload(std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &scene));
    ASSERT_TRUE(buffers) << buffers.error().describe();
    FrameStats stats;
    auto frame = render::renderFrame(device(), *buffers, scene, o, 0.0, stats);
    ASSERT_TRUE(frame) << frame.error().describe();
    EXPECT_EQ(frame->readback.flatTriangles, scene.meshes[0].primitives[0].elementCount());
    // Two lines of two corners, 12 + 12 + 12 bytes each (position, normal, centroid), each
    // stream padded to 16 bytes, after the 16-byte header: far less than the sphere's corners.
    const std::size_t bytes = (*buffers)->flatGeometryBytes();
    EXPECT_GT(bytes, 0u);
    EXPECT_LT(bytes, 256u) << "the sphere's triangles got per-corner streams";
}

} // namespace
