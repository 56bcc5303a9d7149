// Skinning and morph targets on the CPU: poses, deformed vertices and bounds against values
// worked out by hand (rotations of a two-bone strip, Hermite and linear weight curves), and the
// scene model's refusals of bad skins and morph targets.
#include "DeformScenes.h"

#include <lantern/Scene.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using lantern::test::makeSkinnedStrip;

constexpr double kTol = 1e-6;

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Vertex index of column i (x = 2i/8), row r (0: y = -0.25, 1: y = +0.25) of an 8-segment strip.
std::size_t vertex(int i, int r) { return std::size_t(2 * i + r); }

TEST(Deform, TwoBoneStripBendsAsTheJointsRotate) {
    const Scene s = makeSkinnedStrip();
    ASSERT_TRUE(s.validate());
    const Primitive& prim = s.meshes[0].primitives[0];
    ASSERT_TRUE(isSkinned(s, 2, prim));
    // t = 1: bone 1 turned 90 degrees about +Y around (1, 0, 0): (x, y, z) - (1, 0, 0) goes to
    // (z, y, -x). The end column (x = 2) follows bone 1 only; the node's (5, 5, 5) is ignored.
    const Pose p1 = evaluatePose(s, -1, 1.0);
    const DeformedPrimitive d1 = deformPrimitive(s, p1, 2, prim);
    expectNear(d1.positions[vertex(8, 1)], {1.0, 0.25, -1.0});
    expectNear(d1.normals[vertex(8, 1)], {1.0, 0.0, 0.0});
    // x <= 0.5 follows bone 0, which does not move.
    expectNear(d1.positions[vertex(1, 0)], {0.25, -0.25, 0.0});
    expectNear(d1.normals[vertex(1, 0)], {0.0, 0.0, 1.0});
    // x = 1 is half on each bone; both put it at (1, y, 0). Its normal is the cofactor of the
    // average of I and a 90 degree turn: the normal turned 45 degrees.
    expectNear(d1.positions[vertex(4, 1)], {1.0, 0.25, 0.0});
    expectNear(d1.normals[vertex(4, 1)], {std::sqrt(0.5), 0.0, std::sqrt(0.5)});
    // t = 0.5: 45 degrees (LINEAR slerp): (1, 0.25, 0) relative to bone 1 goes to
    // (cos45, 0.25, -sin45).
    const Pose ph = evaluatePose(s, -1, 0.5);
    const DeformedPrimitive dh = deformPrimitive(s, ph, 2, prim);
    expectNear(dh.positions[vertex(8, 1)], {1.0 + std::sqrt(0.5), 0.25, -std::sqrt(0.5)});
    // t = 0: the bind pose, in world space (the strip node's translation does not apply).
    const DeformedPrimitive d0 = deformPrimitive(s, evaluatePose(s, -1, 0.0), 2, prim);
    for (std::size_t v = 0; v < prim.positions.size(); ++v)
        expectNear(d0.positions[v], glm::dvec3(prim.positions[v]));
    EXPECT_EQ(worldFromDrawn(s, p1, 2, prim), glm::dmat4(1.0));
}

TEST(Deform, EightInfluencesGiveTheSameAsFour) {
    const Scene four = makeSkinnedStrip(8, false), eight = makeSkinnedStrip(8, true);
    ASSERT_TRUE(eight.validate());
    ASSERT_FALSE(eight.meshes[0].primitives[0].joints1.empty());
    for (double t : {0.0, 0.3, 1.0}) {
        const DeformedPrimitive a = deformPrimitive(four, evaluatePose(four, -1, t), 2, four.meshes[0].primitives[0]);
        const DeformedPrimitive b = deformPrimitive(eight, evaluatePose(eight, -1, t), 2, eight.meshes[0].primitives[0]);
        for (std::size_t v = 0; v < a.positions.size(); ++v) {
            expectNear(a.positions[v], b.positions[v], 1e-6);
            expectNear(a.normals[v], b.normals[v], 1e-6);
        }
    }
}

