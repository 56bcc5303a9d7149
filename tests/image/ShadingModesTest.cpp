// Flat, gouraud and phong renders of small scenes against the double-precision reference
// under the same interpolation rule, pixel by pixel: each pixel's triangle comes from the id
// AOV; flat is the equation at the triangle's centroid with its face normal, gouraud the
// vertex colours interpolated with the pixel centre's perspective-correct barycentrics, phong
// the equation at the pixel centre with the interpolated normal renormalised.
#include "LightingCompare.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <iostream>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

constexpr double kPi = 3.14159265358979323846;

Material plastic(glm::dvec3 diffuse, double shininess = 20.0) {
    Material m =
        test::phongMaterial(diffuse * 0.25, glm::dvec4(diffuse, 1.0), {0.8, 0.8, 0.8}, shininess);
    m.front.emission = {0.02, 0.01, 0.0};
    return m;
}

// A sphere whose vertex colours follow the normal.
Primitive colouredSphere(int segments) {
    Primitive p = makeSphere(1.0, segments, segments / 2);
    for (const glm::vec3& n : p.normals)
        p.colors.emplace_back(0.5f + 0.4f * n.x, 0.5f + 0.4f * n.y, 0.5f + 0.4f * n.z, 1.0f);
    return p;
}

// A sphere with the triangles of its front cap (z > 0.6) removed: its inside shows.
Primitive openSphere(int segments) {
    Primitive p = makeSphere(1.0, segments, segments / 2);
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        bool cap = true;
        for (int c = 0; c < 3; ++c)
            cap &= p.positions[p.indices[t + c]].z > 0.6f;
        if (!cap)
            kept.insert(kept.end(), p.indices.begin() + long(t), p.indices.begin() + long(t) + 3);
    }
    p.indices = kept;
    return p;
}

Scene sphereDirectional() {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 24, 12), plastic({0.8, 0.6, 0.4}), glm::dmat4(1.0)});
    s.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -1})});
    return s.build();
}

Scene spherePointAttenuated() {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 24, 12), plastic({0.3, 0.7, 0.5}, 40.0), glm::dmat4(1.0)});
    Light l = test::makeLight(LightType::Point);
    l.attenuation = {1.0, 0.2, 0.05};
    l.ambient = {0.1, 0.1, 0.1};
    s.lights.push_back({l, test::translation({1.5, 2.0, 3.0})});
    s.lighting->localViewer = true;
    return s.build();
}

Scene planeGlSpot() {
    LitScene s;
    s.objects.push_back({makePlane(3.0, 6), plastic({0.7, 0.7, 0.7}, 10.0),
                         glm::rotate(glm::dmat4(1.0), -0.3, glm::dvec3(1, 0, 0))});
    Light l = test::makeLight(LightType::Spot);
    l.spotCutoffDeg = 25.0;
    l.spotExponent = 8.0;
    l.attenuation = {1.0, 0.1, 0.0};
    s.lights.push_back({l, test::aimed({0.2, 0.3, 2.0}, {0.1, -0.1, -1.0})});
    s.lighting->globalAmbient = {0.05, 0.05, 0.05};
    return s.build();
}

Scene planeGltfSpot() {
    LitScene s;
    s.objects.push_back({makePlane(3.0, 6), plastic({0.6, 0.6, 0.9}, 15.0),
                         glm::rotate(glm::dmat4(1.0), 0.4, glm::dvec3(0, 1, 0))});
    Light l = test::makeLight(LightType::Spot);
    l.falloff = LightFalloff::Gltf;
    l.diffuse = l.specular = {4.0, 4.0, 3.0};
    l.innerConeAngle = 0.15;
    l.outerConeAngle = 0.45;
    l.range = 6.0;
    s.lights.push_back({l, test::aimed({-0.3, 0.0, 2.0}, {0.2, 0.0, -1.0})});
    Light p = test::makeLight(LightType::Point);
    p.falloff = LightFalloff::Gltf;
    p.diffuse = p.specular = {0.5, 1.0, 0.5};
    s.lights.push_back({p, test::translation({1.0, 1.0, 1.0})});
    return s.build();
}

