// The reference ray caster (lantern/Reference.h) against pixels computed by hand from the
// scene contract's equation, its refusals, and the error metrics on images built by hand.
#include "TestSupport.h"

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <lantern/Reference.h>
#include <limits>

namespace {

using namespace lantern;

constexpr double kPi = 3.14159265358979323846;

// A phong material: ambient 0.2, diffuse 0.8 (grey), the given specular and shininess.
Material grey(double specular, double shininess) {
    Material m;
    m.front.ambient = {0.2, 0.2, 0.2};
    m.front.diffuse = {0.8, 0.8, 0.8, 1.0};
    m.front.specular = glm::dvec3(specular);
    m.front.shininess = shininess;
    return m;
}

// An orthographic camera at (0, 0, 5) looking down -Z over [-half, half]^2.
test::SimpleScene orthoScene(const Primitive& primitive, const Material& material, double half) {
    test::SimpleScene s;
    s.primitive = primitive;
    s.material = material;
    s.projection = Projection::makeOrtho(-half, half, -half, half, 1.0, 10.0);
    s.lookAt = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
    return s;
}

RenderOptions size(int w, int h) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    o.background = {0.0f, 0.0f, 0.0f, 0.0f}; // alpha is coverage (the default is opaque black)
    return o;
}

ReferenceImage cast(const Scene& scene, const RenderOptions& o, const AnalyticShape& shape,
                    int boxSamples = 4) {
    ReferenceOptions r;
    r.shapes = {shape};
    r.boxSamples = boxSamples;
    auto ref = raycastReference(scene, o, 0.0, r);
    EXPECT_TRUE(ref) << ref.error().describe();
    return ref ? std::move(*ref) : ReferenceImage{};
}

// One hand-computed pixel: the centre image's RGB (grey: all three equal) and alpha, and
// whether the pixel is interior.
struct PixelCase {
    int x, y;
    double grey, alpha;
    int interior;
    const char* derivation;
};

void expectPixels(const ReferenceImage& ref, const std::vector<PixelCase>& cases) {
    for (const PixelCase& c : cases) {
        const float* p = ref.centre.pixel(c.x, c.y);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(p[k], c.grey, 1e-6)
                << "pixel " << c.x << "," << c.y << ": " << c.derivation;
        EXPECT_EQ(p[3], float(c.alpha)) << "pixel " << c.x << "," << c.y;
        EXPECT_EQ(int(ref.interior[std::size_t(c.y) * ref.centre.width + c.x]), c.interior)
            << "pixel " << c.x << "," << c.y << " interior flag";
    }
}

TEST(RayCaster, OrthographicSphereUnderGlsDefaultLight) {
    // No light in the scene: GL's light 0, directional along -Z (l = (0,0,1)), diffuse and
    // specular 1; distant viewer v = (0,0,1), so Blinn's h = (0,0,1) and n.h = n.l = n_z.
    // c = 0.2 * 0.2 (global ambient) + 0.8 n_z + 1 * n_z^2 (shininess 2), n_z = sqrt(1 - x^2 -
    // y^2). 8 x 8 pixels over [-2, 2]^2: pixel i spans x in [-2 + i/2, -1.5 + i/2], row j spans y
    // in [1.5 - j/2, 2 - j/2].
    const test::SimpleScene s = orthoScene(makeSphere(1.0, 16, 8), grey(1.0, 2.0), 2.0);
    const ReferenceImage ref = cast(s.build(), size(8, 8), AnalyticShape::sphere(0, 1.0));
    auto lit = [](double x, double y) {
        const double nz = std::sqrt(1.0 - x * x - y * y);
        return 0.04 + 0.8 * nz + nz * nz;
    };
    expectPixels(ref,
                 {
                     {3, 3, lit(-0.25, 0.25), 1.0, 1,
                      "centre (-0.25, 0.25); the whole pixel is on the sphere"},
                     {4, 4, lit(0.25, -0.25), 1.0, 1, "centre (0.25, -0.25)"},
                     {2, 3, lit(-0.75, 0.25), 1.0, 0,
                      "centre (-0.75, 0.25); corner (-1, 0.5) is off the sphere"},
                     {2, 2, 0.0, 0.0, 0,
                      "centre (-0.75, 0.75) is off the sphere (r^2 = 1.125); a corner is on it"},
                     {0, 0, 0.0, 0.0, 0, "background"},
                 });
    EXPECT_EQ(ref.box.pixel(0, 0)[3], 0.0f) << "no part of pixel (0,0) is on the sphere";
    const float partial = ref.box.pixel(2, 2)[3];
    EXPECT_GT(partial, 0.0f);
    EXPECT_LT(partial, 0.5f) << "the sphere covers a small corner of pixel (2,2)";
}

