// glTF's material maps on the GPU (shaders/include/maps.glsl): a square filling an
// orthographic view, textured with small nearest-filtered maps, against renders of the same
// square whose vertex data or material factors say what the map says:
// - a normal map draws what the same normal given per vertex draws (glTF's +Y is up in the
//   image), and a zero normal scale what no map draws; given tangents orient its frame;
// - an occlusion map scales the ambient term by 1 + strength (R - 1), in phong;
// - an emissive map multiplies the emission (sRGB-decoded), in every shading mode;
// - a map on the second texture-coordinate set reads it, in every shading mode;
// - a metallic-roughness map draws, texel by texel, what the factors it scales draw.
#include "LightingCompare.h"

#include "io/gltf/GltfInternal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/type_precision.hpp>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

constexpr int kSize = 48;

// A width x 1 texture whose left half is `left` and right half `right` (RGBA bytes).
Texture halves(glm::u8vec4 left, glm::u8vec4 right, bool srgb) {
    Texture t;
    t.name = "halves";
    t.width = 2;
    t.height = 1;
    t.rgba8 = {left.r, left.g, left.b, left.a, right.r, right.g, right.b, right.a};
    t.nearest = true;
    t.wrapS = t.wrapT = TextureWrap::ClampToEdge;
    t.srgb = srgb;
    return t;
}

// The square (z = 0, facing +Z, u along +X, v down the image) with `material`, lit by
// `lights`, seen straight on; `textures` become Scene::textures 0, 1...
Scene square(const Material& material, const std::vector<Texture>& textures,
             const std::vector<std::pair<Light, glm::dmat4>>& lights, glm::dvec3 globalAmbient,
             const glm::vec3& normal = {0, 0, 1}) {
    LitScene s;
    Primitive p = makePlane(2.0, 1);
    for (glm::vec3& n : p.normals) n = normal;
    s.objects.push_back({p, material, glm::dmat4(1.0)});
    s.lights = lights;
    s.projection = Projection::makeOrtho(-1, 1, -1, 1, 0.1, 10);
    s.lookAt = LookAt{{0, 0, 2}, {0, 0, 0}, {0, 1, 0}};
    LightingModel model;
    model.globalAmbient = globalAmbient;
    s.lighting = model;
    Scene scene = s.build();
    scene.textures = textures;
    return scene;
}

Image render(gpu::Device& device, const Scene& scene, ShadingMode mode = ShadingMode::Phong) {
    EXPECT_TRUE(scene.validate());
    auto f = test::renderWithIds(device, scene, test::optionsFor(kSize, kSize, mode));
    EXPECT_TRUE(f) << (f ? "" : f.error().describe());
    if (!f) return {};
    EXPECT_EQ(f->readback.nonFinite, 0u);
    return std::move(f->readback.image);
}

// The largest channel difference over pixels at least 2 away from the image's edges and from
// the vertical line between the textures' halves.
double interiorDifference(const Image& a, const Image& b) {
    double worst = 0.0;
    for (int y = 2; y < kSize - 2; ++y)
        for (int x = 2; x < kSize - 2; ++x) {
            if (std::abs(x - kSize / 2) < 2) continue;
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, double(std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c])));
        }
    return worst;
}

