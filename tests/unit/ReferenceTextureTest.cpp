// The reference's textures (reference/SurfaceTexture.cpp): the texture coordinates it computes
// on a sphere and a plane are the ones tessellate() gives their vertices, and nearest sampling
// follows Vulkan's rule with each wrap mode and the sRGB decode.
#include "reference/SurfaceTexture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace lantern;

TEST(ReferenceTexture, AnalyticCoordinatesAreTheTessellationsAtItsVertices) {
    for (const AnalyticShape& shape : {AnalyticShape::plane(0, 3.0), AnalyticShape::sphere(0, 0.7)}) {
        const Primitive p = tessellate(shape, 16);
        ASSERT_EQ(p.texcoords.size(), p.positions.size());
        for (std::size_t i = 0; i < p.positions.size(); ++i) {
            const glm::dvec3 q(p.positions[i]);
            const glm::dvec2 uv = ref::analyticUv(shape, q);
            // The sphere's seam column is duplicated (u = 0 and 1) and its poles have every u.
            const bool pole = shape.kind == AnalyticKind::Sphere && std::abs(std::abs(q.y) - 0.7) < 1e-6;
            const double du = std::abs(uv.x - p.texcoords[i].x);
            if (!pole) {
                EXPECT_TRUE(du < 1e-6 || std::abs(du - 1.0) < 1e-6) << i << " u " << uv.x;
            }
            // v through its cosine: acos is ill-conditioned at the poles' float positions.
            EXPECT_NEAR(std::cos(3.14159265358979323846 * uv.y),
                        std::cos(3.14159265358979323846 * p.texcoords[i].y), 1e-6) << i;
        }
    }
}

TEST(ReferenceTexture, NearestSamplingWrapsAndDecodes) {
    Texture t;
    t.width = 4;
    t.height = 2;
    t.srgb = true;
    for (int i = 0; i < 8; ++i) t.rgba8.insert(t.rgba8.end(), {std::uint8_t(i * 30), 0, 255, std::uint8_t(i * 30)});
    // Texel (x, y) = floor(uv * size): uv (0.3, 0.7) is texel (1, 1), index 5.
    glm::dvec4 c = ref::sampleNearest(t, {0.3, 0.7});
    EXPECT_NEAR(c.a, 150.0 / 255.0, 1e-12);  // alpha is linear
    EXPECT_NEAR(c.r, std::pow((150.0 / 255.0 + 0.055) / 1.055, 2.4), 1e-12);
    EXPECT_NEAR(c.b, 1.0, 1e-12);
    // Repeat: u = 1.3 is u = 0.3; mirrored: u = 1.3 is u = 0.7 (texel 2); clamp: texel 3.
    EXPECT_EQ(ref::sampleNearest(t, {1.3, 0.7}), c);
    t.wrapS = TextureWrap::MirroredRepeat;
    EXPECT_NEAR(ref::sampleNearest(t, {1.3, 0.7}).a, 180.0 / 255.0, 1e-12);
    t.wrapS = TextureWrap::ClampToEdge;
    EXPECT_NEAR(ref::sampleNearest(t, {1.3, 0.7}).a, 210.0 / 255.0, 1e-12);
    EXPECT_NEAR(ref::sampleNearest(t, {-0.5, 0.2}).a, 0.0, 1e-12);
    t.srgb = false;
    EXPECT_NEAR(ref::sampleNearest(t, {0.3, 0.7}).r, 150.0 / 255.0, 1e-12);
}

} // namespace
