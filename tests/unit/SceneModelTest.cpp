// The scene model: validation messages name the object, procedural meshes face outward,
// smooth normals are angle-weighted, animation sampling at and between keys.
#include <lantern/Io.h>
#include <lantern/Scene.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;

Scene oneTriangle() {
    Scene s;
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    s.meshes.push_back({"tri", {p}});
    Node n;
    n.mesh = 0;
    s.nodes.push_back(n);
    s.roots.push_back({"root", {0}, std::nullopt});
    return s;
}

TEST(SceneModel, ValidSceneValidates) { EXPECT_TRUE(oneTriangle().validate()); }

TEST(SceneModel, ValidationNamesTheObject) {
    struct Case {
        const char* expectObject;
        std::function<void(Scene&)> breakIt;
    };
    const Case cases[] = {
        {"meshes[0].primitives[0].indices[2]", [](Scene& s) { s.meshes[0].primitives[0].indices = {0, 1, 7}; }},
        {"meshes[0].primitives[0]", [](Scene& s) { s.meshes[0].primitives[0].normals.pop_back(); }},
        {"meshes[0].primitives[0].positions[1]",
         [](Scene& s) { s.meshes[0].primitives[0].positions[1].x = NAN; }},
        {"meshes[0].primitives[0].material", [](Scene& s) { s.meshes[0].primitives[0].material = 3; }},
        {"materials[0].shininess", [](Scene& s) {
             s.materials.emplace_back();
             s.materials[0].front.shininess = -1;
         }},
        {"lights[0].spotCutoffDeg", [](Scene& s) {
             s.lights.emplace_back();
             s.lights[0].spotCutoffDeg = 90.0001;
         }},
        {"lights[0].attenuation", [](Scene& s) {
             s.lights.emplace_back();
             s.lights[0].attenuation = {0, 0, 0};
         }},
        {"nodes[0].children[0]", [](Scene& s) { s.nodes[0].children = {0}; }},
        {"scenes[0].nodes[0]", [](Scene& s) { s.roots[0].nodes = {5}; }},
        {"cameras[0]", [](Scene& s) {
             Camera c;
             c.projection = Projection::makePerspective(1, 1, -1, 10);
             s.cameras.push_back(c);
         }},
    };
    for (const Case& c : cases) {
        Scene s = oneTriangle();
        c.breakIt(s);
        const auto r = s.validate();
        ASSERT_FALSE(r) << c.expectObject;
        EXPECT_EQ(r.error().object, c.expectObject) << r.error().describe();
        EXPECT_EQ(r.error().code, ErrorCode::InvalidInput);
    }
}

TEST(SceneModel, NodeCyclesAreRefused) {
    Scene s = oneTriangle();
    s.nodes.resize(3);
    s.nodes[1].children = {2};
    s.nodes[2].children = {1};
    const auto r = s.validate();
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("cycle"), std::string::npos) << r.error().describe();
}

void expectOutwardFaces(const Primitive& p, const char* what) {
    ASSERT_EQ(p.normals.size(), p.positions.size());
    for (std::size_t t = 0; t < p.triangleCount(); ++t) {
        const glm::vec3 a = p.positions[p.indices[t * 3]], b = p.positions[p.indices[t * 3 + 1]],
                        c = p.positions[p.indices[t * 3 + 2]];
        const glm::vec3 face = glm::cross(b - a, c - a);
        const glm::vec3 n = p.normals[p.indices[t * 3]] + p.normals[p.indices[t * 3 + 1]] +
                            p.normals[p.indices[t * 3 + 2]];
        ASSERT_GT(glm::dot(face, n), 0.0f) << what << " triangle " << t << " winds clockwise";
    }
}

TEST(SceneModel, ProceduralMeshesAreCounterClockwiseFromOutside) {
    expectOutwardFaces(makeSphere(1.0, 16, 8), "sphere");
    expectOutwardFaces(makePlane(2.0, 3), "plane");
    expectOutwardFaces(makeCube(2.0), "cube");
    const Primitive s = makeSphere(2.0, 32, 16);
    for (std::size_t i = 0; i < s.positions.size(); ++i)
        EXPECT_NEAR(glm::length(s.positions[i]), 2.0f, 1e-6f);
}

