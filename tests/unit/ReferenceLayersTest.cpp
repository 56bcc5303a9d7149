// The reference ray caster's layers (lantern/Reference.h): blended surfaces composited in exact
// depth order, whatever order the scene lists them in, and exact shadow rays for every light
// type, checked against pixels computed by hand and against the same scene rendered without
// the shadowing light's direct terms.
#include "TestSupport.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <lantern/Reference.h>

#include <cmath>

namespace {

using namespace lantern;

// One placed analytic surface of a test scene.
struct Object {
    AnalyticShape shape;  ///< mesh filled in by build()
    Material material;
    glm::dmat4 model{1.0};
};

Material unlit(const glm::dvec4& colour, AlphaMode mode = AlphaMode::Blend) {
    Material m;
    m.unlit = true;
    m.front.diffuse = colour;
    m.alphaMode = mode;
    return m;
}

Material matte(AlphaMode mode = AlphaMode::Opaque, double alpha = 1.0) {
    Material m;
    m.front.ambient = {0.3, 0.2, 0.1};
    m.front.diffuse = {0.6, 0.7, 0.8, alpha};
    m.front.specular = {0.5, 0.5, 0.5};
    m.front.shininess = 20.0;
    m.alphaMode = mode;
    return m;
}

// The objects under an orthographic camera at (0, 0, 5) looking down -Z over [-2, 2]^2, lit by
// `lights` (none: GL's default light), and the reference options that describe them.
struct LayerScene {
    std::vector<Object> objects;
    std::vector<std::pair<Light, glm::dmat4>> lights;

    Scene build(ReferenceOptions& r) const {
        test::SimpleScene s;
        s.primitive = tessellate(objects[0].shape, 4);
        s.material = objects[0].material;
        s.model = objects[0].model;
        s.lights = lights;
        s.projection = Projection::makeOrtho(-2, 2, -2, 2, 1.0, 10.0);
        s.lookAt = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
        Scene scene = s.build();
        r.shapes = {objects[0].shape};
        r.shapes[0].mesh = 0;
        for (std::size_t i = 1; i < objects.size(); ++i) {
            const int mesh = int(scene.meshes.size());
            scene.meshes.push_back(Mesh{"mesh", {tessellate(objects[i].shape, 4)}});
            scene.meshes.back().primitives[0].material = int(scene.materials.size());
            scene.materials.push_back(objects[i].material);
            Node n;
            n.mesh = mesh;
            n.matrix = objects[i].model;
            scene.roots[0].nodes.push_back(int(scene.nodes.size()));
            scene.nodes.push_back(n);
            r.shapes.push_back(objects[i].shape);
            r.shapes.back().mesh = mesh;
        }
        return scene;
    }
};

RenderOptions size(int w, int h) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    o.background = {0.0f, 0.0f, 0.0f, 0.0f};
    return o;
}

ReferenceImage cast(const LayerScene& s, int w, int h, bool shadows = false) {
    ReferenceOptions r;
    const Scene scene = s.build(r);
    r.boxSamples = 2;
    r.shadows = shadows;
    auto ref = raycastReference(scene, size(w, h), 0.0, r);
    EXPECT_TRUE(ref) << ref.error().describe();
    return ref ? std::move(*ref) : ReferenceImage{};
}

void expectPixel(const ReferenceImage& ref, int x, int y, const glm::dvec4& expected, const char* why) {
    const float* p = ref.centre.pixel(x, y);
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(p[k], expected[k], 1e-6) << "pixel " << x << "," << y << " channel " << k << ": " << why;
}

glm::dmat4 at(const glm::dvec3& t) { return glm::translate(glm::dmat4(1.0), t); }

TEST(ReferenceLayers, ABlendedPlaneOverAnOpaqueOneCompositesInDepthOrder) {
    // A green opaque plane filling the view at z = 0; a red plane of opacity 0.25 over its
    // middle (|x|, |y| < 1) at z = 1. 8 x 8 pixels of 0.5: pixels 2..5 lie under the red plane.
    LayerScene s;
    s.objects.push_back({AnalyticShape::plane(0, 4.0), unlit({0, 1, 0, 1}, AlphaMode::Opaque)});
    s.objects.push_back({AnalyticShape::plane(0, 2.0), unlit({1, 0, 0, 0.25}), at({0, 0, 1})});
    const ReferenceImage ref = cast(s, 8, 8);
    expectPixel(ref, 3, 3, {0.25, 0.75, 0.0, 1.0}, "0.25 red + 0.75 green");
    expectPixel(ref, 0, 0, {0.0, 1.0, 0.0, 1.0}, "green alone");
    EXPECT_EQ(ref.interior[3 * 8 + 3], 1) << "the same two layers cover the pixel";
    // The red plane's edge runs between pixels 1 and 2: probes on pixel 1's edge meet it.
    EXPECT_EQ(ref.interior[3 * 8 + 1], 0) << "the red layer's edge";

    // The scene listing the red plane first gives the same picture.
    LayerScene swapped;
    swapped.objects = {s.objects[1], s.objects[0]};
    const ReferenceImage again = cast(swapped, 8, 8);
    EXPECT_EQ(again.centre.rgba, ref.centre.rgba);
    EXPECT_EQ(again.box.rgba, ref.box.rgba);

    // Alone over the transparent background: premultiplied red, alpha its opacity.
    LayerScene alone;
    alone.objects.push_back(s.objects[1]);
    expectPixel(cast(alone, 8, 8), 3, 3, {0.25, 0.0, 0.0, 0.25}, "premultiplied over nothing");
}

