// The KHR_materials_* extensions Lantern approximates in the classic equation
// (docs/scene-format-support.md, "The other KHR_materials extensions"), each rendered on a lit
// sphere beside the same material without it: the picture moves the way the extension means.
// specular and ior: a brighter highlight (and specularFactor 0 none); clearcoat: a second,
// sharper lobe on a rough base (a higher, narrower peak); sheen: a brighter body; transmission:
// the background seen through; volume: what is seen through tinted.
#include "../unit/GltfTestSupport.h"

#include <lantern/Io.h>
#include <lantern/Renderer.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using namespace lantern::test;
using nlohmann::json;

constexpr int kSize = 64;
constexpr double kPi = 3.14159265358979323846;

// A UV sphere of radius 1 (positions = normals) as a glTF mesh on node 0, lit by one
// directional light from the upper left, seen from +Z by a camera 4 units away.
GltfBuilder sphereFile(const json& material) {
    std::vector<float> pos;
    std::vector<std::uint16_t> idx;
    const int rings = 32, segments = 48;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const double th = kPi * r / rings, ph = 2 * kPi * s / segments;
            pos.insert(pos.end(), {float(std::sin(th) * std::cos(ph)), float(std::cos(th)),
                                   float(std::sin(th) * std::sin(ph))});
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const auto a = std::uint16_t(r * (segments + 1) + s), b = std::uint16_t(a + segments + 1);
            idx.insert(idx.end(), {a, std::uint16_t(a + 1), b, std::uint16_t(a + 1), std::uint16_t(b + 1), b});
        }
    GltfBuilder g;
    const int p = g.addFloats(pos, "VEC3");
    const int n = g.addFloats(pos, "VEC3");
    const int i = g.addIndices(idx);
    g.doc["materials"] = json::array({material});
    g.addNode({{"mesh", g.addMesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", i}, {"material", 0}})}});
    g.doc["cameras"] = json::array({json{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}});
    g.addNode({{"camera", 0}, {"translation", {0, 0, 4}}});
    g.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({json{{"type", "directional"}, {"intensity", 2.0}}});
    // -Z turned towards (-1, -1, -1): from the upper left front.
    g.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
               {"rotation", {-0.32505758, 0.32505758, 0.0, 0.88807383}}});
    g.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_specular", "KHR_materials_ior",
                               "KHR_materials_clearcoat", "KHR_materials_sheen",
                               "KHR_materials_transmission", "KHR_materials_volume"};
    return g;
}

json pbr(double metallic, double roughness, json extensions = json::object()) {
    json m = {{"pbrMetallicRoughness",
               {{"baseColorFactor", {0.6, 0.3, 0.2, 1.0}}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}};
    if (!extensions.empty()) m["extensions"] = extensions;
    return m;
}

struct Picture {
    double peak = 0;     ///< the brightest pixel's luminance
    std::size_t bright = 0;  ///< pixels above half of `peak` (how wide the highlight is)
    double meanLum = 0;  ///< over the whole picture
    glm::dvec3 centre{0};  ///< the middle pixel
};

class PbrExtensions : public GpuTest {
protected:
    Picture render(const json& material, const glm::vec4& background = {0, 0, 0, 1}) {
        GltfBuilder g = sphereFile(material);
        auto scene = loadScene(g.write(testOutputDir(), "sphere").string());
        EXPECT_TRUE(scene) << scene.error().describe();
        RenderOptions o;
        o.width = o.height = kSize;
        o.background = background;
        auto shared = std::make_shared<const Scene>(std::move(*scene));
        auto prepared = renderer().prepare(shared);
        EXPECT_TRUE(prepared);
        auto image = renderer().render(*prepared, o, 0.0);
        EXPECT_TRUE(image) << image.error().describe();
        Picture p;
        std::vector<double> lum(image->pixelCount());
        for (std::size_t k = 0; k < lum.size(); ++k) {
            const float* c = image->rgba.data() + k * 4;
            lum[k] = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            p.peak = std::max(p.peak, lum[k]);
            p.meanLum += lum[k] / double(lum.size());
        }
        for (double l : lum) p.bright += l > 0.5 * p.peak;
        const float* mid = image->pixel(kSize / 2, kSize / 2);
        p.centre = {mid[0], mid[1], mid[2]};
        return p;
    }
};

TEST_F(PbrExtensions, EachMovesThePictureTheWayItsExtensionMeans) {
    const Picture plain = render(pbr(0.0, 0.4));
    const Picture ior = render(pbr(0.0, 0.4, {{"KHR_materials_ior", {{"ior", 2.5}}}}));
    EXPECT_GT(ior.peak, plain.peak * 1.5) << "ior 2.5: F0 0.18 against 0.04";
    const Picture noSpecular = render(pbr(0.0, 0.4, {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}));
    EXPECT_LT(noSpecular.peak, plain.peak * 0.8) << "specularFactor 0: no highlight";
    const Picture roughBase = render(pbr(0.0, 0.9));
    const Picture coated = render(pbr(0.0, 0.9, {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}, {"clearcoatRoughnessFactor", 0.1}}}}));
    EXPECT_GT(coated.peak, roughBase.peak * 1.5) << "a sharp coat over a rough base";
    const Picture sheen = render(pbr(0.0, 0.4, {{"KHR_materials_sheen", {{"sheenColorFactor", {1.0, 1.0, 1.0}}}}}));
    EXPECT_GT(sheen.meanLum, plain.meanLum * 1.1) << "sheen brightens the body";
    // Transmission: a red background is seen through the sphere's centre.
    const glm::vec4 red{1, 0, 0, 1};
    const Picture opaqueOnRed = render(pbr(0.0, 0.4), red);
    const json glass = {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}}};
    const Picture glassOnRed = render(pbr(0.0, 0.4, glass), red);
    EXPECT_GT(glassOnRed.centre.r - glassOnRed.centre.g, opaqueOnRed.centre.r - opaqueOnRed.centre.g + 0.3)
        << "the red background through the glass";
    json tinted = glass;
    tinted["KHR_materials_volume"] = {{"thicknessFactor", 1.0}, {"attenuationColor", {0.1, 1.0, 0.1}}, {"attenuationDistance", 0.5}};
    const Picture green = render(pbr(0.0, 0.4, tinted), red);
    EXPECT_LT(green.centre.r, glassOnRed.centre.r) << "the volume absorbs red";
}

} // namespace