TEST(Deform, EachOfEightJointsContributesItsWeight) {
    // One vertex at the origin, eight joints each translated to e_k * (k + 1), weights 1/8.
    Scene s;
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.normals.assign(3, glm::vec3(0, 0, 1));
    for (int v = 0; v < 3; ++v) {
        p.joints0.push_back({0, 1, 2, 3});
        p.joints1.push_back({4, 5, 6, 7});
        p.weights0.push_back(glm::vec4(0.125f));
        p.weights1.push_back(glm::vec4(0.125f));
    }
    s.meshes.push_back(Mesh{"m", {p}, {}});
    Skin skin;
    glm::dvec3 mean(0.0);
    for (int k = 0; k < 8; ++k) {
        Node j;
        j.translation = glm::dvec3(k % 3 == 0, k % 3 == 1, k % 3 == 2) * double(k + 1);
        mean += j.translation / 8.0;
        s.nodes.push_back(j);
        skin.joints.push_back(k);
        skin.inverseBind.push_back(glm::dmat4(1.0));
    }
    s.skins.push_back(skin);
    Node n;
    n.mesh = 0;
    n.skin = 0;
    s.nodes.push_back(n);
    s.roots.push_back(SceneRoot{"", {0, 1, 2, 3, 4, 5, 6, 7, 8}, std::nullopt});
    ASSERT_TRUE(s.validate());
    const DeformedPrimitive d = deformPrimitive(s, evaluatePose(s, -1, 0.0), 8, s.meshes[0].primitives[0]);
    expectNear(d.positions[0], mean);
    expectNear(d.positions[1], mean + glm::dvec3(1, 0, 0));
}

TEST(Deform, ZeroWeightsLeaveTheVertexInBindSpace) {
    Scene s = makeSkinnedStrip();
    s.meshes[0].primitives[0].weights0[3] = glm::vec4(0.0f);
    const DeformedPrimitive d = deformPrimitive(s, evaluatePose(s, -1, 1.0), 2, s.meshes[0].primitives[0]);
    expectNear(d.positions[3], glm::dvec3(s.meshes[0].primitives[0].positions[3]));
}

TEST(Deform, BoundsAndFramingFollowTheDeformedMesh) {
    const Scene s = makeSkinnedStrip();
    const Bounds b1 = computeBounds(s, evaluatePose(s, -1, 1.0));
    EXPECT_NEAR(b1.min.z, -1.0, kTol);  // the bent end reaches z = -1
    // After the bend a column at x with bone-1 weight w lands at x' = (1 - w) x + w * 1: the
    // furthest is x = 1.25 (w = 0.75): 0.3125 + 0.75.
    EXPECT_NEAR(b1.max.x, 1.0625, kTol);
    const Bounds b0 = computeBounds(s, evaluatePose(s, -1, 0.0));
    EXPECT_NEAR(b0.max.x, 2.0, kTol);
    EXPECT_NEAR(b0.min.z, 0.0, kTol);
    EXPECT_LT(b0.max.y, 1.0);  // not at the node's (5, 5, 5)
}

TEST(Deform, WeightCurvesInterpolateLinearStepAndCubic) {
    AnimationSampler lin;
    lin.interpolation = Interpolation::Linear;
    lin.times = {0.0, 1.0};
    lin.weightCount = 2;
    lin.weights = {0.0, 1.0, 1.0, 0.5};
    std::vector<double> w = sampleWeights(lin, 0.25);
    ASSERT_EQ(w.size(), 2u);
    EXPECT_NEAR(w[0], 0.25, 1e-12);
    EXPECT_NEAR(w[1], 0.875, 1e-12);
    EXPECT_EQ(sampleWeights(lin, -1.0), (std::vector<double>{0.0, 1.0}));
    EXPECT_EQ(sampleWeights(lin, 9.0), (std::vector<double>{1.0, 0.5}));

    AnimationSampler step = lin;
    step.interpolation = Interpolation::Step;
    EXPECT_EQ(sampleWeights(step, 0.99), (std::vector<double>{0.0, 1.0}));

    // Hermite over [0, 2] from 0 (out-tangent 1) to 1 (in-tangent 0); at s = 1/2:
    // h00 0 + h10 dt m0 + h01 1 + h11 dt m1 = 0.125 * 2 + 0.5 = 0.75.
    AnimationSampler cubic;
    cubic.interpolation = Interpolation::CubicSpline;
    cubic.times = {0.0, 2.0};
    cubic.weightCount = 1;
    cubic.weights = {0.0, 0.0, 1.0, /* key 1: */ 0.0, 1.0, 0.0};
    EXPECT_NEAR(sampleWeights(cubic, 1.0)[0], 0.75, 1e-12);
    EXPECT_NEAR(sampleWeights(cubic, 0.0)[0], 0.0, 1e-12);
    EXPECT_NEAR(sampleWeights(cubic, 2.0)[0], 1.0, 1e-12);
}

