// Cluster culling and levels of detail (gpu/Clusters.h, shaders/cull.comp): the clusters a view
// cannot see (outside it, or facing away where back faces are culled) are not drawn, and the
// picture is bit-identical to drawing everything, whatever the camera (inside a grid of
// meshes, moving, orthographic, several views), the transforms (instanced, scaled unevenly,
// sheared, mirrored), the sides (double-sided meshes) and the samples; every built-in scene
// too. A level-of-detail bound draws fewer triangles, and 0 draws the exact picture.
#include "LightingCompare.h"

#include <gtest/gtest.h>
#include <lantern/Io.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>

namespace {

using namespace lantern;

constexpr int kW = 128, kH = 96;

// A cube of side 2 s whose faces are n x n quads each, face after face (each face's triangles
// are neighbours in the list, so its clusters face one way, as in a mesh a tool ordered).
Primitive tiledBox(double s, int n) {
    Primitive p;
    const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::dvec3& a : axes) {
        const glm::dvec3 u = std::abs(a.x) > 0 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
        const glm::dvec3 v = glm::cross(a, u);
        const auto first = std::uint32_t(p.positions.size());
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const glm::dvec3 q = s * (a + (2.0 * i / n - 1.0) * u + (2.0 * j / n - 1.0) * v);
                p.positions.push_back(glm::vec3(q));
                p.normals.push_back(glm::vec3(a));
            }
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const std::uint32_t k = first + std::uint32_t(j * (n + 1) + i), r = std::uint32_t(n + 1);
                p.indices.insert(p.indices.end(), {k, k + 1, k + r + 1, k, k + r + 1, k + r});
            }
    }
    return p;
}

class ClusterCulling : public test::RenderTest {
protected:
    // A 6 x 6 x 3 grid of spheres of 1,984 triangles (16 clusters) sharing one mesh, plus
    // three of their own: scaled unevenly, sheared and mirrored, and a double-sided one.
    static Scene grid() {
        test::LitScene s;
        const Material plastic =
            test::phongMaterial({0.2, 0.1, 0.05}, {0.8, 0.5, 0.3, 1.0}, {0.9, 0.9, 0.9}, 30.0);
        s.objects.push_back({makeSphere(0.35, 32, 32), plastic, test::translation({0, 0, 0})});
        Material twoSided = plastic;
        twoSided.doubleSided = true;
        const glm::dmat4 placed[3] = {glm::scale(test::translation({1, 1, -1}), glm::dvec3(1.6, 0.7, 1.0)),
                                      test::translation({-1, 1, -1}),
                                      glm::scale(test::translation({0, -1, -1}), glm::dvec3(-1, 1, 1))};
        for (int k = 0; k < 3; ++k) s.objects.push_back({makeSphere(0.3, 24, 24), plastic, placed[k]});
        s.objects[2].model[1][0] = 0.4;  // shear x by y
        s.objects.push_back({makeSphere(0.3, 24, 24), twoSided, test::translation({1, -1, -1})});
        Light point = test::makeLight(LightType::Point);
        point.attenuation = {1.0, 0.02, 0.0};
        s.lights.push_back({point, test::translation({1.0, 2.5, 3.0})});
        Scene scene = s.build();
        for (int i = 0; i < 6 * 6 * 3; ++i) {
            Node n;
            n.name = "grid " + std::to_string(i);
            n.mesh = 0;
            n.matrix = test::translation({-2.5 + (i % 6), -2.5 + (i / 6 % 6), -2.0 - 1.5 * (i / 36)});
            scene.roots[0].nodes.push_back(int(scene.nodes.size()));
            scene.nodes.push_back(n);
        }
        return scene;
    }

    static RenderOptions looking(const glm::dvec3& eye, const glm::dvec3& target) {
        RenderOptions o = test::optionsFor(kW, kH, ShadingMode::Phong);
        o.camera.lookAt = LookAt{eye, target, {0, 1, 0}};
        return o;
    }

    // Renders `scene` culled and not; expects the same bytes and returns the share of the
    // clustered triangles the culled frame drew.
    double expectIdentical(const Scene& scene, const RenderOptions& o) {
        RenderOptions all = o;
        all.culling = false;
        const Image everything = render(scene, all);
        EXPECT_EQ(renderer().lastFrameStats().clusterTriangles, 0u) << "culling off clusters nothing";
        const Image culled = render(scene, o);
        const FrameStats stats = renderer().lastFrameStats();
        EXPECT_EQ(culled.rgba.size(), everything.rgba.size());
        EXPECT_TRUE(culled.rgba.size() == everything.rgba.size() &&
                    std::memcmp(culled.rgba.data(), everything.rgba.data(), culled.rgba.size() * 4) == 0)
            << "culling changed the picture: " << test::saveComparison(culled, everything, "cluster-culling");
        EXPECT_LE(stats.clusterTrianglesDrawn, stats.clusterTriangles);
        return stats.clusterTriangles > 0 ? double(stats.clusterTrianglesDrawn) / double(stats.clusterTriangles) : 1.0;
    }
};

// Inside the grid, looking along it: most clusters are behind the eye or beside the view, and
// half of each sphere faces away.
TEST_F(ClusterCulling, InsideTheGridDropsMostClustersAndNoPixel) {
    const Scene scene = grid();
    const double drawn = expectIdentical(scene, looking({0.3, 0.2, -2.2}, {-2.0, -1.0, -6.0}));
    std::printf("inside the grid: %.1f %% of the clustered triangles drawn\n", 100.0 * drawn);
    EXPECT_LT(drawn, 0.35);
    EXPECT_GT(drawn, 0.0) << "something is in view";
}