TEST(SceneModel, SmoothNormalsAreAngleWeighted) {
    // A vertex shared by a face with a 90 degree corner and a face with a 45 degree corner.
    std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}};
    std::vector<std::uint32_t> idx = {0, 1, 2, 0, 4, 3};  // normals +z and +y... see below
    const auto n = computeSmoothNormals(pos, idx);
    // Face A (0,1,2): normal +z, angle 90 deg at vertex 0. Face B (0,4,3): normal (-1,0,... )
    const glm::dvec3 fa(0, 0, 1);
    const glm::dvec3 fb = glm::normalize(glm::cross(glm::dvec3(1, 0, 1), glm::dvec3(0, 0, 1)));
    const double angleA = 3.14159265358979323846 / 2, angleB = 3.14159265358979323846 / 4;
    const glm::dvec3 expected = glm::normalize(fa * angleA + fb * angleB);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(n[0][i], expected[i], 1e-6);
    // A degenerate face contributes nothing; an unused vertex gets zero.
    const auto z = computeSmoothNormals({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {5, 5, 5}}, {0, 1, 2});
    EXPECT_EQ(z[3], glm::vec3(0.0f));
    EXPECT_EQ(z[0], glm::vec3(0.0f));
}

TEST(SceneModel, AnimationSamplingAtAndBetweenKeys) {
    AnimationSampler s;
    s.times = {1.0, 2.0, 4.0};
    s.values = {{0, 0, 0, 0}, {10, 0, 0, 0}, {10, 20, 0, 0}};
    s.interpolation = Interpolation::Linear;
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 0.0).x, 0.0);     // clamped before
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 1.5).x, 5.0);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 3.0).y, 10.0);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 9.0).y, 20.0);    // clamped after
    s.interpolation = Interpolation::Step;
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 1.99).x, 0.0);
    EXPECT_EQ(sampleAnimation(s, AnimationPath::Translation, 2.0).x, 10.0);
    // Rotation: slerp along the shorter arc between q and -q' gives the same as q and q'.
    AnimationSampler r;
    r.times = {0.0, 1.0};
    const double h = std::sqrt(0.5);
    r.values = {{0, 0, 0, 1}, {0, 0, -h, -h}};  // 90 degrees about z, stored negated
    const glm::dvec4 q = sampleAnimation(r, AnimationPath::Rotation, 0.5);
    const double angle = 2.0 * std::acos(std::abs(q.w));
    EXPECT_NEAR(angle, 3.14159265358979323846 / 4, 1e-12);  // 45 degrees, not 135
    // Cubic spline with zero tangents is smoothstep between values.
    AnimationSampler c;
    c.interpolation = Interpolation::CubicSpline;
    c.times = {0.0, 2.0};
    c.values = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {8, 0, 0, 0}, {0, 0, 0, 0}};
    EXPECT_DOUBLE_EQ(sampleAnimation(c, AnimationPath::Translation, 1.0).x, 4.0);
    EXPECT_DOUBLE_EQ(sampleAnimation(c, AnimationPath::Translation, 0.5).x, 8.0 * (3 * 0.0625 - 2 * 0.015625));
}

TEST(SceneModel, BuiltinScenesValidate) {
    for (const std::string& name : builtinSceneNames()) {
        auto s = builtinScene(name);
        ASSERT_TRUE(s) << name;
        EXPECT_TRUE(s->validate()) << name << ": " << s->validate().error().describe();
        EXPECT_GT(summarize(*s).triangles, 0u) << name;
    }
    const auto unknown = loadScene("builtin:nope");
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("spheres"), std::string::npos);
}

TEST(SceneModel, PoseComposesParentTransforms) {
    Scene s = oneTriangle();
    s.nodes[0].translation = {1, 0, 0};
    Node child;
    child.translation = {0, 2, 0};
    child.scale = {3, 3, 3};
    s.nodes.push_back(child);
    s.nodes[0].children = {1};
    const Pose p = evaluatePose(s, -1, 0.0);
    const glm::dvec4 origin = p.worldFromNode[1] * glm::dvec4(1, 0, 0, 1);
    EXPECT_DOUBLE_EQ(origin.x, 4.0);
    EXPECT_DOUBLE_EQ(origin.y, 2.0);
    EXPECT_TRUE(p.visible[1]);
}

} // namespace