// Directional, point and spot lights of every kind together.
Scene eightLights() {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 32, 16), plastic({0.7, 0.7, 0.7}, 30.0), glm::dmat4(1.0)});
    for (int i = 0; i < 8; ++i) {
        const double a = 2.0 * kPi * i / 8.0;
        const glm::dvec3 pos(2.5 * std::cos(a), 2.5 * std::sin(a), 2.0);
        const glm::dvec3 colour(0.2 + 0.1 * (i % 3), 0.2 + 0.1 * ((i + 1) % 3),
                                0.2 + 0.1 * ((i + 2) % 3));
        Light l = test::makeLight(i < 3   ? LightType::Directional
                                  : i < 6 ? LightType::Point
                                          : LightType::Spot);
        l.diffuse = l.specular = colour;
        l.ambient = colour * 0.1;
        if (l.type != LightType::Directional) l.attenuation = {1.0, 0.05 * i, 0.01 * i};
        if (l.type == LightType::Spot) {
            l.spotCutoffDeg = 20.0 + 10.0 * (i - 6);
            l.spotExponent = 4.0;
        }
        s.lights.push_back({l, test::aimed(pos, -pos)});
    }
    return s.build();
}

// A few hundred lights: they live in a buffer the shader loops over.
Scene threeHundredLights() {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 24, 12), plastic({0.8, 0.8, 0.8}, 25.0), glm::dmat4(1.0)});
    for (int i = 0; i < 300; ++i) {
        // A Fibonacci spiral of point lights around the sphere.
        const double z = 1.0 - (i + 0.5) / 150.0, r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double a = i * 2.399963229728653;
        Light l = test::makeLight(LightType::Point);
        l.name = "bulb " + std::to_string(i);
        l.diffuse = {0.006 * (1 + i % 3), 0.006 * (1 + (i + 1) % 3), 0.006 * (1 + (i + 2) % 3)};
        l.specular = l.diffuse;
        l.ambient = l.diffuse * 0.1;
        l.attenuation = {1.0, 0.0, 0.05};
        s.lights.push_back(
            {l, test::translation(3.0 * glm::dvec3(r * std::cos(a), r * std::sin(a), z))});
    }
    return s.build();
}

Scene twoSidedBackMaterial() {
    LitScene s;
    Material m = plastic({0.9, 0.5, 0.2});
    m.doubleSided = true;
    MaterialSide back;
    back.ambient = {0.1, 0.1, 0.3};
    back.diffuse = {0.2, 0.4, 0.9, 1.0};
    back.specular = {0.5, 0.5, 0.5};
    back.shininess = 8.0;
    m.back = back;
    s.objects.push_back(
        {openSphere(24), m, glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(0, 1, 0))});
    s.lights.push_back({test::makeLight(LightType::Point), test::translation({0.3, 0.4, 2.5})});
    s.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {-1, -0.5, -1})});
    s.lighting->twoSided = true;
    return s.build();
}

// glTF's doubleSided with no lighting model stated: a plane seen from behind, lit from the
// camera's side, its back face lit with the reversed normal and its back material.
Scene gltfDoubleSidedBack() {
    LitScene s;
    Material m = plastic({0.9, 0.5, 0.2});
    m.doubleSided = true;
    m.back = m.front;
    m.back->diffuse = {0.2, 0.5, 0.9, 1.0};
    s.objects.push_back({makePlane(2.5, 6), m,
                         glm::rotate(glm::dmat4(1.0), 3.14159265358979323846 - 0.3, glm::dvec3(0, 1, 0))});
    s.lights.push_back({test::makeLight(LightType::Point), test::translation({0.3, 0.4, 2.5})});
    s.lighting.reset();
    return s.build();
}

