// The CPU reference of the lighting equation against hand-computed values and the numeric
// traps of numerics.md section 3 (x^0 = 1, zero normals, zero halfway vector, attenuation at
// d = 0, extreme shininess).
#include "reference/Lighting.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using namespace lantern::ref;

EyeLight directional(glm::dvec3 toLight) {
    EyeLight l;
    l.type = LightType::Directional;
    l.toLight = glm::normalize(toLight);
    return l;
}

TEST(ReferenceLighting, HandComputedDiffuseAndBlinnSpecular) {
    MaterialSide m;
    m.ambient = {0.2, 0.2, 0.2};
    m.diffuse = {0.8, 0.4, 0.2, 1.0};
    m.specular = {1.0, 1.0, 1.0};
    m.emission = {0.01, 0.02, 0.03};
    m.shininess = 10.0;
    Settings st;
    st.globalAmbient = {0.1, 0.1, 0.1};
    EyeLight l = directional({0, 1, 1});  // 45 degrees above the normal
    l.ambient = {0.05, 0.05, 0.05};
    const glm::dvec3 n(0, 0, 1);
    const glm::dvec3 c = shade({0, 0, -3}, n, m, {l}, st);
    const double ndotl = std::sqrt(0.5);
    // Blinn: h = normalize(l + (0,0,1)), n.h = cos(22.5 deg).
    const double spec = std::pow(std::cos(3.14159265358979323846 / 8), 10.0);
    for (int i = 0; i < 3; ++i) {
        const double expected = m.emission[i] + m.ambient[i] * 0.1 + m.ambient[i] * 0.05 +
                                ndotl * m.diffuse[i] + spec;
        EXPECT_NEAR(c[i], expected, 1e-14) << i;
    }
}

TEST(ReferenceLighting, ZeroShininessIsOneWhereverTheSurfaceIsLit) {
    // x^0 = 1 for every x >= 0, including n.h <= 0 (GLSL pow(0,0) is undefined).
    EXPECT_EQ(lobe({0, 0, 1}, {1, 0, 0}, 0.0), 1.0);
    EXPECT_EQ(lobe({0, 0, 1}, {0, 0, -1}, 0.0), 1.0);
    EXPECT_EQ(lobe({0, 0, 1}, {0, 1, 0}, 2.0), 0.0);
    // The spot exponent goes through the same lobe: exponent 0 inside the cone is 1.
    EXPECT_EQ(glSpotFactor({0, 0, -1}, {0, 0, -1}, 0.0, 0.0), 1.0);
    EXPECT_EQ(glSpotFactor({0, 1, 0}, {0, 0, -1}, 1.0, 0.0), 1.0);  // 90 degrees, cutoff 90
}

TEST(ReferenceLighting, LobeIsExactForHugeShininess) {
    for (double s : {1e3, 1e4, 1e5, 1e6, 1e7}) {
        const double angle = 0.5 / std::sqrt(s);  // well inside the lobe
        const glm::dvec3 a(0, 0, 1), b(std::sin(angle), 0, std::cos(angle));
        const double exact = std::exp(s * std::log(std::cos(angle)));
        EXPECT_NEAR(lobe(a, b, s) / exact, 1.0, 1e-9) << s;
    }
}

TEST(ReferenceLighting, ZeroNormalGivesAmbientAndEmissionOnly) {
    MaterialSide m;
    m.specular = {1, 1, 1};
    m.shininess = 0.0;
    m.emission = {0.3, 0.0, 0.0};
    const glm::dvec3 c = shade({0, 0, -1}, {0, 0, 0}, m, {directional({0, 0, 1})}, Settings{});
    EXPECT_NEAR(c.x, 0.3 + 0.2 * 0.2, 1e-15);
    EXPECT_NEAR(c.y, 0.2 * 0.2, 1e-15);
}

TEST(ReferenceLighting, NoHalfwayVectorMeansNoSpecular) {
    // Distant viewer v = (0,0,1), light from behind: l = -v. On a surface facing away,
    // n.l > 0 but h does not exist: the term is 0, not NaN.
    MaterialSide m;
    m.specular = {1, 1, 1};
    m.shininess = 5.0;
    m.diffuse = {0, 0, 0, 1};
    m.ambient = {0, 0, 0};
    const glm::dvec3 c = shade({0, 0, -1}, {0, 0, -1}, m, {directional({0, 0, -1})}, Settings{});
    EXPECT_EQ(c, glm::dvec3(0.0));
}