TEST(ReferenceLayers, CrossingBlendedPlanesSwapOrderWhereTheyCross) {
    // Plane A turned 30 degrees about Y (z = -x tan 30 along it: in front on the left), plane B
    // turned -30 degrees (in front on the right); they cross at x = 0. Left of it A is over B,
    // right of it B is over A: no order of the two objects is right on both sides.
    const double a = 0.4, b = 0.7;
    LayerScene s;
    const double angle = 0.5235987755982988;
    s.objects.push_back({AnalyticShape::plane(0, 4.0), unlit({1, 0, 0, a}),
                         glm::rotate(glm::dmat4(1.0), angle, glm::dvec3(0, 1, 0))});
    s.objects.push_back({AnalyticShape::plane(0, 4.0), unlit({0, 0, 1, b}),
                         glm::rotate(glm::dmat4(1.0), -angle, glm::dvec3(0, 1, 0))});
    for (Object& o : s.objects) o.material.doubleSided = true;
    const ReferenceImage ref = cast(s, 8, 8);
    // Left (x < 0): red over blue. Right: blue over red.
    expectPixel(ref, 2, 4, {a, (1 - a) * 0.0, (1 - a) * b, a + (1 - a) * b}, "red over blue");
    expectPixel(ref, 5, 4, {(1 - b) * a, 0.0, b, b + (1 - b) * a}, "blue over red");
}

// Where the light comes from, for a shadow centred at (-1.25, 0, 0) on the plane z = 0 cast by a
// sphere of radius 0.5 at (0, 0, 1): the line from there through the sphere's centre.
const glm::dvec3 kTowardsLight = glm::normalize(glm::dvec3(1.25, 0.0, 1.0));

// A node transform at `position` whose -Z (where lights shine) points along `direction`.
glm::dmat4 aimed(const glm::dvec3& position, const glm::dvec3& direction) {
    const glm::dvec3 up = std::abs(direction.y) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::inverse(glm::lookAt(position, position + direction, up));
}

std::pair<Light, glm::dmat4> lightOf(LightType type) {
    Light l;
    l.type = type;
    l.ambient = {0.1, 0.1, 0.1};
    if (type == LightType::Spot) {
        l.spotCutoffDeg = 60.0;
        l.spotExponent = 2.0;
    }
    const glm::dvec3 position = glm::dvec3(-1.25, 0.0, 0.0) + 2.4 * glm::dvec3(1.25, 0.0, 1.0);
    return {l, aimed(type == LightType::Directional ? glm::dvec3(0.0) : position, -kTowardsLight)};
}

glm::dvec4 pixel(const ReferenceImage& r, int x, int y) {
    const float* p = r.centre.pixel(x, y);
    return {p[0], p[1], p[2], p[3]};
}

TEST(ReferenceLayers, EveryLightTypeCastsExactShadows) {
    // 16 x 16 pixels of 0.25: pixel (3, 7) is the plane at (-1.125, 0.125), inside the
    // shadow; (13, 2) the plane at (1.375, 1.375), in the light; (8, 7) the sphere's lit top,
    // which must not shadow itself.
    for (LightType type : {LightType::Directional, LightType::Point, LightType::Spot}) {
        SCOPED_TRACE(int(type));
        LayerScene s;
        s.objects.push_back({AnalyticShape::plane(0, 4.0), matte()});
        s.objects.push_back({AnalyticShape::sphere(0, 0.5), matte(), at({0, 0, 1})});
        s.lights.push_back(lightOf(type));
        const ReferenceImage lit = cast(s, 16, 16, false), shadowed = cast(s, 16, 16, true);
        // The shadowed pixel is the scene with the light's diffuse and specular taken away.
        LayerScene dark = s;
        dark.lights[0].first.diffuse = dark.lights[0].first.specular = glm::dvec3(0.0);
        const ReferenceImage ambientOnly = cast(dark, 16, 16, false);
        expectPixel(shadowed, 3, 7, pixel(ambientOnly, 3, 7), "in the sphere's shadow");
        EXPECT_GT(pixel(lit, 3, 7).r, pixel(ambientOnly, 3, 7).r + 0.05) << "the light reaches it unshadowed";
        EXPECT_EQ(pixel(shadowed, 13, 2), pixel(lit, 13, 2)) << "outside the shadow nothing changes";
        EXPECT_EQ(pixel(shadowed, 8, 7), pixel(lit, 8, 7)) << "the sphere does not shadow itself";
    }
}

