// What the viewer asks of the renderer, headless: scene edits between frames are seen (the
// rule in Renderer::prepare), the wireframe and normals overlays draw only their own colour
// over the picture, lights can follow the camera, and resolveCameraPlacement() is the camera a
// render uses.
#include "TestSupport.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::maxAbsDifference;

class ViewerFeatures : public GpuTest {};

RenderOptions small(int w = 96, int h = 64) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    return o;
}

TEST_F(ViewerFeatures, EditsBetweenFramesAreSeenByThePreparedScene) {
    auto built = builtinScene("spheres");
    ASSERT_TRUE(built);
    auto scene = std::make_shared<Scene>(std::move(*built));
    auto prepared = renderer().prepare(scene);
    ASSERT_TRUE(prepared);
    auto before = renderer().render(*prepared, small(), 0.0);
    ASSERT_TRUE(before);
    // What the viewer's panel edits: a material, a light's colour and its node's position.
    scene->materials[0].front.diffuse = {0.0, 0.6, 0.9, 1.0};
    scene->materials[0].front.shininess = 90.0;
    scene->lights[1].diffuse = {1.0, 0.2, 0.2};
    scene->nodes[5].translation = {-3.0, 2.0, 3.0};
    ASSERT_EQ(scene->nodes[5].light, 1);
    auto edited = renderer().render(*prepared, small(), 0.0);
    ASSERT_TRUE(edited);
    // The same edits prepared afresh give the same picture.
    auto fresh = renderer().prepare(std::make_shared<const Scene>(*scene));
    ASSERT_TRUE(fresh);
    auto expected = renderer().render(*fresh, small(), 0.0);
    ASSERT_TRUE(expected);
    EXPECT_EQ(maxAbsDifference(*edited, *expected), 0.0f)
        << lantern::test::saveComparison(*edited, *expected, "live-edit");
    EXPECT_GT(maxAbsDifference(*edited, *before), 0.2f);
}

struct OverlayRow {
    const char* name;
    bool wireframe, normals;
    DepthMode depth;
    int msaa;
    const char* why;
};

TEST_F(ViewerFeatures, OverlaysDrawOnlyTheirColourOverThePicture) {
    const OverlayRow rows[] = {
        {"wireframe", true, false, DepthMode::ReversedZ, 1, "edges over the shaded triangles"},
        {"normals", false, true, DepthMode::ReversedZ, 1, "a line from each vertex"},
        {"both", true, true, DepthMode::ReversedZ, 1, "both at once"},
        {"standard-z", true, false, DepthMode::Standard, 1, "the depth bias flips with the depth mode"},
        {"msaa", true, true, DepthMode::ReversedZ, 4, "multisampled (edges blend: colours not checked)"},
    };
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    const glm::vec3 wire(1.0f, 0.55f, 0.1f), normal(0.1f, 0.75f, 1.0f);
    for (const OverlayRow& row : rows) {
        SCOPED_TRACE(std::string(row.name) + ": " + row.why);
        RenderOptions o = small(128, 80);
        o.depth = row.depth;
        o.msaa = row.msaa;
        if (std::find(renderer().device().msaaSampleCounts.begin(),
                      renderer().device().msaaSampleCounts.end(),
                      row.msaa) == renderer().device().msaaSampleCounts.end())
            continue;
        auto plain = renderer().render(*scene, o, 0.0);
        ASSERT_TRUE(plain);
        o.wireframe = row.wireframe;
        o.normals = row.normals;
        auto drawn = renderer().render(*scene, o, 0.0);
        ASSERT_TRUE(drawn) << drawn.error().describe();
        EXPECT_EQ(lantern::test::countNonFinite(*drawn), 0u);
        std::size_t changed = 0, wrongColour = 0;
        for (std::size_t i = 0; i < drawn->pixelCount(); ++i) {
            const float* a = &drawn->rgba[i * 4];
            const float* b = &plain->rgba[i * 4];
            if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) continue;
            ++changed;
            const glm::vec3 c(a[0], a[1], a[2]);
            const bool isWire = row.wireframe && glm::length(c - wire) < 1e-6f;
            const bool isNormal = row.normals && glm::length(c - normal) < 1e-6f;
            if (!isWire && !isNormal) ++wrongColour;
        }
        EXPECT_GT(changed, std::size_t(300));
        EXPECT_LT(changed, drawn->pixelCount() / 2) << "lines, not filled triangles";
        if (row.msaa == 1) {
            EXPECT_EQ(wrongColour, 0u);
        }
    }
}

