// The lighting image tests' shared scene builder and per-pixel reference comparison.
#include "LightingCompare.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <sstream>

namespace lantern::test {

Scene LitScene::build() const {
    // The first object, the lights and the camera as SimpleScene builds them; then the rest.
    SimpleScene first;
    first.primitive = objects.at(0).primitive;
    first.material = objects[0].material;
    first.model = objects[0].model;
    first.lights = lights;
    first.projection = projection;
    first.lookAt = lookAt;
    first.lighting = lighting.value_or(LightingModel{});
    Scene s = first.build();
    s.roots[0].lighting = lighting;
    for (std::size_t i = 1; i < objects.size(); ++i) {
        Mesh mesh{"mesh " + std::to_string(i), {objects[i].primitive}};
        mesh.primitives[0].material = int(s.materials.size());
        s.materials.push_back(objects[i].material);
        Node n;
        n.name = "object " + std::to_string(i);
        n.mesh = int(s.meshes.size());
        n.matrix = objects[i].model;
        s.meshes.push_back(std::move(mesh));
        s.roots[0].nodes.push_back(int(s.nodes.size()));
        s.nodes.push_back(n);
    }
    return s;
}

Material phongMaterial(const glm::dvec3& ambient, const glm::dvec4& diffuse,
                       const glm::dvec3& specular, double shininess) {
    Material m;
    m.front.ambient = ambient;
    m.front.diffuse = diffuse;
    m.front.specular = specular;
    m.front.shininess = shininess;
    return m;
}

float brightestColour(const Image& image) {
    float b = 0.0f;
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        if (i % 4 != 3) b = std::max(b, image.rgba[i]);
    return b;
}

glm::dmat4 translation(const glm::dvec3& t) {
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(t, 1.0);
    return m;
}

glm::dmat4 aimed(const glm::dvec3& position, const glm::dvec3& direction) {
    const glm::dvec3 z = -glm::normalize(direction);
    const glm::dvec3 up = std::abs(z.y) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 x = glm::normalize(glm::cross(up, z));
    const glm::dvec3 y = glm::cross(z, x);
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(x, 0.0);
    m[1] = glm::dvec4(y, 0.0);
    m[2] = glm::dvec4(z, 0.0);
    m[3] = glm::dvec4(position, 1.0);
    return m;
}

Light makeLight(LightType type) {
    Light l;
    l.type = type;
    l.name = type == LightType::Directional ? "sun" : type == LightType::Point ? "bulb" : "spot";
    return l;
}

RenderOptions optionsFor(int width, int height, ShadingMode mode) {
    RenderOptions o;
    o.background = glm::vec4(0.0f); // alpha is coverage in these checks
    o.width = width;
    o.height = height;
    o.shading = mode;
    return o;
}

std::string ReferenceComparison::describe(const std::string& name) const {
    std::ostringstream s;
    s.precision(9);
    s << compared << " pixels compared; worst difference " << worst << " at (" << worstX << ", "
      << worstY << ")";
    if (worstX >= 0) {
        const float* p = pixel(worstX, worstY);
        s << ": rendered (" << p[0] << ", " << p[1] << ", " << p[2] << ", " << p[3]
          << "), reference (" << worstReport.colour.r << ", " << worstReport.colour.g << ", "
          << worstReport.colour.b << ", " << worstReport.colour.a << "), triangle "
          << worstReport.triangle << ", back facing " << worstReport.backFacing;
    }
    s << "\n" << saveComparison(frame.readback.image, expected, name);
    return s.str();
}

Result<render::RenderedFrame> renderWithIds(gpu::Device& device, const Scene& scene,
                                            const RenderOptions& options,
                                            const render::FrameEdits& edits, double time) {
    RenderOptions o = options;
    o.aovs.depth = o.aovs.normal = true;
    LANTERN_TRY(render::checkOptions(device, o));
    LANTERN_TRY(scene.validate());
    // Not owned: the scene outlives the synchronous render.
    auto buffers = device.upload(std::shared_ptr<const Scene>(std::shared_ptr<const Scene>(), &scene));
    if (!buffers) return std::move(buffers).error();
    FrameStats stats;
    // The ids plane is read back only when a frame asks for it (as the probe does).
    render::FrameEdits withIds = edits;
    withIds.list = [&edits](gpu::DrawList& list) {
        list.target.ids = true;
        if (edits.list) edits.list(list);
    };
    return render::renderFrame(device, *buffers, scene, o, time, stats, withIds);
}

ReferenceComparison compareWithReference(gpu::Device& device, const Scene& scene,
                                         const RenderOptions& options, const PixelCheck& check,
                                         const render::FrameEdits& edits, double time) {
    ReferenceComparison c;
    auto f = renderWithIds(device, scene, options, edits, time);
    if (!f) {
        ADD_FAILURE() << f.error().describe();
        return c;
    }
    c.frame = std::move(*f);
    const Image& img = c.frame.readback.image;
    const std::vector<std::uint32_t>& ids = c.frame.readback.ids;
    const ref::PixelReference reference(scene, c.frame.frame, img.height);
    c.expected = Image(img.width, img.height);
    c.reports.resize(img.pixelCount());
    auto drawAt = [&](int x, int y) -> std::uint32_t {
        if (x < 0 || y < 0 || x >= img.width || y >= img.height) return 0;
        return ids[(std::size_t(y) * img.width + x) * 2];
    };
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const std::size_t i = std::size_t(y) * img.width + x;
            const std::uint32_t drawId = ids[i * 2];
            if (drawId == 0) continue;
            ProbeReport r = reference.explain(x, y, drawId, ids[i * 2 + 1], check.perLight);
            for (int k = 0; k < 4; ++k)
                c.expected.pixel(x, y)[k] = float(r.colour[k]);
            const float* got = img.pixel(x, y);
            r.pixel = glm::dvec4(got[0], got[1], got[2], got[3]);
            bool interior = true;
            if (check.skipSilhouettes)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        interior &= drawAt(x + dx, y + dy) == drawId;
            if (interior) {
                ++c.compared;
                for (int k = 0; k < 4; ++k) {
                    const double want = r.colour[k];
                    const double d =
                        std::abs(double(got[k]) - want) / std::max(1.0, std::abs(want));
                    if (!(d <= c.worst)) {
                        c.worst = std::isnan(d) ? HUGE_VAL : d;
                        c.worstX = x;
                        c.worstY = y;
                        c.worstReport = r;
                    }
                }
            }
            c.reports[i] = std::move(r);
        }
    return c;
}

Image RenderTest::render(const Scene& scene, const RenderOptions& options) {
    auto image = renderer().render(scene, options, 0.0);
    EXPECT_TRUE(image) << image.error().describe();
    return image ? std::move(*image) : Image{};
}

} // namespace lantern::test
