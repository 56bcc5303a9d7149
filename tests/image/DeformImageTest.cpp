// Skinning and morph targets on the GPU against the CPU reference: a strip bent by a two-bone
// skin with 8 influences per vertex and a sphere inflated by an animated morph target,
// rendered at sampled times in every shading mode; the reference (reference/PixelReference
// over scene/Deform.cpp) must agree pixel by pixel, and must refuse a frame drawn without the
// deformation.
#include "DeformScenes.h"
#include "LightingCompare.h"

#include <gtest/gtest.h>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

Scene deformingScene() {
    Scene s = test::makeSkinnedStrip(16, true);
    AnimationSampler cubic;
    cubic.interpolation = Interpolation::CubicSpline;
    cubic.times = {0.0, 1.0};
    cubic.weights = {0.0, 0.0, 2.0, /* key 1: */ 0.0, 1.0, 0.0};
    test::addMorphingSphere(s, {1.0, -1.0, 0.0}, cubic);
    Light sun = test::makeLight(LightType::Directional);
    s.lights.push_back(sun);
    Node n;
    n.name = "sun";
    n.light = 0;
    n.rotation = glm::dquat(glm::dvec3(-0.7, 0.5, 0.0));
    s.nodes.push_back(n);
    s.roots[0].nodes.push_back(int(s.nodes.size()) - 1);
    return s;
}

class DeformImage : public GpuTest {};

TEST_F(DeformImage, GpuAgreesWithTheReferenceAtSampledTimes) {
    const Scene scene = deformingScene();
    ASSERT_TRUE(scene.validate());
    test::PixelCheck check;
    check.skipSilhouettes = true;
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat})
        for (double t : {0.0, 0.35, 1.0}) {
            const std::string name = std::string("deform_") + toString(mode) + "_" + std::to_string(t);
            SCOPED_TRACE(name);
            const RenderOptions o = test::optionsFor(96, 96, mode);
            const test::ReferenceComparison c = test::compareWithReference(device(), scene, o, check, {}, t);
            EXPECT_GT(c.compared, 300u);
            EXPECT_LE(c.worst, 2.0 / 255.0) << c.describe(name);
            EXPECT_EQ(c.frame.readback.nonFinite, 0u);
        }
}

TEST_F(DeformImage, TheDeformationMovesWhatIsDrawn) {
    const Scene scene = deformingScene();
    const RenderOptions o = test::optionsFor(64, 64, ShadingMode::Phong);
    auto a = test::renderWithIds(device(), scene, o, {}, 0.0);
    auto b = test::renderWithIds(device(), scene, o, {}, 1.0);
    ASSERT_TRUE(a && b);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a->readback.ids.size(); i += 2)
        differ += a->readback.ids[i] != b->readback.ids[i] ? 1 : 0;
    EXPECT_GT(differ, 100u) << "the pictures at t = 0 and t = 1 cover the same pixels";
}

TEST_F(DeformImage, AFrameDrawnWithoutTheDeformationFailsAgainstTheReference) {
    const Scene scene = deformingScene();
    const RenderOptions o = test::optionsFor(96, 96, ShadingMode::Phong);
    test::PixelCheck check;
    check.skipSilhouettes = true;
    render::FrameEdits bindPose;
    bindPose.list = [](gpu::DrawList& list) {
        for (gpu::ViewCommands& v : list.views)
            for (gpu::DrawCommand& d : v.draws) d.deform = -1;
        list.deforms.clear();
    };
    const test::ReferenceComparison c =
        test::compareWithReference(device(), scene, o, check, bindPose, 1.0);
    EXPECT_GT(c.worst, 0.05) << "the reference did not notice the undeformed mesh";
}

} // namespace