TEST(RayCaster, PerspectivePointLightAtThePixelCentre) {
    // S1: unit sphere 4 units in front of a 40-degree camera; the light at eye (2, 2, 0).
    // The middle pixel of a 5 x 5 image looks straight down -Z and meets (0, 0, -3), n = +Z.
    // l = (2, 2, 3) / sqrt(17): n.l = 3 / sqrt(17); no attenuation;
    // Blinn: h = normalize(l + (0,0,1)), n.h = (3/sqrt(17) + 1) / |l + (0,0,1)|; shininess 8.
    test::SimpleScene s;
    s.primitive = makeSphere(1.0, 16, 8);
    s.material = grey(1.0, 8.0);
    s.projection = Projection::makePerspective(40.0 * kPi / 180.0, 0.0, 0.1, kInfinity);
    Light point;
    point.type = LightType::Point;
    glm::dmat4 at(1.0);
    at[3] = glm::dvec4(2, 2, 4, 1); // world; the camera at (0, 0, 4) makes it eye (2, 2, 0)
    s.lights = {{point, at}};
    const ReferenceImage ref = cast(s.build(), size(5, 5), AnalyticShape::sphere(0, 1.0));
    const double ndl = 3.0 / std::sqrt(17.0);
    const glm::dvec3 h(2.0 / std::sqrt(17.0), 2.0 / std::sqrt(17.0), ndl + 1.0);
    const double ndh = h.z / std::sqrt(glm::dot(h, h));
    const double expected = 0.04 + 0.8 * ndl + std::pow(ndh, 8.0);
    EXPECT_NEAR(expected, 1.1788348416, 1e-9) << "the derivation itself";
    expectPixels(ref, {{2, 2, expected, 1.0, 1, "0.04 + 0.8 n.l + (n.h)^8"}});
    // Up is up: the light is above and to the right, so the upper-right pixel is brighter
    // than the lower-left one (a flipped image or light would swap them).
    EXPECT_GT(ref.centre.pixel(3, 1)[0], ref.centre.pixel(1, 3)[0]);
}

TEST(RayCaster, GlSpotOnAPlaneInsideAndOutsideTheCone) {
    // A 6 x 6 plane facing the camera (wider than the view); a GL spot at (0, 0, 2) shining down
    // -Z, cutoff 30 degrees, exponent 2, no attenuation, no specular. 4 x 4 pixels over [-2, 2]^2.
    test::SimpleScene s = orthoScene(makePlane(6.0, 2), grey(0.0, 0.0), 2.0);
    Light spot;
    spot.type = LightType::Spot;
    spot.spotCutoffDeg = 30.0;
    spot.spotExponent = 2.0;
    glm::dmat4 at(1.0);
    at[3] = glm::dvec4(0, 0, 2, 1);
    s.lights = {{spot, at}};
    const ReferenceImage ref = cast(s.build(), size(4, 4), AnalyticShape::plane(0, 6.0));
    // Pixel (2,1): centre (0.5, 0.5, 0); towards the light (-0.5, -0.5, 2) / sqrt(4.5):
    // x = -l.s = 2 / sqrt(4.5) = 0.943 > cos 30 = 0.866, so spot = x^2 = 8/9; n.l = x.
    // Pixel (3,0): centre (1.5, 1.5): x = 2 / sqrt(8.5) = 0.686 < 0.866: outside, ambient only.
    expectPixels(ref, {
                          {2, 1, 0.04 + 0.8 * (2.0 / std::sqrt(4.5)) * (8.0 / 9.0), 1.0, 1,
                           "inside the cone"},
                          {3, 0, 0.04, 1.0, 1, "outside the cone: global ambient only"},
                      });
}