TEST_F(ViewerFeatures, OverlaysAreNotCombinedWithAovs) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    RenderOptions o = small();
    o.wireframe = true;
    o.aovs.depth = true;
    auto r = renderer().render(*scene, o, 0.0);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::InvalidInput);
    EXPECT_NE(r.error().message.find("AOV"), std::string::npos);
}

TEST_F(ViewerFeatures, LightsThatFollowTheCameraTurnWithIt) {
    // A sphere lit by a point light; the camera orbits it by 90 degrees about +Y. With lights
    // in the world the lit side stays put (the pictures differ); with the lights fixed to each
    // camera they turn along and, the sphere being symmetric, both pictures agree.
    lantern::test::SimpleScene s;
    s.primitive = makeSphere(1.0, 64, 32);
    s.material.front.diffuse = {0.8, 0.7, 0.6, 1.0};
    s.material.front.specular = {0.5, 0.5, 0.5};
    s.material.front.shininess = 30.0;
    Light lamp;
    lamp.type = LightType::Point;
    s.lights.push_back({lamp, glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 2.0, 2.0))});
    const Scene scene = s.build();
    auto view = [](double degrees) {
        const double a = degrees * 3.14159265358979323846 / 180.0;
        CameraSpec c;
        c.source = CameraSpec::Source::SceneCamera;
        c.sceneCamera = 0;
        c.lookAt = LookAt{{4.0 * std::sin(a), 0.0, 4.0 * std::cos(a)}, {0, 0, 0}, {0, 1, 0}};
        return c;
    };
    auto renderFrom = [&](double degrees, bool follow) {
        RenderOptions o = small(80, 80);
        o.camera = view(degrees);
        if (follow) {
            auto p = resolveCameraPlacement(scene, o.camera, 1.0);
            EXPECT_TRUE(p);
            // Fixed to the camera at 0 degrees: where the lamp sits relative to that camera.
            auto p0 = resolveCameraPlacement(scene, view(0.0), 1.0);
            EXPECT_TRUE(p0);
            o.lightsViewFromWorld = p0->viewFromWorld;
        }
        auto img = renderer().render(scene, o, 0.0);
        EXPECT_TRUE(img);
        return img ? *img : Image{};
    };
    const Image world0 = renderFrom(0.0, false), world90 = renderFrom(90.0, false);
    const Image head0 = renderFrom(0.0, true), head90 = renderFrom(90.0, true);
    EXPECT_EQ(maxAbsDifference(head0, world0), 0.0f) << "fixed where the camera stands: no change";
    EXPECT_GT(maxAbsDifference(world90, world0), 0.2f);
    // The tessellation is symmetric under a quarter turn up to float rounding of its vertices.
    EXPECT_LT(maxAbsDifference(head90, head0), 2e-3f)
        << lantern::test::saveComparison(head90, head0, "headlight");
}

TEST_F(ViewerFeatures, CameraPlacementIsTheCameraARenderUses) {
    auto scene = builtinScene("spheres");
    ASSERT_TRUE(scene);
    for (CameraSpec::Source source : {CameraSpec::Source::Automatic, CameraSpec::Source::Framing,
                                      CameraSpec::Source::GlDefault}) {
        CameraSpec spec;
        spec.source = source;
        RenderOptions o = small(96, 64);
        o.camera = spec;
        auto img = renderer().render(*scene, o, 0.0);
        ASSERT_TRUE(img);
        ASSERT_TRUE(img->camera);
        auto placement = resolveCameraPlacement(*scene, spec, 96.0 / 64.0);
        ASSERT_TRUE(placement);
        EXPECT_EQ(placement->viewFromWorld, img->camera->viewFromWorld);
    }
    CameraSpec missing;
    missing.source = CameraSpec::Source::SceneCamera;
    missing.sceneCamera = 7;
    auto bad = resolveCameraPlacement(*scene, missing, 1.0);
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, ErrorCode::InvalidInput);
    EXPECT_FALSE(resolveCameraPlacement(*scene, CameraSpec{}, 0.0));
}

} // namespace