// A mirroring transform flips which faces are front faces.
Scene mirroredTwoSided() {
    LitScene s;
    Material m = plastic({0.4, 0.8, 0.3});
    m.doubleSided = true;
    m.back = m.front;
    m.back->diffuse = {0.8, 0.2, 0.8, 1.0};
    glm::dmat4 model = glm::scale(glm::rotate(glm::dmat4(1.0), -0.4, glm::dvec3(0, 1, 0)),
                                  glm::dvec3(-1.0, 1.0, 1.0));
    s.objects.push_back({openSphere(24), m, model});
    s.lights.push_back({test::makeLight(LightType::Point), test::translation({-0.5, 0.5, 2.5})});
    s.lighting->twoSided = true;
    return s.build();
}

Scene vertexColors() {
    LitScene s;
    s.objects.push_back({colouredSphere(24), plastic({1, 1, 1}), glm::dmat4(1.0)});
    s.lights.push_back(
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -2})});
    return s.build();
}

Scene unlitVertexColors() {
    LitScene s;
    Material m;
    m.unlit = true;
    m.front.diffuse = {0.9, 0.7, 0.5, 1.0};
    s.objects.push_back({colouredSphere(24), m, glm::dmat4(1.0)});
    return s.build();
}

// The PBR fallback's ambient = diffuse: COLOR_0 and the texture scale both.
Scene pbrMappedVertexColors() {
    LitScene s;
    Material m = plastic({0.6, 0.5, 0.4});
    m.front.ambient = glm::dvec3(m.front.diffuse);
    m.ambientFollowsDiffuse = true;
    s.objects.push_back({colouredSphere(24), m, glm::dmat4(1.0)});
    s.lights.push_back({test::makeLight(LightType::Point), test::translation({-2.0, 1.0, 3.0})});
    return s.build();
}

// Values far beyond half's 65504: the output is float and unclamped.
Scene hdrBright() {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 24, 12), plastic({0.8, 0.6, 0.4}), glm::dmat4(1.0)});
    Light l = test::makeLight(LightType::Directional);
    l.diffuse = {1e5, 5e4, 2e4};
    l.specular = {1e5, 1e5, 1e5};
    s.lights.push_back({l, test::aimed({0, 0, 0}, {0.5, -0.5, -1})});
    return s.build();
}

struct SceneRow {
    const char* name;
    Scene (*build)();
    SpecularModel specular;
    double tolerance;
    const char* why;
};

const SceneRow kScenes[] = {
    {"sphere_directional", sphereDirectional, SpecularModel::Blinn, 1.0 / 255, "one 8-bit step"},
    {"sphere_point_attenuated_phong_specular", spherePointAttenuated, SpecularModel::Phong,
     1.0 / 255, "one 8-bit step"},
    {"plane_gl_spot", planeGlSpot, SpecularModel::Blinn, 1.0 / 255, "one 8-bit step"},
    {"plane_gltf_spot", planeGltfSpot, SpecularModel::Blinn, 1.0 / 255, "one 8-bit step"},
    {"eight_lights", eightLights, SpecularModel::Blinn, 1.0 / 255, "one 8-bit step"},
    {"three_hundred_lights", threeHundredLights, SpecularModel::Phong, 1.0 / 255, "one 8-bit step"},
    {"two_sided_back_material", twoSidedBackMaterial, SpecularModel::Blinn, 1.0 / 255,
     "one 8-bit step"},
    {"gltf_double_sided_back", gltfDoubleSidedBack, SpecularModel::Blinn, 1.0 / 255,
     "one 8-bit step"},
    {"mirrored_two_sided", mirroredTwoSided, SpecularModel::Blinn, 1.0 / 255, "one 8-bit step"},
    {"vertex_colors", vertexColors, SpecularModel::Blinn, 1.0 / 255, "one 8-bit step"},
    {"unlit_vertex_colors", unlitVertexColors, SpecularModel::Blinn, 1.0 / 255, "one 8-bit step"},
    {"pbr_mapped_vertex_colors", pbrMappedVertexColors, SpecularModel::Blinn, 1.0 / 255,
     "one 8-bit step"},
    {"hdr_above_half_range", hdrBright, SpecularModel::Blinn, 1.0 / 255,
     "one 8-bit step relative to the value (HDR)"},
};