TEST(RayCaster, BoxFilterAtAPlaneEdgeAndTheInteriorMask) {
    // A 2 x 2 plane (|x|, |y| <= 1) under GL's headlight: c = 0.04 + 0.8 everywhere on it.
    // 5 x 5 pixels over [-2.5, 2.5]^2: pixel 3 spans x in [0.5, 1.5], so the edge x = 1 halves
    // it; 8 x 8 stratified samples split 4 : 4 across the pixel's middle.
    const test::SimpleScene s = orthoScene(makePlane(2.0, 1), grey(0.0, 0.0), 2.5);
    const ReferenceImage ref = cast(s.build(), size(5, 5), AnalyticShape::plane(0, 2.0), 8);
    const float* half = ref.box.pixel(3, 2);
    EXPECT_NEAR(half[0], 0.5 * 0.84, 1e-6) << "premultiplied: half the colour";
    EXPECT_EQ(half[3], 0.5f);
    EXPECT_EQ(ref.interior[2 * 5 + 3], 0) << "an edge pixel is not interior";
    const float* full = ref.box.pixel(2, 2);
    EXPECT_NEAR(full[0], 0.84, 1e-6);
    EXPECT_EQ(full[3], 1.0f);
    EXPECT_EQ(ref.interior[2 * 5 + 2], 1);
    const float* quarter = ref.box.pixel(3, 1);
    EXPECT_EQ(quarter[3], 0.25f) << "the corner (1, 1) quarters pixel (3,1)";
    EXPECT_EQ(ref.box.pixel(4, 2)[3], 0.0f);
    EXPECT_EQ(ref.rays, std::size_t(25 * (1 + 64 + 16)));
}

TEST(RayCaster, NodeScaleMakesAnEllipsoidWithInverseTransposeNormals) {
    // The unit sphere scaled (2, 1, 1): x^2/4 + y^2 + z^2 = 1, normal along (x/4, y, z).
    // At (1.25, 0.25): z^2 = 1 - 0.390625 - 0.0625; headlight: c = 0.04 + 0.8 n_z.
    test::SimpleScene s = orthoScene(makeSphere(1.0, 16, 8), grey(0.0, 0.0), 2.0);
    s.model = glm::dmat4(1.0);
    s.model[0][0] = 2.0;
    const ReferenceImage ref = cast(s.build(), size(8, 8), AnalyticShape::sphere(0, 1.0));
    const glm::dvec3 n(1.25 / 4.0, 0.25, std::sqrt(1.0 - 0.390625 - 0.0625));
    expectPixels(ref, {{6, 3, 0.04 + 0.8 * n.z / glm::length(n), 1.0, 1,
                        "centre (1.25, 0.25); the pixel lies inside the ellipse"}});
}

struct SidednessCase {
    const char* name;
    bool doubleSided, twoSided;
    double grey, alpha;
    const char* why;
};

class RayCasterSidedness : public ::testing::TestWithParam<SidednessCase> {};

TEST_P(RayCasterSidedness, ThePlaneSeenFromBehind) {
    // The plane turned away from the camera (normal -Z) under GL's headlight (l = +Z).
    const SidednessCase& c = GetParam();
    Material m = grey(0.0, 0.0);
    m.doubleSided = c.doubleSided;
    MaterialSide back = m.front;
    back.diffuse = {0.4, 0.4, 0.4, 1.0};
    m.back = back;
    test::SimpleScene s = orthoScene(makePlane(4.0, 1), m, 2.0);
    s.model = glm::mat4_cast(glm::angleAxis(kPi, glm::dvec3(0, 1, 0)));
    s.lighting.twoSided = c.twoSided;
    const ReferenceImage ref = cast(s.build(), size(4, 4), AnalyticShape::plane(0, 4.0));
    expectPixels(ref, {{1, 1, c.grey, c.alpha, c.alpha > 0 ? 1 : 0, c.why}});
}