TEST(ReferenceLighting, LightOnTheSurfaceIsFinite) {
    EyeLight l;
    l.type = LightType::Point;
    l.position = {0, 0, -2};
    l.attenuation = {0, 0, 1};
    MaterialSide m;
    const glm::dvec3 c = shade({0, 0, -2}, {0, 0, 1}, m, {l}, Settings{});
    EXPECT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    EXPECT_NEAR(c.x, 0.2 * 0.2 + 1e30 * 0.8, 1e16);  // att = 1 / max(0, 1e-30)
    // Huge coefficients make the light vanish, never NaN.
    l.attenuation = {0, 0, 1e30};
    l.position = {0, 0, 1e5};
    const glm::dvec3 far = shade({0, 0, 0}, {0, 0, 1}, m, {l}, Settings{});
    EXPECT_NEAR(far.x, 0.04, 1e-12);
}

TEST(ReferenceLighting, GlSpotCutoffAndExponent) {
    EyeLight l;
    l.type = LightType::Spot;
    l.position = {0, 0, 0};
    l.spotAxis = {0, 0, -1};
    l.oneMinusCosCutoff = 1.0 - std::cos(30.0 * 3.14159265358979323846 / 180.0);
    l.exponent = 2.0;
    MaterialSide m;
    m.ambient = {0, 0, 0};
    Settings st;
    st.globalAmbient = {0, 0, 0};
    // On the axis: full; at 20 degrees: cos^2; at 40 degrees: outside the cone.
    auto at = [&](double degrees) {
        const double a = degrees * 3.14159265358979323846 / 180.0;
        const glm::dvec3 p(std::sin(a) * 5, 0, -std::cos(a) * 5);
        return shade(p, glm::normalize(-p), m, {l}, st).x;
    };
    EXPECT_NEAR(at(0), 0.8, 1e-14);
    EXPECT_NEAR(at(20), 0.8 * std::pow(std::cos(20 * 3.14159265358979323846 / 180), 2), 1e-14);
    EXPECT_EQ(at(40), 0.0);
}

TEST(ReferenceLighting, GlSpotConeEdgesAtTheExtremes) {
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    auto oneMinusCos = [&](double cutoffDeg) {
        return 2.0 * std::pow(std::sin(cutoffDeg * kDeg / 2.0), 2.0);
    };
    const glm::dvec3 axis(0, 0, -1);
    auto towards = [&](double degrees) {
        return glm::dvec3(std::sin(degrees * kDeg), 0, -std::cos(degrees * kDeg));
    };
    // Cutoff 90, exponent 0 (numerics.md LN-2): -l.s = +-1e-6 either side of the cone.
    EXPECT_EQ(glSpotFactor(glm::normalize(glm::dvec3(1, 0, -1e-6)), axis, oneMinusCos(90), 0.0), 1.0);
    EXPECT_EQ(glSpotFactor(glm::normalize(glm::dvec3(1, 0, 1e-6)), axis, oneMinusCos(90), 0.0), 0.0);
    // Cutoff 0: only the axis itself.
    EXPECT_EQ(glSpotFactor(axis, axis, oneMinusCos(0), 3.0), 1.0);
    EXPECT_EQ(glSpotFactor(towards(1e-6), axis, oneMinusCos(0), 0.0), 0.0);
    // A 0.05 degree cone keeps its edge to 0.1% of its angle.
    EXPECT_GT(glSpotFactor(towards(0.05 * 0.999), axis, oneMinusCos(0.05), 0.0), 0.0);
    EXPECT_EQ(glSpotFactor(towards(0.05 * 1.001), axis, oneMinusCos(0.05), 0.0), 0.0);
    // A huge exponent is exact: cos(a)^1e6 at a = 1e-3.
    EXPECT_NEAR(glSpotFactor(towards(1e-3 / kDeg), axis, oneMinusCos(1.0), 1e6) /
                    std::exp(1e6 * std::log(std::cos(1e-3))),
                1.0, 1e-9);
}