// A lookAt among the meshes of a scene without a camera: automatic framing's depth range is
// fitted again from the lookAt's eye (it was fitted from framing's own, far outside, and
// clipped everything away), and the spheres around the eye are drawn.
TEST_F(ClusterCulling, ALookAtInsideTheBoundsSeesThem) {
    Scene scene = grid();
    for (Node& n : scene.nodes) n.camera = -1;
    scene.cameras.clear();
    RenderOptions o = looking({0.3, 0.2, -2.2}, {-2.0, -1.0, -6.0});
    o.camera.source = CameraSpec::Source::Framing;
    o.background = glm::vec4(0.0f);  // alpha: coverage
    const Image image = render(scene, o);
    EXPECT_GT(test::countCovered(image, 0.01f), std::size_t(kW * kH / 4));
}

// Boxes in view whose faces are clusters of their own: the faces turned away are dropped (the
// grid's spheres, listed ring by ring, have clusters that face every way, and keep most).
TEST_F(ClusterCulling, BackFacingClustersAreDroppedWithoutChange) {
    const double spheres = expectIdentical(grid(), looking({0.5, 0.8, 6.0}, {0, 0, -2}));
    test::LitScene s;
    const Material plastic =
        test::phongMaterial({0.2, 0.1, 0.05}, {0.8, 0.5, 0.3, 1.0}, {0.9, 0.9, 0.9}, 30.0);
    for (int k = 0; k < 4; ++k) {
        glm::dmat4 m = glm::rotate(test::translation({-1.5 + k, 0.3 * k - 0.5, -1.0}), 0.6 * k, glm::dvec3(0.3, 1, 0.2));
        if (k == 3) m = glm::scale(m, glm::dvec3(1, -1, 1));  // mirrored: its winding turns
        s.objects.push_back({tiledBox(0.3, 16), plastic, m});
    }
    s.lights.push_back({test::makeLight(LightType::Directional), test::translation({0, 0, 0})});
    const double boxes = expectIdentical(s.build(), looking({0.4, 0.6, 4.0}, {0, 0, -1}));
    std::printf("whole grid of spheres: %.1f %%, boxes: %.1f %% of the clustered triangles drawn\n",
                100.0 * spheres, 100.0 * boxes);
    EXPECT_LT(boxes, 0.6) << "about half of each box faces away";
}

// A camera moving through the grid, with 4x MSAA, Gouraud and two views: every frame the same.
TEST_F(ClusterCulling, EveryCameraEveryModeTheSamePicture) {
    const Scene scene = grid();
    for (int step = 0; step < 4; ++step) {
        SCOPED_TRACE(step);
        const double a = 0.9 * step;
        RenderOptions o = looking({3.5 * std::cos(a), 0.5 * step - 1.0, -3.0 + 3.5 * std::sin(a)}, {0, 0, -3});
        if (step == 1) o.msaa = 4;
        if (step == 2) o.shading = ShadingMode::Gouraud;
        if (step == 3) {
            View left, right;
            left.width = right.width = kW / 2;
            left.height = right.height = kH;
            right.x = kW / 2;
            left.camera = o.camera;
            right.camera.lookAt = LookAt{{0, 0, 1}, {0, 0, -3}, {0, 1, 0}};
            o.views = {left, right};
        }
        expectIdentical(scene, o);
    }
}

// An orthographic view (no cone test: the eye is at infinity), and GL's default camera.
TEST_F(ClusterCulling, OrthographicViewsTheSamePicture) {
    const Scene scene = grid();
    RenderOptions o = looking({0.5, 0.5, 4.0}, {0, 0, -2});
    o.camera.projection = Projection::makeOrtho(-2.0, 2.0, -1.5, 1.5, 0.1, 20.0);
    const double drawn = expectIdentical(scene, o);
    EXPECT_LT(drawn, 1.0) << "the spheres beside the box are dropped";
    RenderOptions gl = test::optionsFor(kW, kH, ShadingMode::Phong);
    gl.camera.source = CameraSpec::Source::GlDefault;
    expectIdentical(scene, gl);
}

// Every built-in scene, as `lantern render` frames it.
TEST_F(ClusterCulling, BuiltinScenesTheSamePicture) {
    for (const std::string& name : builtinSceneNames()) {
        SCOPED_TRACE(name);
        auto scene = builtinScene(name);
        ASSERT_TRUE(scene) << scene.error().describe();
        expectIdentical(*scene, test::optionsFor(kW, kH, ShadingMode::Phong));
    }
}

// Far away, a level-of-detail bound of one pixel draws far fewer triangles at nearly the same
// picture; a bound of 0 is the exact one.
TEST_F(ClusterCulling, LevelsOfDetailDrawFewerTrianglesCloseToTheExactPicture) {
    const Scene scene = grid();
    RenderOptions o = looking({0.5, 0.8, 16.0}, {0, 0, -2});
    const double exact = expectIdentical(scene, o);
    const Image reference = render(scene, o);
    o.lodError = 1.0;
    const Image coarse = render(scene, o);
    const FrameStats stats = renderer().lastFrameStats();
    const double drawn = double(stats.clusterTrianglesDrawn) / double(stats.clusterTriangles);
    double sum = 0.0;
    for (std::size_t i = 0; i < coarse.rgba.size(); ++i) sum += std::abs(coarse.rgba[i] - reference.rgba[i]);
    const double mean = sum / double(coarse.rgba.size());
    std::printf("lod 1 px: %.1f %% of the triangles (exact: %.1f %%), mean difference %.2e\n",
                100.0 * drawn, 100.0 * exact, mean);
    EXPECT_LT(drawn, 0.5 * exact);
    EXPECT_LT(mean, 0.01);
    EXPECT_EQ(test::countNonFinite(coarse), 0u);
}

} // namespace
