// KHR_texture_transform and the sampler wrap modes on the GPU: a textured square filling an
// orthographic view, unlit so that each pixel is its texel. A material's uv transform must
// draw exactly what the same transform applied to the texture coordinates draws (and differ
// from the untransformed picture); MIRRORED_REPEAT over u in [0, 2] must give a picture whose
// right half mirrors its left, where REPEAT gives a translated copy. A minified texture samples
// the mip levels the host made (gpu/TextureMips.h), each copied to its own level.
#include "LightingCompare.h"

#include "io/gltf/GltfInternal.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

constexpr int kSize = 64;

// 8x8 texels, every one a different colour, nothing symmetric.
Texture checker(TextureWrap wrapS, TextureWrap wrapT) {
    Texture t;
    t.name = "checker";
    t.width = t.height = 8;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            t.rgba8.insert(t.rgba8.end(), {std::uint8_t(x * 32), std::uint8_t(y * 32),
                                           std::uint8_t(((x * 3 + y * 5) % 8) * 32), 255});
    t.nearest = true;
    t.wrapS = wrapS;
    t.wrapT = wrapT;
    return t;
}

Scene texturedSquare(const Texture& texture, const glm::dmat3& uvTransform,
                     const std::function<glm::vec2(glm::vec2)>& texcoords = {}) {
    LitScene s;
    Material m;
    m.unlit = true;
    m.front.diffuse = {1, 1, 1, 1};
    m.baseColorTexture = 0;
    m.baseColorUvTransform = uvTransform;
    Primitive square = makePlane(2.0, 1);
    if (texcoords)
        for (glm::vec2& uv : square.texcoords) uv = texcoords(uv);
    s.objects.push_back({square, m, glm::dmat4(1.0)});
    s.projection = Projection::makeOrtho(-1, 1, -1, 1, 0.1, 10);
    s.lookAt = LookAt{{0, 0, 2}, {0, 0, 0}, {0, 1, 0}};
    Scene scene = s.build();
    scene.textures.push_back(texture);
    return scene;
}

Image render(gpu::Device& device, const Scene& scene) {
    auto f = test::renderWithIds(device, scene, test::optionsFor(kSize, kSize, ShadingMode::Phong));
    EXPECT_TRUE(f) << (f ? "" : f.error().describe());
    if (!f) return {};
    EXPECT_EQ(f->readback.nonFinite, 0u);
    return std::move(f->readback.image);
}

double largestDifference(const Image& a, const Image& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i)
        worst = std::max(worst, double(std::abs(a.rgba[i] - b.rgba[i])));
    return worst;
}

class TextureTransform : public GpuTest {};

TEST_F(TextureTransform, DrawsWhatTheTransformedTexcoordsDraw) {
    const Texture tex = checker(TextureWrap::Repeat, TextureWrap::Repeat);
    for (const auto& [offset, rotation, scale] :
         {std::tuple{glm::dvec2(0.25, 0.5), 0.0, glm::dvec2(1.0)},
          std::tuple{glm::dvec2(0.0), 0.3, glm::dvec2(1.0)},
          std::tuple{glm::dvec2(0.0), 0.0, glm::dvec2(1.5, -0.75)},
          std::tuple{glm::dvec2(0.1, 1.0), 1.2, glm::dvec2(0.5, 2.0)}}) {
        const glm::dmat3 t = gltf::textureTransform(offset, rotation, scale);
        const Image viaMaterial = render(device(), texturedSquare(tex, t));
        const Image viaTexcoords = render(device(), texturedSquare(tex, glm::dmat3(1.0), [&](glm::vec2 uv) {
            return glm::vec2(t * glm::dvec3(uv, 1.0));
        }));
        const Image untransformed = render(device(), texturedSquare(tex, glm::dmat3(1.0)));
        // Nearest texels: a pixel centre near a texel edge may land on either side in float.
        std::size_t differing = 0;
        for (std::size_t i = 0; i < viaMaterial.rgba.size(); i += 4)
            differing += std::abs(viaMaterial.rgba[i] - viaTexcoords.rgba[i]) +
                             std::abs(viaMaterial.rgba[i + 1] - viaTexcoords.rgba[i + 1]) > 1e-4;
        EXPECT_LE(differing, std::size_t(kSize * kSize / 100))
            << "offset " << offset.x << "," << offset.y << " rotation " << rotation;
        EXPECT_GT(largestDifference(viaMaterial, untransformed), 0.1) << "the transform changed nothing";
    }
}

TEST_F(TextureTransform, MirroredRepeatMirrorsWhereRepeatTranslates) {
    auto doubled = [](glm::vec2 uv) { return glm::vec2(uv.x * 2.0f, uv.y); };  // u in [0, 2]
    const Image mirrored =
        render(device(), texturedSquare(checker(TextureWrap::MirroredRepeat, TextureWrap::Repeat),
                                        glm::dmat3(1.0), doubled));
    const Image repeated = render(device(), texturedSquare(checker(TextureWrap::Repeat, TextureWrap::Repeat),
                                                           glm::dmat3(1.0), doubled));
    ASSERT_EQ(mirrored.width, kSize);
    double mirrorError = 0.0, repeatShiftError = 0.0, repeatMirrorError = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize / 2; ++x)
            for (int c = 0; c < 3; ++c) {
                mirrorError = std::max(mirrorError, double(std::abs(mirrored.pixel(x, y)[c] -
                                                                    mirrored.pixel(kSize - 1 - x, y)[c])));
                repeatShiftError = std::max(repeatShiftError, double(std::abs(repeated.pixel(x, y)[c] -
                                                                              repeated.pixel(x + kSize / 2, y)[c])));
                repeatMirrorError = std::max(repeatMirrorError, double(std::abs(repeated.pixel(x, y)[c] -
                                                                                repeated.pixel(kSize - 1 - x, y)[c])));
            }
    EXPECT_LT(mirrorError, 1e-5);
    EXPECT_LT(repeatShiftError, 1e-5);
    EXPECT_GT(repeatMirrorError, 0.1);
    // The left halves agree: mirroring only changes what lies beyond u = 1.
    double leftError = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize / 2; ++x)
            leftError = std::max(leftError, double(std::abs(mirrored.pixel(x, y)[0] - repeated.pixel(x, y)[0])));
    EXPECT_LT(leftError, 1e-5);
}

// A black and white checker of single texels, 128 x 32 (levels 64x16 down to 1x1, each a
// different shape), repeated 8 times across the square: each pixel covers 16 x 4 texels, so
// the sampler reads levels 2 to 4, where every texel is half the light (sRGB 188: 0.5029
// linear). Level 0 alone, or a level copied to the wrong place, would alias to black and white.
TEST_F(TextureTransform, AMinifiedCheckerSamplesTheHostsMipLevels) {
    Texture t;
    t.name = "fine checker";
    t.width = 128;
    t.height = 32;
    for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) {
            const std::uint8_t v = (x + y) % 2 ? 255 : 0;
            t.rgba8.insert(t.rgba8.end(), {v, v, v, 255});
        }
    const Image image = render(device(), texturedSquare(t, glm::dmat3(1.0), [](glm::vec2 uv) {
        return uv * 8.0f;
    }));
    ASSERT_EQ(image.width, kSize);
    const double half = std::pow((188 / 255.0 + 0.055) / 1.055, 2.4);
    double worst = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(double(image.pixel(x, y)[c]) - half));
    EXPECT_LT(worst, 0.01) << "a minified pixel is not the checker's mean";
}

} // namespace