INSTANTIATE_TEST_SUITE_P(
    Faces, RayCasterSidedness,
    ::testing::Values(
        SidednessCase{"culled", false, false, 0.0, 0.0, "single-sided: the back face is culled"},
        SidednessCase{"one_sided_lighting", true, false, 0.04, 1.0,
                      "drawn, front material, n = -Z unflipped: n.l = -1, ambient only"},
        SidednessCase{"two_sided_lighting", true, true, 0.04 + 0.4, 1.0,
                      "back material (diffuse 0.4) and -n = +Z: n.l = 1"}),
    [](const auto& p) { return std::string(p.param.name); });

TEST(RayCaster, RefusesWhatItDoesNotModel) {
    const test::SimpleScene s = orthoScene(makeSphere(1.0, 8, 4), grey(0.0, 0.0), 2.0);
    const Scene scene = s.build();
    ReferenceOptions good;
    good.shapes = {AnalyticShape::sphere(0, 1.0)};
    struct Refusal {
        const char* name;
        std::function<void(RenderOptions&, ReferenceOptions&, Scene&)> edit;
        ErrorCode code;
        const char* text;
    };
    const std::vector<Refusal> refusals = {
        {"no shape", [](RenderOptions&, ReferenceOptions& r, Scene&) { r.shapes.clear(); },
         ErrorCode::InvalidInput, "no analytic description"},
        {"shape of a missing mesh",
         [](RenderOptions&, ReferenceOptions& r, Scene&) { r.shapes[0].mesh = 3; },
         ErrorCode::InvalidInput, "does not exist"},
        {"zero radius", [](RenderOptions&, ReferenceOptions& r, Scene&) { r.shapes[0].radius = 0; },
         ErrorCode::InvalidInput, "radius"},
        {"views",
         [](RenderOptions& o, ReferenceOptions&, Scene&) {
             o.views.push_back(View{0, 0, 4, 4, {}});
         },
         ErrorCode::Unsupported, "one full-image view"},
        {"gl compat", [](RenderOptions& o, ReferenceOptions&, Scene&) { o.glCompat = true; },
         ErrorCode::Unsupported, "GL compatibility"},
        {"linear-filtered texture",
         [](RenderOptions&, ReferenceOptions&, Scene& sc) {
             sc.textures.push_back(Texture{"t", 1, 1, {255, 255, 255, 255}});
             sc.materials[0].baseColorTexture = 0;
         },
         ErrorCode::Unsupported, "textures nearest"},
        {"box samples", [](RenderOptions&, ReferenceOptions& r, Scene&) { r.boxSamples = 0; },
         ErrorCode::InvalidInput, "box samples"},
        {"empty image", [](RenderOptions& o, ReferenceOptions&, Scene&) { o.width = 0; },
         ErrorCode::InvalidInput, "image size"},
    };
    for (const Refusal& r : refusals) {
        RenderOptions o = size(4, 4);
        ReferenceOptions ro = good;
        Scene sc = scene;
        r.edit(o, ro, sc);
        auto ref = raycastReference(sc, o, 0.0, ro);
        ASSERT_FALSE(ref) << r.name;
        EXPECT_EQ(ref.error().code, r.code) << r.name << ": " << ref.error().describe();
        EXPECT_NE(ref.error().describe().find(r.text), std::string::npos)
            << r.name << ": " << ref.error().describe();
    }
    EXPECT_TRUE(raycastReference(scene, size(4, 4), 0.0, good));
}

