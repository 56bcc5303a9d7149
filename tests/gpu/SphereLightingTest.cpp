// A finely tessellated sphere lit head-on, rendered per fragment, against the lighting
// equation evaluated in double precision on the exact sphere at the same pixel centres.
#include "TestSupport.h"

#include "reference/Lighting.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using lantern::test::GpuTest;

struct Case {
    const char* name;
    SpecularModel specular;
    double shininess;
    bool pointLight;
    double tolerance;  // per channel, linear
    const char* why;
};

// Names the row in test listings instead of dumping its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class SphereLighting : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(SphereLighting, MatchesTheExactSphereAtPixelCentres) {
    const Case& c = GetParam();
    const int W = 128, H = 128;
    const double fovy = 40.0 * 3.14159265358979323846 / 180.0;
    test::SimpleScene ss;
    ss.primitive = makeSphere(1.0, 256, 128);
    ss.material.front.ambient = {0.2, 0.2, 0.2};
    ss.material.front.diffuse = {0.8, 0.6, 0.4, 1.0};
    ss.material.front.specular = {1.0, 1.0, 1.0};
    ss.material.front.shininess = c.shininess;
    ss.projection = Projection::makePerspective(fovy, 0.0, 0.1, kInfinity);
    ss.lookAt = {{0, 0, 4}, {0, 0, 0}, {0, 1, 0}};
    Light light;
    glm::dmat4 lightModel(1.0);
    if (c.pointLight) {
        light.type = LightType::Point;
        lightModel[3] = glm::dvec4(2, 2, 4, 1);  // eye space (2, 2, 0)
    } else {
        light.type = LightType::Directional;  // head-on: shines down -Z from the eye
    }
    ss.lights = {{light, lightModel}};
    ss.lighting.specular = c.specular;
    const Scene scene = ss.build();

    RenderOptions o;
    o.background = glm::vec4(0.0f); // alpha is coverage in these checks
    o.width = W;
    o.height = H;
    o.shading = ShadingMode::Phong;
    auto img = renderer().render(scene, o, 0.0);
    ASSERT_TRUE(img) << img.error().describe();
    ASSERT_EQ(test::countNonFinite(*img), 0u);

    // The reference: exact ray-sphere intersection in eye space (sphere centre (0,0,-4)).
    const Pose pose = evaluatePose(scene, -1, 0.0);
    const glm::dmat4 viewFromWorld = lookAt(ss.lookAt.eye, ss.lookAt.target, ss.lookAt.up);
    const auto lights = frame::placeLights(scene, pose, viewFromWorld, false);
    ref::Settings st;
    st.specular = c.specular;
    const double t = std::tan(fovy / 2);
    int compared = 0;
    double worst = 0.0;
    int worstX = -1, worstY = -1;
    double worstNz = 0.0;
    Image expected(W, H);
    // Coverage of the exact sphere, so that pixels next to the silhouette can be left out.
    auto onSphere = [&](int px, int py) {
        const double nx = (px + 0.5) / W * 2 - 1, ny = 1 - (py + 0.5) / H * 2;
        const glm::dvec3 dir = glm::normalize(glm::dvec3(nx * t, ny * t, -1));
        const double b = dir.z * -4.0;
        return b * b - (16.0 - 1.0) >= 0.0;
    };
    auto interior = [&](int px, int py) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (!onSphere(px + dx, py + dy)) return false;
        return true;
    };
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
            const double nx = (px + 0.5) / W * 2 - 1, ny = 1 - (py + 0.5) / H * 2;
            const glm::dvec3 dir = glm::normalize(glm::dvec3(nx * t, ny * t, -1));
            const glm::dvec3 centre(0, 0, -4);
            const double b = glm::dot(dir, centre), disc = b * b - (glm::dot(centre, centre) - 1);
            const float* got = img->pixel(px, py);
            if (disc < 0) {
                EXPECT_EQ(got[3], 0.0f) << "background at " << px << "," << py;
                continue;
            }
            const glm::dvec3 p = dir * (b - std::sqrt(disc));
            const glm::dvec3 n = p - centre;
            const glm::dvec3 colour = ref::shade(p, n, scene.materials[0].front, lights, st);
            for (int k = 0; k < 3; ++k) expected.pixel(px, py)[k] = float(colour[k]);
            expected.pixel(px, py)[3] = 1.0f;
            if (!interior(px, py)) continue;  // pixel centres away from the silhouette
            ++compared;
            for (int k = 0; k < 3; ++k)
                if (std::abs(got[k] - colour[k]) > worst) {
                    worst = std::abs(got[k] - colour[k]);
                    worstX = px, worstY = py, worstNz = n.z;
                }
        }
    EXPECT_GT(compared, 2500);
    EXPECT_LE(worst, c.tolerance) << c.name << ": " << c.why << "; worst at pixel (" << worstX << ", "
                                  << worstY << "), normal z " << worstNz << "\n"
                                  << test::saveComparison(*img, expected, std::string("sphere_") + c.name);
}

INSTANTIATE_TEST_SUITE_P(
    HeadOn, SphereLighting,
    ::testing::Values(
        Case{"directional_blinn", SpecularModel::Blinn, 32.0, false, 1.0 / 255, "1/255: one 8-bit step"},
        Case{"point_blinn", SpecularModel::Blinn, 32.0, true, 1.0 / 255, "1/255: one 8-bit step"},
        Case{"point_phong", SpecularModel::Phong, 32.0, true, 1.0 / 255, "1/255: one 8-bit step"},
        Case{"point_blinn_s500", SpecularModel::Blinn, 500.0, true, 1.0 / 255, "1/255: one 8-bit step"}),
    [](const auto& p) { return std::string(p.param.name); });

} // namespace
