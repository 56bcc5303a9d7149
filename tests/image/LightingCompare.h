// LightingCompare.h: what the lighting image tests share: a scene builder for several lit
// objects, and the comparison of a render with the double-precision reference pixel by
// pixel (each pixel's draw and triangle from the id AOV, its colour from the reference under
// the same interpolation rule: reference/PixelReference.h).
#pragma once

#include "TestSupport.h"
#include "reference/PixelReference.h"
#include "render/FrameRender.h"

#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <tuple>
#include <vector>

namespace lantern::test {

/// Objects (primitive, material, world transform), lights (light, world transform), one
/// camera and the scene's lighting model (absent: the scene chooses nothing). Object 0 is
/// node 0 ("object"), then the lights' nodes, then the other objects ("object N").
struct LitScene {
    struct Object {
        Primitive primitive;
        Material material;
        glm::dmat4 model{1.0};
    };
    std::vector<Object> objects;
    std::vector<std::pair<Light, glm::dmat4>> lights;
    Projection projection = Projection::makePerspective(0.6981317007977318, 0.0, 0.1, kInfinity);
    LookAt lookAt{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}};
    std::optional<LightingModel> lighting = LightingModel{};
    Scene build() const;
};

/// A Phong material (front side).
Material phongMaterial(const glm::dvec3& ambient, const glm::dvec4& diffuse,
                       const glm::dvec3& specular, double shininess);

/// The largest colour channel value of an image (alpha left out).
float brightestColour(const Image& image);

/// A world transform that only translates.
glm::dmat4 translation(const glm::dvec3& t);

/// A light of the given type with GL falloff, white diffuse and specular.
Light makeLight(LightType type);
/// A world transform at `position` whose -Z axis (where lights shine) points along `direction`.
glm::dmat4 aimed(const glm::dvec3& position, const glm::dvec3& direction);

/// How a render is compared with the reference.
struct PixelCheck {
    /// Leave out pixels next to the background or to another draw (silhouettes).
    bool skipSilhouettes = false;
    bool perLight = false; ///< fill ProbeReport per-light terms (slower)
};

/// The outcome of comparing every covered pixel of an opaque render with the reference.
struct ReferenceComparison {
    render::RenderedFrame frame;  ///< the frame model and what was read back
    Image expected;           ///< the reference colour of every covered pixel
    std::size_t compared = 0; ///< pixels compared
    /// The largest |rendered - reference| / max(1, |reference|) over compared pixels and
    /// channels (compare with PixelCheck::tolerance).
    double worst = 0.0;
    int worstX = -1, worstY = -1;
    ProbeReport worstReport;
    std::vector<ProbeReport> reports; ///< per pixel (hit = false for the background)

    const ProbeReport& at(int x, int y) const {
        return reports[std::size_t(y) * frame.readback.image.width + x];
    }
    const float* pixel(int x, int y) const { return frame.readback.image.pixel(x, y); }
    /// The worst pixel, both colours, and the paths of saved actual/expected/diff images.
    std::string describe(const std::string& name) const;
};

/// Renders `scene` (AOVs on, optionally edited plan) and compares every covered pixel with
/// the reference. Fails the current test on a render error.
/// Renders `scene` on the engine's device with the depth, normal and id AOVs on; `edits` may
/// change the frame or the draw list before submission.
Result<render::RenderedFrame> renderWithIds(gpu::Device& device, const Scene& scene,
                                            const RenderOptions& options,
                                            const render::FrameEdits& edits = {},
                                            double time = 0.0);

ReferenceComparison compareWithReference(gpu::Device& device, const Scene& scene,
                                         const RenderOptions& options,
                                         const PixelCheck& check = {},
                                         const render::FrameEdits& edits = {},
                                         double time = 0.0);

/// A GpuTest whose render() renders a scene at time 0 on the test's renderer; a failure fails
/// the test, naming the error, and gives an empty image.
class RenderTest : public GpuTest {
protected:
    Image render(const Scene& scene, const RenderOptions& options);
};

/// RenderOptions of the given size and shading mode.
RenderOptions optionsFor(int width, int height, ShadingMode mode);

} // namespace lantern::test