TEST(RayCaster, TessellateBuildsTheMeshesTheShapesDescribe) {
    EXPECT_EQ(tessellate(AnalyticShape::sphere(0, 1.0), 8).triangleCount(), 48u)
        << "8 segments, 4 rings: 2 * 8 * 3";
    EXPECT_EQ(tessellate(AnalyticShape::sphere(0, 1.0), 64).triangleCount(), 3968u);
    EXPECT_EQ(tessellate(AnalyticShape::plane(0, 2.0), 4).triangleCount(), 32u);
    const Primitive sphere = tessellate(AnalyticShape::sphere(0, 2.5), 16);
    for (const glm::vec3& p : sphere.positions)
        EXPECT_NEAR(glm::length(p), 2.5f, 1e-5f);
}

// A reference of two pixels, both interior, values given; and a render of the same size.
ReferenceImage twoPixelReference(float a, float b) {
    ReferenceImage r;
    r.centre = Image(2, 1);
    for (int x = 0; x < 2; ++x)
        for (int k = 0; k < 4; ++k)
            r.centre.pixel(x, 0)[k] = k == 3 ? 1.0f : (x == 0 ? a : b);
    r.box = r.centre;
    r.interior = {1, 1};
    return r;
}

Image twoPixelRender(float a, float b, float alphaB = 1.0f) {
    Image img(2, 1);
    for (int k = 0; k < 3; ++k) {
        img.pixel(0, 0)[k] = a;
        img.pixel(1, 0)[k] = b;
    }
    img.pixel(0, 0)[3] = 1.0f;
    img.pixel(1, 0)[3] = alphaB;
    return img;
}

TEST(ReferenceMetrics, ComputedByHandOnTwoPixels) {
    const ReferenceImage ref = twoPixelReference(0.5f, 1.0f);
    auto exact = measureError(twoPixelRender(0.5f, 1.0f), ref);
    ASSERT_TRUE(exact);
    EXPECT_EQ(exact->whole.rmse, 0.0);
    EXPECT_TRUE(std::isinf(exact->psnr));
    EXPECT_EQ(exact->interior.pixels, 2u);
    EXPECT_EQ(exact->silhouette.pixels, 0u);
    EXPECT_DOUBLE_EQ(exact->peakRatio, 1.0);

    // The highlight pixel 0.25 low in every channel: RMSE sqrt(3 * 0.0625 / 6), max 0.25,
    // PSNR 20 log10(1 / rmse), peak 0.75 / 1.
    auto low = measureError(twoPixelRender(0.5f, 0.75f), ref);
    ASSERT_TRUE(low);
    EXPECT_NEAR(low->whole.rmse, std::sqrt(0.0625 / 2.0), 1e-7);
    EXPECT_NEAR(low->interior.rmse, std::sqrt(0.0625 / 2.0), 1e-7);
    EXPECT_NEAR(low->interior.max, 0.25, 1e-7);
    EXPECT_NEAR(low->interior.p99, 0.25, 1e-7) << "the 99th percentile of two is the larger";
    EXPECT_NEAR(low->psnr, 20.0 * std::log10(1.0 / std::sqrt(0.0625 / 2.0)), 1e-5);
    EXPECT_NEAR(low->peakRatio, 0.75, 1e-7);

    // A render that covers the second pixel only half (MSAA at a tessellated outline): its
    // error is a geometry error, counted with the silhouettes.
    auto partial = measureError(twoPixelRender(0.5f, 0.5f, 0.5f), ref);
    ASSERT_TRUE(partial);
    EXPECT_EQ(partial->interior.pixels, 1u);
    EXPECT_EQ(partial->silhouette.pixels, 1u);
    EXPECT_NEAR(partial->silhouette.max, 0.5, 1e-7);

    Image nan = twoPixelRender(0.5f, 1.0f);
    nan.pixel(0, 0)[1] = std::numeric_limits<float>::quiet_NaN();
    auto counted = measureError(nan, ref);
    ASSERT_TRUE(counted);
    EXPECT_EQ(counted->nonFinite, 1u);

    EXPECT_FALSE(measureError(Image(3, 1), ref)) << "sizes differ";
}

} // namespace
