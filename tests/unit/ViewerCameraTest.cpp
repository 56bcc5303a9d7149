// The viewer's camera (apps/lantern/view/ViewerCamera): taking a scene camera over keeps the
// view, orbit/pan/zoom/fly move it as documented, the orthographic switch keeps the size of what
// is at the pivot, framing contains the bounds, and the printed command line gives back the very
// same doubles.
#include "TestSupport.h"
#include "common/CliSupport.h"
#include "view/ViewerCamera.h"
#include "view/ViewerState.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <fstream>

namespace {

using namespace lantern;
using lantern::cli::ViewerCamera;

double maxAbs(const glm::dmat4& a, const glm::dmat4& b) {
    double m = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m = std::max(m, std::abs(a[c][r] - b[c][r]));
    return m;
}

Bounds unitBounds() {
    Bounds b;
    b.extend({-1.0, -1.0, -1.0});
    b.extend({1.0, 1.0, 1.0});
    return b;
}

ViewerCamera takenOver(const LookAt& at, const Projection& p) {
    ViewerCamera cam;
    cam.setBounds(unitBounds());
    cam.takeOver(CameraPlacement{lookAt(at.eye, at.target, at.up), p, "test"});
    return cam;
}

glm::dmat4 viewOf(const CameraSpec& s) { return lookAt(s.lookAt->eye, s.lookAt->target, s.lookAt->up); }

TEST(ViewerCamera, UntouchedItIsTheBaseSpec) {
    ViewerCamera cam;
    CameraSpec base;
    base.source = CameraSpec::Source::SceneCamera;
    base.sceneCamera = 2;
    cam.setBase(base);
    EXPECT_FALSE(cam.isFree());
    const CameraSpec s = cam.spec(1.5);
    EXPECT_EQ(s.source, CameraSpec::Source::SceneCamera);
    EXPECT_EQ(s.sceneCamera, 2);
    EXPECT_FALSE(s.lookAt);
    EXPECT_EQ(cam.commandLine(1.5), " --camera 2");
}

TEST(ViewerCamera, TakingOverKeepsTheView) {
    struct Row {
        LookAt at;
        const char* why;
    };
    const Row rows[] = {
        {{{0, 2, 9}, {0, 0, 0}, {0, 1, 0}}, "looking down slightly"},
        {{{5, -3, 1}, {1, 0, -2}, {0, 1, 0}}, "from below, off-axis"},
        {{{-7, 0.5, -4}, {0, 0, 0}, {0, 1, 0}}, "from behind"},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(row.why);
        const Projection p = Projection::makePerspective(0.7, 0.0, 0.1, kInfinity);
        ViewerCamera cam = takenOver(row.at, p);
        ASSERT_TRUE(cam.isFree());
        const CameraSpec s = cam.spec(1.5);
        ASSERT_TRUE(s.lookAt && s.projection);
        EXPECT_LT(maxAbs(viewOf(s), lookAt(row.at.eye, row.at.target, row.at.up)), 1e-12);
        EXPECT_NEAR(s.projection->yfov, 0.7, 1e-15);
        EXPECT_EQ(s.projection->aspect, 1.5);
    }
}

TEST(ViewerCamera, OrbitTurnsAboutThePivotAndBack) {
    ViewerCamera cam = takenOver({{0, 2, 9}, {0, 0, 0}, {0, 1, 0}},
                                 Projection::makePerspective(0.7, 0.0, 0.1, kInfinity));
    const glm::dvec3 eye = cam.eye(), target = cam.target();
    cam.orbit(120.0, -40.0);
    EXPECT_GT(glm::length(cam.eye() - eye), 1.0);
    EXPECT_NEAR(glm::length(cam.eye() - cam.target()), glm::length(eye - target), 1e-12);
    EXPECT_EQ(cam.target(), target);
    cam.orbit(-120.0, 40.0);
    EXPECT_LT(glm::length(cam.eye() - eye), 1e-12);
}

TEST(ViewerCamera, PanMovesThePivotAcrossTheView) {
    ViewerCamera cam = takenOver({{0, 0, 5}, {0, 0, 0}, {0, 1, 0}},
                                 Projection::makePerspective(0.7, 0.0, 0.1, kInfinity));
    cam.pan(100.0, 0.0, 200.0);  // half the view's height to the right
    const glm::dvec3 moved = cam.target();
    EXPECT_NEAR(moved.y, 0.0, 1e-12);
    EXPECT_NEAR(moved.z, 0.0, 1e-12);
    // The scene follows the mouse: the pivot goes left by half the view's height at it.
    EXPECT_NEAR(moved.x, -5.0 * std::tan(0.35), 1e-9);
}

TEST(ViewerCamera, ZoomAndOrthographicKeepTheSizeAtThePivot) {
    ViewerCamera cam = takenOver({{0, 0, 5}, {0, 0, 0}, {0, 1, 0}},
                                 Projection::makePerspective(0.7, 0.0, 0.1, kInfinity));
    cam.zoom(1.0);
    EXPECT_NEAR(glm::length(cam.eye()), 4.5, 1e-12);
    cam.setOrthographic(true);
    CameraSpec s = cam.spec(2.0);
    ASSERT_EQ(s.projection->kind, ProjectionKind::Orthographic);
    const double halfHeight = 4.5 * std::tan(0.35);
    EXPECT_NEAR(s.projection->top, halfHeight, 1e-12);
    EXPECT_NEAR(s.projection->right, 2.0 * halfHeight, 1e-12);
    EXPECT_LT(s.projection->znear, 4.5 - 1.0);  // the bounds are inside the depth range
    EXPECT_GT(s.projection->zfar, 4.5 + 1.0);
    cam.setOrthographic(false);
    EXPECT_NEAR(glm::length(cam.eye()), 4.5, 1e-12);
}

TEST(ViewerCamera, FrameAllContainsTheBounds) {
    for (bool ortho : {false, true})
        for (double aspect : {0.5, 1.0, 2.5}) {
            SCOPED_TRACE(std::string(ortho ? "orthographic" : "perspective") + ", aspect " +
                         std::to_string(aspect));
            ViewerCamera cam = takenOver({{30, 20, 40}, {3, 0, 0}, {0, 1, 0}},
                                         Projection::makePerspective(0.7, 0.0, 0.1, kInfinity));
            cam.setOrthographic(ortho);
            cam.frameAll(aspect);
            const CameraSpec s = cam.spec(aspect);
            const glm::dmat4 clip = vulkanClipFromView(*s.projection, aspect, DepthMode::ReversedZ) * viewOf(s);
            for (int i = 0; i < 8; ++i) {
                const glm::dvec4 p = clip * glm::dvec4(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1, 1.0);
                EXPECT_LE(std::abs(p.x / p.w), 1.0);
                EXPECT_LE(std::abs(p.y / p.w), 1.0);
                EXPECT_GE(p.z / p.w, 0.0);
                EXPECT_LE(p.z / p.w, 1.0);
            }
        }
}

// The keypad views turn the free camera to look as `--view` does (straight up and down stop at
// the orbit's 89.5 degrees), then frame all.
TEST(ViewerCamera, NamedViewsLookAsTheCommandLineViewsDo) {
    for (ViewDirection v : kViewDirections) {
        ViewerCamera cam = takenOver({{3, 1, 4}, {0, 0, 0}, {0, 1, 0}},
                                     Projection::makePerspective(0.7, 0.0, 0.1, kInfinity));
        cam.lookFrom(v, 1.0);
        const glm::dvec3 want = glm::normalize(framingDirection(v));
        const bool vertical = std::abs(want.y) > 0.999;
        EXPECT_LT(glm::length(cam.forward() - want), vertical ? 0.01 : 1e-12) << toString(v);
        EXPECT_LT(glm::length(cam.target()), 1e-12) << toString(v) << ": the pivot is the centre";
        if (vertical) {
            EXPECT_LT(cam.forward().z, 0.0) << toString(v) << ": -Z is up on screen";
        }
    }
}

TEST(ViewerCamera, FlyTurnsAboutTheEyeAndMoves) {
    ViewerCamera cam = takenOver({{0, 0, 5}, {0, 0, 0}, {0, 1, 0}},
                                 Projection::makePerspective(0.7, 0.0, 0.1, kInfinity));
    const glm::dvec3 eye = cam.eye();
    cam.look(200.0, 50.0);
    EXPECT_LT(glm::length(cam.eye() - eye), 1e-12);
    const glm::dvec3 f = cam.forward();
    cam.move({0.0, 0.0, 1.0});  // one scene radius (sqrt 3 for the unit box) forward
    EXPECT_LT(glm::length(cam.eye() - (eye + f * std::sqrt(3.0))), 1e-12);
}

TEST(ViewerCamera, CommandLineGivesBackTheSameDoubles) {
    ViewerCamera cam = takenOver({{0.1, 2.3, 9.7}, {0.3, -0.2, 0.05}, {0, 1, 0}},
                                 Projection::makePerspective(0.6981317007977318, 0.0, 0.1, kInfinity));
    cam.orbit(33.3, 12.1);
    for (bool ortho : {false, true}) {
        cam.setOrthographic(ortho);
        const double aspect = 320.0 / 197.0;
        const CameraSpec s = cam.spec(aspect);
        const std::string line = cam.commandLine(aspect);
        // Re-parse the printed options as `lantern render` would.
        lantern::cli::CameraOptions parsed;
        auto option = [&](const std::string& name) {
            const auto at = line.find(name + " ");
            EXPECT_NE(at, std::string::npos) << line;
            const auto start = at + name.size() + 1;
            return line.substr(start, line.find(' ', start) - start);
        };
        parsed.lookAt = option("--look-at");
        if (ortho)
            parsed.ortho = option("--ortho");
        else
            parsed.perspective = option("--perspective");
        RenderOptions o;
        ASSERT_TRUE(parsed.apply(o));
        ASSERT_TRUE(o.camera.lookAt && o.camera.projection);
        EXPECT_EQ(o.camera.lookAt->eye, s.lookAt->eye);
        EXPECT_EQ(o.camera.lookAt->target, s.lookAt->target);
        const Projection& a = *o.camera.projection;
        const Projection& b = *s.projection;
        EXPECT_EQ(a.kind, b.kind);
        EXPECT_EQ(a.yfov, b.yfov);
        EXPECT_EQ(a.aspect, b.aspect);
        EXPECT_EQ(a.left, b.left);
        EXPECT_EQ(a.top, b.top);
        EXPECT_EQ(a.znear, b.znear);
        EXPECT_EQ(a.zfar, b.zfar);
    }
}

TEST(ViewerDocs, EveryKeyOfTheHelpOverlayIsInDocsViewerMd) {
    std::ifstream in(lantern::test::sourceDir() / "docs" / "viewer.md");
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(doc.empty());
    for (const lantern::cli::KeyHelp& k : lantern::cli::viewerKeys()) {
        const std::string row = std::string("| ") + k.keys + " | " + k.action + " |";
        EXPECT_NE(doc.find(row), std::string::npos) << "docs/viewer.md lacks the row: " << row;
    }
}

} // namespace