// The same shadow at the extremes the renderer's shadow maps are measured at: the scene scaled
// by 1e-3 and 1e4, and moved 1e7 units from the origin (camera and lights with it). Shadow
// rays start on the surface they leave: no pixel outside the shadow may lose light (acne), and
// the shadow keeps its pixels (no light leaks under the sphere).
TEST(ReferenceLayers, ShadowRaysHoldAtExtremeScalesAndDistances) {
    struct Extreme {
        double scale;
        glm::dvec3 offset;
    };
    for (const Extreme& e : {Extreme{1e-3, {}}, Extreme{1e4, {}}, Extreme{1.0, {1e7, -1e7, 1e7}}}) {
        SCOPED_TRACE(std::to_string(e.scale) + " at " + std::to_string(e.offset.x));
        for (LightType type : {LightType::Directional, LightType::Point}) {
            LayerScene s;
            const glm::dmat4 place = at(e.offset) * glm::scale(glm::dmat4(1.0), glm::dvec3(e.scale));
            s.objects.push_back({AnalyticShape::plane(0, 4.0), matte(), place});
            s.objects.push_back({AnalyticShape::sphere(0, 0.5), matte(), place * at({0, 0, 1})});
            auto light = lightOf(type);
            light.second = place * light.second;
            if (type == LightType::Point) light.first.attenuation = {1.0, 0.0, 0.0};
            s.lights.push_back(light);
            ReferenceOptions r;
            Scene scene = s.build(r);
            scene.cameras[0].projection = Projection::makeOrtho(-2 * e.scale, 2 * e.scale, -2 * e.scale,
                                                                2 * e.scale, e.scale, 10.0 * e.scale);
            const glm::dvec3 eye = glm::dvec3(place * glm::dvec4(0, 0, 5, 1));
            const glm::dvec3 centre = glm::dvec3(place * glm::dvec4(0, 0, 0, 1));
            scene.cameras[0].lookAt = LookAt{eye, centre, {0, 1, 0}};
            r.boxSamples = 1;
            auto lit = raycastReference(scene, size(16, 16), 0.0, r);
            r.shadows = true;
            auto shadowed = raycastReference(scene, size(16, 16), 0.0, r);
            ASSERT_TRUE(lit && shadowed);
            // Each pixel that sees the plane, in the scene's own units: in the shadow exactly
            // when the line from its point to the light passes within the sphere's radius
            // (pixels within 1e-3 of the shadow's edge are left out).
            const glm::dvec3 lightAt = glm::dvec3(-1.25, 0.0, 0.0) + 2.4 * glm::dvec3(1.25, 0.0, 1.0);
            int inShadow = 0;
            for (int y = 0; y < 16; ++y)
                for (int x = 0; x < 16; ++x) {
                    const glm::dvec3 p(-2.0 + 0.25 * (x + 0.5), 2.0 - 0.25 * (y + 0.5), 0.0);
                    if (p.x * p.x + p.y * p.y <= 0.26) continue;  // the sphere, seen from above
                    const glm::dvec3 toLight = type == LightType::Directional ? kTowardsLight : lightAt - p;
                    const glm::dvec3 u = glm::normalize(toLight), c(0.0, 0.0, 1.0);
                    const double along = glm::dot(c - p, u);
                    const double miss = glm::length(c - p - along * u);
                    if (std::abs(miss - 0.5) < 1e-3) continue;
                    const bool shade = miss < 0.5 && along > 0.0;
                    inShadow += shade;
                    const glm::dvec4 a = pixel(*lit, x, y), b = pixel(*shadowed, x, y);
                    if (shade)
                        EXPECT_LT(b.g, 0.7 * a.g) << "pixel " << x << "," << y << " should be in the shadow";
                    else
                        EXPECT_EQ(a, b) << "pixel " << x << "," << y << " lost light outside the shadow";
                }
            EXPECT_GE(inShadow, 4) << "the shadow is missing";
        }
    }
}

TEST(ReferenceLayers, ABlendedOccluderLetsThroughOneMinusItsAlpha) {
    const double alpha = 0.4;
    LayerScene s;
    s.objects.push_back({AnalyticShape::plane(0, 4.0), matte()});
    s.objects.push_back({AnalyticShape::sphere(0, 0.5), matte(AlphaMode::Blend, alpha), at({0, 0, 1})});
    s.lights.push_back(lightOf(LightType::Directional));
    LayerScene dark = s;
    dark.lights[0].first.diffuse = dark.lights[0].first.specular = glm::dvec3(0.0);
    const glm::dvec4 full = pixel(cast(s, 16, 16, false), 3, 7);
    const glm::dvec4 ambient = pixel(cast(dark, 16, 16, false), 3, 7);
    // The ray crosses the sphere twice (both faces): (1 - alpha)^2 of the light gets through.
    const double through = (1 - alpha) * (1 - alpha);
    expectPixel(cast(s, 16, 16, true), 3, 7, ambient + through * (full - ambient), "dimmed by the glass");
    // A masked sphere whose alpha is under the cutoff is not there for the light either.
    LayerScene masked = s;
    masked.objects[1].material = matte(AlphaMode::Mask, 0.2);
    expectPixel(cast(masked, 16, 16, true), 3, 7, pixel(cast(masked, 16, 16, false), 3, 7), "masked away");
}

} // namespace