TEST(ReferenceLighting, VertexColorReplacesOrScales) {
    MaterialSide m;
    m.ambient = {0.2, 0.3, 0.4};
    m.diffuse = {0.5, 0.6, 0.7, 0.8};
    const glm::dvec4 c(0.1, 0.2, 0.3, 0.5);
    const MaterialColours replaced = materialColours(m, &c, false);
    EXPECT_EQ(replaced.ambient, glm::dvec3(0.1, 0.2, 0.3));
    EXPECT_EQ(replaced.diffuse, glm::dvec3(0.1, 0.2, 0.3));
    EXPECT_DOUBLE_EQ(replaced.alpha, 0.4);
    const MaterialColours scaled = materialColours(m, &c, true);
    EXPECT_NEAR(scaled.diffuse.y, 0.12, 1e-15);
    EXPECT_NEAR(scaled.ambient.z, 0.12, 1e-15);
    const MaterialColours none = materialColours(m, nullptr, true);
    EXPECT_EQ(none.diffuse, glm::dvec3(0.5, 0.6, 0.7));
    EXPECT_DOUBLE_EQ(none.alpha, 0.8);
}

TEST(ReferenceLighting, ZeroShininessWithoutAHalfwayVectorIsStillOne) {
    // l = -v: no halfway vector, but x^0 = 1 for every x.
    EXPECT_EQ(specularTerm({0, 0, -1}, {0, 0, -1}, {0, 0, 1}, 0.0, SpecularModel::Blinn), 1.0);
    EXPECT_EQ(specularTerm({0, 0, -1}, {0, 0, -1}, {0, 0, 1}, 2.0, SpecularModel::Blinn), 0.0);
}

// The shadow rays: one to a point-like light; with PCSS's light sizes, kAreaLightRays spread
// evenly over the light's disc as the point sees it, so the share of rays within a fraction
// rho of the disc's radius is rho^2 (the area), to within a ray or two.
TEST(ReferenceShadowRays, AreaLightsAreDiscsCoveredEvenly) {
    ShadowOptions hard;
    EyeLight point;
    point.type = LightType::Point;
    point.position = {1.0, 2.0, -3.0};
    const glm::dvec3 p(0.5, -1.0, 0.0);
    ASSERT_EQ(shadowRays(point, p, hard).size(), 1u);
    EXPECT_EQ(shadowRays(point, p, hard)[0].dir, point.position - p);
    ShadowOptions soft;
    soft.filter = ShadowFilter::Pcss;
    soft.lightRadius = 0.25;
    soft.sunRadius = 2.0;
    const std::vector<ShadowRay> rays = shadowRays(point, p, soft);
    ASSERT_EQ(rays.size(), std::size_t(kAreaLightRays));
    const glm::dvec3 axis = glm::normalize(point.position - p);
    for (double rho : {0.25, 0.5, 0.75}) {
        int inside = 0;
        for (const ShadowRay& r : rays) {
            const glm::dvec3 target = p + r.dir;  // on the disc, across the axis
            EXPECT_NEAR(glm::dot(target - point.position, axis), 0.0, 1e-12);
            EXPECT_LE(glm::length(target - point.position), soft.lightRadius + 1e-12);
            EXPECT_EQ(r.tMax, 1.0);
            inside += glm::length(target - point.position) < rho * soft.lightRadius;
        }
        EXPECT_NEAR(double(inside) / kAreaLightRays, rho * rho, 2.0 / kAreaLightRays) << rho;
    }
    // A directional light: a cone of the sun's angular radius about the light's direction.
    const EyeLight sun = directional({0.2, 1.0, 0.3});
    const double tanRadius = std::tan(soft.sunRadius * 3.14159265358979323846 / 180.0);
    int inside = 0;
    for (const ShadowRay& r : shadowRays(sun, p, soft)) {
        EXPECT_TRUE(std::isinf(r.tMax));
        const double along = glm::dot(r.dir, sun.toLight);
        const double across = glm::length(r.dir - along * sun.toLight) / along;
        EXPECT_LE(across, tanRadius * (1.0 + 1e-12));
        inside += across < 0.5 * tanRadius;
    }
    EXPECT_NEAR(inside / double(kAreaLightRays), 0.25, 2.0 / kAreaLightRays);
    // A light of no size is a point again.
    soft.lightRadius = 0.0;
    EXPECT_EQ(shadowRays(point, p, soft).size(), 1u);
}

} // namespace