TEST(Deform, MorphTargetsBlendByAnimatedDefaultAndNodeWeights) {
    Scene s = makeSkinnedStrip();
    AnimationSampler smp;
    smp.interpolation = Interpolation::Linear;
    smp.times = {1.0, 3.0};
    smp.weights = {0.0, 1.0};
    const int node = lantern::test::addMorphingSphere(s, {3, 0, 0}, smp);
    ASSERT_TRUE(s.validate());
    const Primitive& prim = s.meshes[1].primitives[0];
    EXPECT_FALSE(isSkinned(s, node, prim));
    EXPECT_TRUE(isDeformed(s, node, prim));
    // At t = 2 the weight is 0.5: radius 0.5 + 0.5 * 0.3, in the node's space.
    const Pose pose = evaluatePose(s, -1, 2.0);
    ASSERT_EQ(pose.morphWeights[std::size_t(node)].size(), 1u);
    EXPECT_NEAR(pose.morphWeights[std::size_t(node)][0], 0.5, 1e-12);
    const DeformedPrimitive d = deformPrimitive(s, pose, node, prim);
    for (std::size_t v = 0; v < d.positions.size(); ++v)
        EXPECT_NEAR(glm::length(d.positions[v]), 0.65, 1e-6) << v;
    // Without the animation: the node's weights, else the mesh's (0.25).
    s.animations.pop_back();
    EXPECT_NEAR(evaluatePose(s, -1, 2.0).morphWeights[std::size_t(node)][0], 0.25, 1e-12);
    s.nodes[std::size_t(node)].weights = {1.0};
    const DeformedPrimitive full = deformPrimitive(s, evaluatePose(s, -1, 0.0), node, prim);
    EXPECT_NEAR(glm::length(full.positions[0]), 0.8, 1e-6);
    EXPECT_NEAR(computeBounds(s, evaluatePose(s, -1, 0.0)).max.x, 3.8, 1e-3);
}

TEST(Deform, ValidationRefusesBadSkinsAndTargetsWithTheObject) {
    {
        Scene s = makeSkinnedStrip();
        s.meshes[0].primitives[0].joints0[5] = glm::uvec4(0, 2, 0, 0);
        auto r = s.validate();
        ASSERT_FALSE(r);
        EXPECT_EQ(r.error().object, "meshes[0].primitives[0].joints");
        EXPECT_NE(r.error().message.find("out of range"), std::string::npos) << r.error().describe();
    }
    {
        Scene s = makeSkinnedStrip();
        s.meshes[0].primitives[0].weights0[3].y = -0.5f;
        auto r = s.validate();
        ASSERT_FALSE(r);
        EXPECT_EQ(r.error().object, "meshes[0].primitives[0].weights0[3]");
    }
    {
        Scene s = makeSkinnedStrip();
        s.meshes[0].primitives[0].weights0[3].y = std::nanf("");
        EXPECT_FALSE(s.validate());
    }
    {
        Scene s = makeSkinnedStrip();
        s.skins[0].joints = {0, 7};
        auto r = s.validate();
        ASSERT_FALSE(r);
        EXPECT_EQ(r.error().object, "skins[0].joints[1]");
    }
    {
        Scene s = makeSkinnedStrip();
        s.skins[0].inverseBind.pop_back();
        EXPECT_FALSE(s.validate());
    }
    {
        Scene s = makeSkinnedStrip();
        s.nodes[2].skin = 3;
        auto r = s.validate();
        ASSERT_FALSE(r);
        EXPECT_EQ(r.error().object, "nodes[2].skin");
    }
    {
        Scene s = makeSkinnedStrip();
        AnimationSampler smp;
        smp.times = {0.0, 1.0};
        smp.weights = {0.0, 1.0};
        const int node = lantern::test::addMorphingSphere(s, {3, 0, 0}, smp);
        s.nodes[std::size_t(node)].weights = {0.1, 0.2};
        auto r = s.validate();
        ASSERT_FALSE(r);
        EXPECT_EQ(r.error().object, "nodes[" + std::to_string(node) + "].weights");
        s.nodes[std::size_t(node)].weights = {};
        s.meshes[1].primitives[0].targets[0].positions.pop_back();
        EXPECT_FALSE(s.validate());
        s.meshes[1].primitives[0].targets[0].positions.clear();
        ASSERT_TRUE(s.validate());
        s.animations.back().samplers[0].weights.push_back(0.5);
        EXPECT_FALSE(s.validate());
    }
}

} // namespace
