// Automatic framing and the named views: the default three-quarter view from above sees a
// scene lying in any axis plane at 30 degrees or more (never edge-on), the bounding sphere
// fits the view with the near and far planes around it, the named views look from where
// their names say, and a valid scene that draws nothing frames and builds without error.
#include "frame/Frame.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace {

using namespace lantern;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

Scene planeScene(const glm::dmat4& model) {
    Scene s;
    s.meshes.push_back({"plane", {makePlane(2.0, 1)}});
    Node n;
    n.mesh = 0;
    n.matrix = model;
    s.nodes.push_back(n);
    s.roots.push_back(SceneRoot{"root", {0}, std::nullopt});
    return s;
}

frame::ViewCamera automatic(const Scene& s, const CameraSpec& spec = {}) {
    const Pose pose = evaluatePose(s, -1, 0.0);
    auto cam = frame::resolveCamera(s, pose, spec, 1.0, DepthMode::ReversedZ, "camera");
    EXPECT_TRUE(cam) << cam.error().describe();
    return cam ? *cam : frame::ViewCamera{};
}

// The camera's viewing direction in world space.
glm::dvec3 lookDirection(const frame::ViewCamera& c) {
    const glm::dmat4 worldFromView = glm::inverse(c.viewFromWorld);
    return glm::normalize(glm::dvec3(worldFromView * glm::dvec4(0, 0, -1, 0)));
}

TEST(Framing, NamedViewsLookFromWhereTheirNamesSay) {
    struct Row {
        ViewDirection view;
        glm::dvec3 from;
    };
    for (const Row& r : {Row{ViewDirection::Front, {0, 0, 1}}, Row{ViewDirection::Back, {0, 0, -1}},
                         Row{ViewDirection::Left, {-1, 0, 0}}, Row{ViewDirection::Right, {1, 0, 0}},
                         Row{ViewDirection::Top, {0, 1, 0}}, Row{ViewDirection::Bottom, {0, -1, 0}},
                         Row{ViewDirection::Iso, glm::normalize(glm::dvec3(1, 1, 1))}}) {
        EXPECT_LT(glm::length(framingDirection(r.view) + r.from), 1e-12) << toString(r.view);
        EXPECT_EQ(parseViewDirection(toString(r.view)), r.view);
        CameraSpec spec;
        spec.source = CameraSpec::Source::Framing;
        spec.framingDirection = framingDirection(r.view);
        const frame::ViewCamera c = automatic(planeScene(glm::dmat4(1.0)), spec);
        EXPECT_LT(glm::length(lookDirection(c) + r.from), 1e-9) << toString(r.view);
    }
    EXPECT_FALSE(parseViewDirection("diagonal"));
    // The default: front right, above.
    const glm::dvec3 from = -framingDirection(ViewDirection::ThreeQuarter);
    EXPECT_NEAR(std::asin(from.y), 30.0 * kDeg, 1e-12);
    EXPECT_NEAR(std::atan2(from.x, from.z), 45.0 * kDeg, 1e-12);
    EXPECT_LT(glm::length(CameraSpec{}.framingDirection - framingDirection(ViewDirection::ThreeQuarter)),
              1e-15);
}

// A plane in each axis plane (XZ: a ground; XY: a wall facing the front; YZ: a wall facing
// the side) is seen by the default camera at 30 degrees or more.
TEST(Framing, TheDefaultViewIsNeverEdgeOnToAnAxisPlane) {
    const glm::dmat4 identity(1.0);
    struct Row {
        const char* name;
        glm::dmat4 model;
        glm::dvec3 normal;
    };
    const glm::dmat4 ground = glm::dmat4(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);  // XY -> XZ
    const glm::dmat4 side = glm::dmat4(0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1);     // XY -> YZ
    for (const Row& r : {Row{"ground (XZ)", ground, {0, 1, 0}}, Row{"front wall (XY)", identity, {0, 0, 1}},
                         Row{"side wall (YZ)", side, {1, 0, 0}}}) {
        const frame::ViewCamera c = automatic(planeScene(r.model));
        const double sine = std::abs(glm::dot(lookDirection(c), r.normal));
        EXPECT_GE(sine, std::sin(30.0 * kDeg) - 1e-12) << r.name;
        // And the plane is in front of the camera, inside the fitted depth range.
        const Projection& p = c.projection;
        EXPECT_TRUE(std::isfinite(p.zfar)) << r.name << ": the far plane is fitted";
        const double d = glm::length(glm::dvec3(glm::inverse(c.viewFromWorld)[3]));
        const double radius = std::sqrt(2.0);  // the 2x2 plane's bounding sphere
        EXPECT_LE(p.znear, d - radius) << r.name;
        EXPECT_GE(p.zfar, d + radius) << r.name;
        EXPECT_GT(p.znear, 0.0) << r.name;
    }
}

TEST(Framing, AValidSceneThatDrawsNothingBuildsAnEmptyFrameAndSaysWhy) {
    Scene none;  // no scene, no node
    ASSERT_TRUE(none.validate()) << none.validate().error().describe();
    EXPECT_EQ(nothingToDraw(none).value_or(""), "the file defines no scene and no node");
    RenderOptions o;
    o.width = o.height = 16;
    auto f = frame::buildFrame(none, o, 0.0);
    ASSERT_TRUE(f) << f.error().describe();
    EXPECT_EQ(f->drawCount(), 0u);

    Scene emptyRoot;
    emptyRoot.roots.push_back(SceneRoot{"Empty", {}, std::nullopt});
    ASSERT_TRUE(emptyRoot.validate());
    EXPECT_EQ(nothingToDraw(emptyRoot).value_or(""), "scene 0 \"Empty\" has no nodes");

    Scene lonely = planeScene(glm::dmat4(1.0));
    lonely.nodes[0].mesh = -1;
    EXPECT_EQ(nothingToDraw(lonely).value_or(""),
              "no node of scene 0 \"root\" draws a mesh with anything in it");
    EXPECT_FALSE(nothingToDraw(planeScene(glm::dmat4(1.0))));
}

} // namespace