double srgbToLinear(int byte) {
    const double c = byte / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

class MaterialMaps : public GpuTest {};

// A shiny material lit obliquely, and a normal map of one texel: tangent-space (0.3, 0.4, 1)
// normalised, stored as bytes, and `decoded` as the shader decodes it.
struct NormalMapCase {
    Material shiny = test::phongMaterial({0.1, 0.1, 0.1}, {0.7, 0.6, 0.5, 1.0}, {0.6, 0.6, 0.6}, 30.0);
    std::vector<std::pair<Light, glm::dmat4>> lights = {
        {test::makeLight(LightType::Directional), test::aimed({1, 2, 3}, {-1, -2, -3})}};
    glm::u8vec4 texel;
    glm::vec3 decoded;
    Material mapped;
    NormalMapCase() {
        const glm::dvec3 t = glm::normalize(glm::dvec3(0.3, 0.4, 1.0));
        auto byte = [](double c) { return std::uint8_t(std::lround((c + 1) * 127.5)); };
        texel = glm::u8vec4(byte(t.x), byte(t.y), byte(t.z), 255);
        decoded = glm::normalize(glm::vec3(texel) / 255.0f * 2.0f - 1.0f);
        mapped = shiny;
        mapped.normalMap.texture = 0;
    }
};

TEST_F(MaterialMaps, ANormalMapDrawsWhatTheSameNormalPerVertexDraws) {
    auto [shiny, lights, texel, decoded, mapped] = NormalMapCase();
    const Image withMap = render(device(), square(mapped, {halves(texel, texel, false)}, lights, glm::dvec3(0.2)));
    const Image perVertex = render(device(), square(shiny, {}, lights, glm::dvec3(0.2), decoded));
    const Image flat = render(device(), square(shiny, {}, lights, glm::dvec3(0.2)));
    EXPECT_LT(interiorDifference(withMap, perVertex), 2e-4) << test::saveComparison(withMap, perVertex, "normal_map");
    EXPECT_GT(interiorDifference(withMap, flat), 0.05) << "the normal map changed nothing";
    // +Y of the map tilts towards world +Y (up the image), not down.
    const glm::vec3 mirrored(decoded.x, -decoded.y, decoded.z);
    const Image wrongWay = render(device(), square(shiny, {}, lights, glm::dvec3(0.2), mirrored));
    EXPECT_GT(interiorDifference(withMap, wrongWay), 0.02);
    // A zero normal scale keeps the geometric normal.
    mapped.normalScale = 0.0;
    const Image unscaled = render(device(), square(mapped, {halves(texel, texel, false)}, lights, glm::dvec3(0.2)));
    EXPECT_LT(interiorDifference(unscaled, flat), 2e-4);
}

// glTF TANGENT orients the normal map's frame: T the tangent, B = cross(N, T) w. A tangent
// along +u draws what the frame from derivatives draws; turned or with w = -1, the map tilts
// the normal the way the given frame says, though the texture coordinates are the same.
TEST_F(MaterialMaps, GivenTangentsOrientTheNormalMapsFrame) {
    const NormalMapCase n;  // no structured bindings: lambdas capture them only from clang 16
    const glm::vec3 m = n.decoded;
    auto withTangent = [&](const glm::vec4& tangent) {
        Scene scene = square(n.mapped, {halves(n.texel, n.texel, false)}, n.lights, glm::dvec3(0.2));
        Primitive& p = scene.meshes.at(0).primitives.at(0);
        p.tangents.assign(p.positions.size(), tangent);
        return render(device(), scene);
    };
    auto perVertex = [&](const glm::vec3& normal) {
        return render(device(), square(n.shiny, {}, n.lights, glm::dvec3(0.2), normal));
    };
    const Image derivatives =
        render(device(), square(n.mapped, {halves(n.texel, n.texel, false)}, n.lights, glm::dvec3(0.2)));
    const Image alongU = withTangent({1, 0, 0, 1});
    EXPECT_LT(interiorDifference(alongU, derivatives), 2e-4) << test::saveComparison(alongU, derivatives, "tangent_u");
    struct Case {
        glm::vec4 tangent;
        glm::vec3 normal;  // T m.x + B m.y + N m.z
        const char* name;
    };
    for (const Case& c : {Case{{0, 1, 0, 1}, {-m.y, m.x, m.z}, "tangent_up"},   // B = -X
                          Case{{1, 0, 0, -1}, {m.x, -m.y, m.z}, "tangent_w"},   // B = -Y
                          Case{{-2, 0, 0.5f, 1}, {-m.x, -m.y, m.z}, "tangent_back"}}) {  // not unit, not orthogonal
        SCOPED_TRACE(c.name);
        const Image given = withTangent(c.tangent);
        const Image expected = perVertex(c.normal);
        EXPECT_LT(interiorDifference(given, expected), 2e-4) << test::saveComparison(given, expected, c.name);
        EXPECT_GT(interiorDifference(given, derivatives), 0.02) << "the tangent changed nothing";
    }
}

TEST_F(MaterialMaps, OcclusionScalesTheAmbientTermInPhong) {
    Material m = test::phongMaterial({0.8, 0.6, 0.4}, {0.0, 0.0, 0.0, 1.0}, {0.0, 0.0, 0.0}, 1.0);
    m.occlusionMap.texture = 0;
    const std::vector<Texture> ao = {halves({255, 0, 0, 255}, {64, 0, 0, 255}, false)};
    for (double strength : {1.0, 0.5}) {
        m.occlusionStrength = strength;
        const Image img = render(device(), square(m, ao, {}, glm::dvec3(0.5)));
        const double dark = 1.0 + strength * (64.0 / 255.0 - 1.0);
        for (int c = 0; c < 3; ++c) {
            const double lit = 0.5 * m.front.ambient[c];
            EXPECT_NEAR(img.pixel(kSize / 4, kSize / 2)[c], lit, 1e-5);
            EXPECT_NEAR(img.pixel(3 * kSize / 4, kSize / 2)[c], lit * dark, 1e-5) << "strength " << strength;
        }
    }
    // Gouraud applies no occlusion map (docs/gl-differences.md): both halves alike.
    const Image gouraud = render(device(), square(m, ao, {}, glm::dvec3(0.5)), ShadingMode::Gouraud);
    EXPECT_NEAR(gouraud.pixel(kSize / 4, kSize / 2)[0], gouraud.pixel(3 * kSize / 4, kSize / 2)[0], 1e-6);
}

TEST_F(MaterialMaps, TheEmissiveMapMultipliesTheEmissionInEveryMode) {
    Material m = test::phongMaterial({0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 1.0}, {0.0, 0.0, 0.0}, 1.0);
    m.front.emission = {1.0, 0.5, 2.0};
    m.emissiveMap.texture = 0;
    const std::vector<Texture> emissive = {halves({200, 100, 50, 255}, {10, 255, 128, 255}, true)};
    // The texels as the device decodes sRGB: the same texture as an unlit base colour.
    Material unlit;
    unlit.unlit = true;
    unlit.front.diffuse = glm::dvec4(1.0);
    unlit.baseColorTexture = 0;
    const Image texels = render(device(), square(unlit, emissive, {}, glm::dvec3(0.0)));
    EXPECT_NEAR(texels.pixel(kSize / 4, kSize / 2)[0], srgbToLinear(200), 3e-3);
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
        SCOPED_TRACE(toString(mode));
        const Image img = render(device(), square(m, emissive, {}, glm::dvec3(0.0)), mode);
        for (int x : {kSize / 4, 3 * kSize / 4})
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(img.pixel(x, kSize / 2)[c], m.front.emission[c] * texels.pixel(x, kSize / 2)[c], 1e-6)
                    << "x " << x << " channel " << c;
    }
}