void PrintTo(const SceneRow& r, std::ostream* os) {
    *os << r.name;
}

using Param = std::tuple<SceneRow, ShadingMode>;
class ShadingModes : public GpuTest, public ::testing::WithParamInterface<Param> {};

TEST_P(ShadingModes, EveryPixelMatchesTheReferenceUnderTheSameInterpolationRule) {
    const auto& [row, mode] = GetParam();
    const Scene scene = row.build();
    RenderOptions o = test::optionsFor(64, 64, mode);
    o.specular = row.specular;
    const test::ReferenceComparison c = test::compareWithReference(device(), scene, o);
    EXPECT_EQ(c.frame.readback.nonFinite, 0u) << "NaN/Inf counted at readback, before any scrub";
    EXPECT_GT(c.compared, 600u) << "the object should cover a good part of the image";
    const std::string name = std::string("shading_") + row.name + "_" + toString(mode);
    EXPECT_LE(c.worst, row.tolerance) << row.why << "; " << c.describe(name);
    if (std::getenv("LANTERN_TEST_VERBOSE")) std::cerr << name << ": " << c.describe(name) << "\n";
}

// glTF: "when a material is double-sided, back-face normals are reversed before lighting".
// Without a lighting model the back of a double-sided plane lit from its own side is lit
// (n.l > 0 everywhere) with the back material; a stated one-sided model (GL's) keeps the front
// normal, so the same back is unlit (n.l < 0), in every mode.
class DoubleSided : public GpuTest, public ::testing::WithParamInterface<ShadingMode> {};

TEST_P(DoubleSided, BackFacesAreLitWithTheReversedNormal) {
    const ShadingMode mode = GetParam();
    for (const bool statedOneSided : {false, true}) {
        RenderOptions o = test::optionsFor(64, 64, mode);
        if (statedOneSided) o.twoSided = false;
        test::PixelCheck check;
        check.perLight = true;
        const test::ReferenceComparison c =
            test::compareWithReference(device(), gltfDoubleSidedBack(), o, check);
        const std::string name = std::string("double_sided_") + (statedOneSided ? "gl_" : "") + toString(mode);
        EXPECT_LE(c.worst, 1.0 / 255) << c.describe(name);
        std::size_t lit = 0, unlit = 0, hits = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const ProbeReport& r = c.at(x, y);
                if (!r.hit) continue;
                ++hits;
                EXPECT_TRUE(r.backFacing);
                EXPECT_EQ(r.backMaterial, !statedOneSided);
                for (const ProbeEvaluation& e : r.evaluations) (e.lights[0].nDotL > 0.0 ? lit : unlit)++;
            }
        EXPECT_GT(hits, 600u) << name;
        EXPECT_EQ(statedOneSided ? lit : unlit, 0u) << name;
    }
}

INSTANTIATE_TEST_SUITE_P(Modes, DoubleSided,
                         ::testing::Values(ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong),
                         [](const auto& p) { return std::string(toString(p.param)); });

INSTANTIATE_TEST_SUITE_P(Scenes, ShadingModes,
                         ::testing::Combine(::testing::ValuesIn(kScenes),
                                            ::testing::Values(ShadingMode::Flat,
                                                              ShadingMode::Gouraud,
                                                              ShadingMode::Phong)),
                         [](const auto& p) {
                             return std::string(std::get<0>(p.param).name) + "_" +
                                    toString(std::get<1>(p.param));
                         });

} // namespace
