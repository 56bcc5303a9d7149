// The Red Book teapot grid (builtin:teapots, the default scene) rendered small: a teapot in
// each of the 24 cells and nothing elsewhere, each lit with its own material (the CPU
// reference, fed the rendered normals, explains every cell by its own material and by no
// other), and no NaN or Inf in any shading mode.
#include "TestSupport.h"

#include "reference/Lighting.h"
#include "scene/Teapot.h"

#include <lantern/Io.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

class TeapotGrid : public GpuTest {};

TEST_F(TeapotGrid, TwentyFourTeapotsEachInItsOwnMaterial) {
    const int W = 320, H = 180;
    auto loaded = loadScene("builtin:teapots");
    ASSERT_TRUE(loaded) << loaded.error().describe();
    const Scene& scene = *loaded;
    RenderOptions o;
    o.background = glm::vec4(0.0f); // alpha is coverage in these checks
    o.width = W;
    o.height = H;
    o.shading = ShadingMode::Phong;
    o.aovs.normal = true;
    auto img = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    ASSERT_EQ(test::countNonFinite(*img), 0u);

    // The orthographic box (fitted to the image, as the example's reshape does) maps pixels
    // straight to world x, y (identity view).
    const Projection box = fittedProjection(scene.cameras.at(0).projection, double(W) / H);
    const auto materials = scene::redbookMaterials();
    ASSERT_EQ(materials.size(), 24u);

    const Pose pose = evaluatePose(scene, -1, 0.0);
    const auto lights = frame::placeLights(scene, pose, glm::dmat4(1.0), false);
    ref::Settings settings;
    settings.globalAmbient = {0.2, 0.2, 0.2};
    settings.localViewer = false;
    settings.specular = SpecularModel::Blinn;

    // Which cell a pixel belongs to: the glutSolidTeapot(1) at (x, y) spans x - 1.5 .. x +
    // 1.77 and y - 0.68 .. y + 0.83; cells are 4 x 3 units around the example's positions.
    auto cellOf = [&](int px, int py) {
        const double x = box.left + (px + 0.5) / W * (box.right - box.left);
        const double y = box.top - (py + 0.5) / H * (box.top - box.bottom);
        const int column = int(std::floor(x / 4.0)), row = int(std::floor((18.5 - y) / 3.0));
        return column >= 0 && column < 4 && row >= 0 && row < 6 ? column * 6 + row : -1;
    };
    auto covered = [&](int px, int py) {
        return px >= 0 && py >= 0 && px < W && py < H && img->pixel(px, py)[3] > 0.5f;
    };

    std::vector<int> coverage(24, 0);
    // Per cell, the squared error of its interior pixels against each of the 24 materials.
    std::vector<std::vector<double>> sumSq(24, std::vector<double>(24, 0.0));
    std::vector<double> worstOwn(24, 0.0);
    std::vector<int> compared(24, 0);
    int strays = 0;
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
            if (!covered(px, py)) continue;
            const int cell = cellOf(px, py);
            if (cell < 0) {
                ++strays;
                continue;
            }
            ++coverage[std::size_t(cell)];
            // Interior pixels only: the colour of an edge pixel depends on its coverage.
            bool interior = true;
            for (int d = -1; d <= 1; d += 2)
                interior = interior && covered(px + d, py) && covered(px, py + d) &&
                           img->pixel(px, py)[3] == 1.0f;
            if (!interior) continue;
            const float* nf = &img->normal[3 * (std::size_t(py) * W + std::size_t(px))];
            const glm::dvec3 n(nf[0], nf[1], nf[2]);
            ASSERT_NEAR(glm::length(n), 1.0, 1e-5) << "normal AOV at " << px << ", " << py;
            const float* got = img->pixel(px, py);
            ++compared[std::size_t(cell)];
            for (std::size_t m = 0; m < 24; ++m) {
                MaterialSide side = scene.materials[m].front;
                const glm::dvec3 want = ref::shade(glm::dvec3(0.0), n, side, lights, settings);
                for (int k = 0; k < 3; ++k) {
                    const double e = double(got[k]) - want[std::size_t(k)];
                    sumSq[std::size_t(cell)][m] += e * e;
                    if (m == std::size_t(cell))
                        worstOwn[std::size_t(cell)] =
                            std::max(worstOwn[std::size_t(cell)], std::abs(e));
                }
            }
        }

    EXPECT_EQ(strays, 0) << "covered pixels outside the 24 cells";
    std::vector<int> sorted = coverage;
    std::sort(sorted.begin(), sorted.end());
    const double median = 0.5 * (sorted[11] + sorted[12]);
    // A teapot is about 3.27 x 1.5 units; at 9.375 px per unit its silhouette covers ~250 px.
    EXPECT_GT(median, 200.0);
    for (std::size_t i = 0; i < 24; ++i) {
        const std::string name(materials[i].name);
        SCOPED_TRACE(name);
        // Same geometry in every cell; only the sub-pixel offset of the grid differs (measured
        // spread 223..235 pixels).
        EXPECT_NEAR(coverage[i], median, 0.08 * median) << "coverage";
        ASSERT_GT(compared[i], 60) << "interior pixels";
        // Same normal in, same equation: float vs double, worst at the sharpest highlight
        // (shininess 76.8 turns a 1e-7 error in N.H into ~1e-5; measured at most 4.4e-6).
        EXPECT_LE(worstOwn[i], 2e-5) << "against its own material";
        const double own = std::sqrt(sumSq[i][i] / compared[i]);
        for (std::size_t m = 0; m < 24; ++m) {
            if (m == i) continue;
            const double other = std::sqrt(sumSq[i][m] / compared[i]);
            EXPECT_GT(other, 10.0 * own + 1e-3)
                << "cell " << i << " is explained almost as well by " << materials[m].name;
        }
    }
}

TEST_F(TeapotGrid, EveryShadingModeIsFiniteWithTheSameCoverage) {
    auto scene = loadScene("builtin:default");
    ASSERT_TRUE(scene) << scene.error().describe();
    RenderOptions o;
    o.background = glm::vec4(0.0f); // alpha is coverage in these checks
    o.width = 320;
    o.height = 180;
    std::vector<float> phongAlpha;
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
        SCOPED_TRACE(toString(mode));
        o.shading = mode;
        auto img = renderer().render(*scene, o, 0.0);
        ASSERT_TRUE(img) << img.error().describe();
        EXPECT_EQ(test::countNonFinite(*img), 0u);
        std::vector<float> alpha;
        for (std::size_t i = 3; i < img->rgba.size(); i += 4) alpha.push_back(img->rgba[i]);
        // The same triangles rasterise to the same pixels whatever the shading.
        if (phongAlpha.empty())
            phongAlpha = alpha;
        else
            EXPECT_EQ(alpha, phongAlpha);
        EXPECT_GT(test::countCovered(*img), 24u * 200u);
    }
}

} // namespace