// A map on the second texture-coordinate set (Primitive::texcoords1, a bake's TEXCOORD_1)
// reads it, in every shading mode: the emissive map on a mirrored second set draws what it
// draws on the first set mirrored, and not what the first set draws. In phong the occlusion
// map does the same.
TEST_F(MaterialMaps, AMapOnTheSecondSetReadsIt) {
    Material m = test::phongMaterial({0.3, 0.3, 0.3}, {0.2, 0.2, 0.2, 1.0}, {0.0, 0.0, 0.0}, 1.0);
    m.front.emission = {1.0, 0.5, 2.0};
    m.emissiveMap.texture = 0;
    m.occlusionMap.texture = 1;
    const std::vector<Texture> maps = {halves({200, 100, 50, 255}, {10, 255, 128, 255}, true),
                                       halves({255, 0, 0, 255}, {40, 0, 0, 255}, false)};
    const std::vector<std::pair<Light, glm::dmat4>> lights = {
        {test::makeLight(LightType::Directional), test::aimed({0, 0, 3}, {0, 0, -3})}};
    auto mirrored = [](std::vector<glm::vec2> uv) {
        for (glm::vec2& t : uv) t.x = 1.0f - t.x;
        return uv;
    };
    for (ShadingMode mode : {ShadingMode::Phong, ShadingMode::Gouraud, ShadingMode::Flat}) {
        SCOPED_TRACE(toString(mode));
        // The maps on the first set, mirrored.
        Scene first = square(m, maps, lights, glm::dvec3(0.2));
        Primitive& p = first.meshes.at(0).primitives.at(0);
        p.texcoords = mirrored(p.texcoords);
        // The same maps on a second set that is mirrored; the first set is not.
        Material onSecond = m;
        onSecond.emissiveMap.secondSet = onSecond.occlusionMap.secondSet = true;
        Scene second = square(onSecond, maps, lights, glm::dvec3(0.2));
        Primitive& q = second.meshes.at(0).primitives.at(0);
        q.texcoords1 = mirrored(q.texcoords);
        const Image a = render(device(), first, mode), b = render(device(), second, mode);
        const Image unmirrored = render(device(), square(m, maps, lights, glm::dvec3(0.2)), mode);
        EXPECT_LT(interiorDifference(a, b), 2e-4) << test::saveComparison(a, b, "second_set");
        EXPECT_GT(interiorDifference(b, unmirrored), 0.05) << "the second set changed nothing";
    }
}

