// The metallic-roughness mapping (gltf::phongFromPbr, docs/scene-format-support.md
// "Materials") swept over metallic and roughness on a lit sphere, rendered in phong mode and
// checked pixel by pixel against the double-precision reference; the reference's per-light
// terms then show the properties the mapping promises: no combination is a constant-colour
// silhouette, a rougher surface has a wider and dimmer highlight, a metal's highlight takes
// the base colour and a dielectric's stays white, and glTF's default material (metallic 1,
// roughness 1) is a matte light surface.
#include "LightingCompare.h"

#include "io/gltf/GltfInternal.h"
#include "lantern_shared.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

// The shaders' per-texel mapping (shaders/include/maps.glsl) uses the loader's range.
static_assert(lantern::gltf::kMinPbrShininess == LANTERN_PBR_MIN_SHININESS);
static_assert(lantern::gltf::kMaxPbrShininess == LANTERN_PBR_MAX_SHININESS);

namespace {

using namespace lantern;
using lantern::test::GpuTest;
using lantern::test::LitScene;

constexpr int kSize = 96;
const glm::dvec3 kBase{0.9, 0.35, 0.1};  // an orange: a tinted highlight is told from white

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

Material pbrMaterial(const glm::dvec3& base, double metallic, double roughness) {
    const gltf::PhongFromPbr p = gltf::phongFromPbr(base, metallic, roughness);
    Material m;
    m.front.diffuse = glm::dvec4(p.diffuse, 1.0);
    m.front.ambient = p.diffuse;
    m.front.specular = p.specular;
    m.front.shininess = p.shininess;
    m.ambientFollowsDiffuse = true;
    return m;
}

Scene pbrSphere(const Material& m) {
    LitScene s;
    s.objects.push_back({makeSphere(1.0, 64, 32), m, glm::dmat4(1.0)});
    // From the upper left, not from the eye: the highlight and the terminator are apart.
    s.lights.push_back({test::makeLight(LightType::Directional), test::aimed({0, 0, 0}, {1, -1, -1})});
    return s.build();
}

// What the reference says about one render: the colour range over the sphere and its
// specular lobe (largest value, pixels above half of it, its colour where largest).
struct Sweep {
    double metallic = 0, roughness = 0;
    std::size_t hits = 0;
    double minLum = 1e30, maxLum = 0;       ///< over the whole sphere
    double minLitLum = 1e30, maxLitLum = 0; ///< over its lit side (n.l > 0)
    double peakSpecular = 0;          ///< luminance of the largest specular term
    glm::dvec3 peakSpecularColour{0};
    std::size_t wideSpecular = 0;     ///< pixels whose specular is above half the peak
};

Sweep measure(gpu::Device& device, double metallic, double roughness, const glm::dvec3& base) {
    Sweep w;
    w.metallic = metallic;
    w.roughness = roughness;
    test::PixelCheck check;
    check.perLight = true;
    const test::ReferenceComparison c =
        test::compareWithReference(device, pbrSphere(pbrMaterial(base, metallic, roughness)),
                                   test::optionsFor(kSize, kSize, ShadingMode::Phong), check);
    std::ostringstream name;
    name << "pbr_m" << metallic << "_r" << roughness;
    EXPECT_LE(c.worst, 1.0 / 255) << c.describe(name.str());
    EXPECT_EQ(c.frame.readback.nonFinite, 0u) << name.str();
    std::vector<double> spec;
    for (const ProbeReport& r : c.reports) {
        if (!r.hit || r.evaluations.empty()) continue;
        const ProbeEvaluation& e = r.evaluations[0];
        ++w.hits;
        const double lum = luminance(e.colour);
        w.minLum = std::min(w.minLum, lum);
        w.maxLum = std::max(w.maxLum, lum);
        const ProbeLight& l = e.lights[0];
        if (l.nDotL > 0.0) {
            w.minLitLum = std::min(w.minLitLum, lum);
            w.maxLitLum = std::max(w.maxLitLum, lum);
        }
        const double s = luminance(l.specular);
        spec.push_back(s);
        if (s > w.peakSpecular) {
            w.peakSpecular = s;
            w.peakSpecularColour = l.specular;
        }
    }
    for (double s : spec) w.wideSpecular += s > 0.5 * w.peakSpecular && w.peakSpecular > 0;
    return w;
}

class PbrMapping : public GpuTest {};

TEST_F(PbrMapping, SweepKeepsTheLookOfAMetallicRoughnessRenderer) {
    const double metals[] = {0.0, 0.5, 1.0};
    const double roughs[] = {0.3, 0.5, 0.7, 0.9, 1.0};
    for (double m : metals) {
        std::vector<Sweep> row;
        for (double r : roughs) row.push_back(measure(device(), m, r, kBase));
        for (std::size_t i = 0; i < row.size(); ++i) {
            const Sweep& w = row[i];
            const std::string at = "metallic " + std::to_string(m) + ", roughness " + std::to_string(w.roughness);
            ASSERT_GT(w.hits, std::size_t(kSize * kSize / 5)) << at;
            // Never a constant-colour silhouette: the lit side itself shades from its brightest
            // point down towards the terminator.
            EXPECT_LT(w.minLitLum, 0.5 * w.maxLitLum)
                << at << ": lit side's luminance " << w.minLitLum << " to " << w.maxLitLum;
            if (i == 0) continue;
            const Sweep& smoother = row[i - 1];
            // Rougher: a dimmer peak and (while there is a lobe) at least as many pixels in it.
            EXPECT_LT(w.peakSpecular, smoother.peakSpecular) << at;
            if (w.peakSpecular > 0) {
                EXPECT_GE(w.wideSpecular, smoother.wideSpecular) << at;
            }
        }
        // Over the sweep the lobe widens markedly.
        const Sweep& sharp = row.front();
        const Sweep& broad = m < 1.0 ? row.back() : row[row.size() - 2];
        EXPECT_GE(broad.wideSpecular, 4 * std::max<std::size_t>(sharp.wideSpecular, 1))
            << "metallic " << m;
        // A metal's highlight is the base colour; a dielectric's is white.
        const glm::dvec3 c = sharp.peakSpecularColour;
        if (m == 1.0) {
            EXPECT_NEAR(c.g / c.r, kBase.g / kBase.r, 1e-6) << "metal highlight colour";
        } else if (m == 0.0) {
            EXPECT_NEAR(c.g / c.r, 1.0, 1e-6) << "dielectric highlight colour";
        }
    }
}

// glTF's default material (base 1, metallic 1, roughness 1): a white Lambertian sphere, its
// brightest pixel near 1 (diffuse plus the global ambient), falling to the ambient alone on the
// unlit side; before this mapping it was a white silhouette of constant colour.
TEST_F(PbrMapping, GltfDefaultMaterialIsAMatteLightSurface) {
    const Sweep w = measure(device(), 1.0, 1.0, glm::dvec3(1.0));
    EXPECT_EQ(w.peakSpecular, 0.0);
    EXPECT_GT(w.maxLum, 0.9);
    EXPECT_LT(w.minLum, 0.25);
    EXPECT_LT(w.minLitLum, 0.5 * w.maxLitLum);
}

} // namespace