// A PBR-mapped material as the loader makes it (gltf::phongFromPbr) from its factors.
Material pbrMaterial(const glm::dvec4& base, double metallic, double roughness) {
    const gltf::PhongFromPbr p = gltf::phongFromPbr(glm::dvec3(base), metallic, roughness);
    Material m;
    m.front.diffuse = glm::dvec4(p.diffuse, base.a);
    m.front.ambient = p.diffuse;
    m.front.specular = p.specular;
    m.front.shininess = p.shininess;
    m.ambientFollowsDiffuse = true;
    m.pbr = PbrFactors{base, metallic, roughness};
    return m;
}

TEST_F(MaterialMaps, AMetallicRoughnessMapDrawsWhatItsTexelsFactorsDraw) {
    const glm::dvec4 base(0.8, 0.5, 0.3, 1.0);
    const std::vector<std::pair<Light, glm::dmat4>> lights = {
        {test::makeLight(LightType::Point), test::translation({0.3, 0.2, 1.5})}};
    // Left: metallic 1 x 255/255, roughness 1 x 77/255; right: metallic 0, roughness 1. The
    // factors (a rough metal) have no specular colour: the map must still bring it in.
    const glm::u8vec4 left(0, 77, 255, 255), right(0, 255, 0, 255);
    Material mapped = pbrMaterial(base, 1.0, 1.0);
    mapped.metallicRoughnessMap.texture = 0;
    const Image img = render(device(), square(mapped, {halves(left, right, false)}, lights, glm::dvec3(0.2)));
    const Image metal = render(device(), square(pbrMaterial(base, 1.0, 77.0 / 255.0), {}, lights, glm::dvec3(0.2)));
    const Image dielectric = render(device(), square(pbrMaterial(base, 0.0, 1.0), {}, lights, glm::dvec3(0.2)));
    double worstLeft = 0.0, worstRight = 0.0;
    for (int y = 2; y < kSize - 2; ++y)
        for (int x = 2; x < kSize - 2; ++x)
            for (int c = 0; c < 3; ++c) {
                const double got = img.pixel(x, y)[c];
                if (x < kSize / 2 - 1)
                    worstLeft = std::max(worstLeft, std::abs(got - metal.pixel(x, y)[c]) / std::max(1.0, got));
                if (x > kSize / 2)
                    worstRight = std::max(worstRight, std::abs(got - dielectric.pixel(x, y)[c]) / std::max(1.0, got));
            }
    EXPECT_LT(worstLeft, 1e-3) << test::saveComparison(img, metal, "mr_map");
    EXPECT_LT(worstRight, 1e-3);
    EXPECT_GT(interiorDifference(metal, dielectric), 0.05) << "the two halves should differ";
}

} // namespace
