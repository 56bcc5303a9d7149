// Sub-pixel measurement of projected points with ramp quads, and image comparison that skips
// silhouette edges.
#include "CameraTestSupport.h"

#include "TestSupport.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <glm/matrix.hpp>
#include <vector>

namespace lantern::test {

PixelRect rectOfView(const View& view, int imageHeight) {
    return {view.x, imageHeight - view.y - view.height, view.width, view.height};
}

Primitive makeRampQuad(double width, double height, float id) {
    Primitive p;
    const float hw = float(width / 2), hh = float(height / 2);
    p.positions = {{-hw, -hh, 0}, {hw, -hh, 0}, {hw, hh, 0}, {-hw, hh, 0}};
    p.normals.assign(4, glm::vec3(0, 0, 1));
    p.colors = {{0, 0, id, 1}, {1, 0, id, 1}, {1, 1, id, 1}, {0, 1, id, 1}};
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

glm::dvec3 rampPoint(double width, double height, double u, double v) {
    // The quad's corners are floats; the point is where the interpolated colour is (u, v).
    const double hw = double(float(width / 2)), hh = double(float(height / 2));
    return {-hw + 2 * hw * u, -hh + 2 * hh * v, 0.0};
}

Material unlitMaterial(const std::string& name) {
    Material m;
    m.name = name;
    m.unlit = true;
    m.doubleSided = true;
    m.front.diffuse = {1, 1, 1, 1};
    return m;
}

std::optional<glm::dvec2> locateRamp(const Image& image, const PixelRect& rect, float id, double u,
                                     double v) {
    struct Sample {
        double du, dv, x, y, distance;
    };
    std::vector<Sample> samples;
    for (int y = std::max(rect.y, 0); y < std::min(rect.y + rect.height, image.height); ++y)
        for (int x = std::max(rect.x, 0); x < std::min(rect.x + rect.width, image.width); ++x) {
            const float* p = image.pixel(x, y);
            if (p[3] < 0.99f || std::abs(p[2] - id) > 0.01f) continue;
            const double du = p[0] - u, dv = p[1] - v;
            samples.push_back({du, dv, x + 0.5, y + 0.5, du * du + dv * dv});
        }
    if (samples.size() < 6) return std::nullopt;
    const std::size_t k = std::min<std::size_t>(samples.size(), 12);
    std::partial_sort(samples.begin(), samples.begin() + std::ptrdiff_t(k), samples.end(),
                      [](const Sample& a, const Sample& b) { return a.distance < b.distance; });
    // Least squares: x = a0 + a1 du + a2 dv (and y likewise); the answer is a0 (du = dv = 0).
    glm::dmat3 normal(0.0);
    glm::dvec3 rx(0.0), ry(0.0);
    for (std::size_t i = 0; i < k; ++i) {
        const glm::dvec3 row(1.0, samples[i].du, samples[i].dv);
        normal += glm::outerProduct(row, row);
        rx += row * samples[i].x;
        ry += row * samples[i].y;
    }
    if (std::abs(glm::determinant(normal)) < 1e-30) return std::nullopt;
    const glm::dmat3 inverse = glm::inverse(normal);
    const glm::dvec3 ax = inverse * rx, ay = inverse * ry;
    const glm::dvec2 at(ax.x, ay.x);
    // The point must lie among the pixels that show the quad, not be extrapolated far off.
    const double gap = glm::length(glm::dvec2(samples[0].x, samples[0].y) - at);
    if (gap > 1.5) return std::nullopt;
    return at;
}

std::string savedAs(const Image& image, const std::string& name) {
    std::string file;
    for (char c : name)
        file += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    const auto path = testOutputDir() / (file + ".exr");
    (void)writeImage(testOutputDir() / (file + ".png"), image); // for a quick look
    auto written = writeImage(path, image);
    return written ? " (image: " + path.string() + ")"
                   : " (image not saved: " + written.error().describe() + ")";
}

Scene emptyScene() {
    Scene s;
    s.sourcePath = "test";
    s.roots.push_back(SceneRoot{"root", {}, std::nullopt});
    return s;
}

int addRampQuad(Scene& scene, double width, double height, float id,
                const glm::dmat4& worldFromQuad) {
    Primitive p = makeRampQuad(width, height, id);
    p.material = int(scene.materials.size());
    scene.materials.push_back(unlitMaterial());
    scene.meshes.push_back(Mesh{"ramp", {std::move(p)}});
    Node n;
    n.name = "ramp " + std::to_string(scene.nodes.size());
    n.mesh = int(scene.meshes.size()) - 1;
    n.matrix = worldFromQuad;
    scene.nodes.push_back(n);
    const int index = int(scene.nodes.size()) - 1;
    scene.roots.at(0).nodes.push_back(index);
    return index;
}

ImageDifference compareAwayFromEdges(const Image& actual, const Image& expected, float tolerance,
                                     int edgeMargin) {
    ImageDifference d;
    const int w = expected.width, h = expected.height;
    const bool depth = !expected.depth.empty() && expected.depth.size() == actual.depth.size();
    auto covered = [&](int x, int y) { return expected.pixel(x, y)[3] > 0.5f; };
    auto z = [&](int x, int y) { return expected.depth[std::size_t(y) * w + x]; };
    // An edge pixel: its coverage or depth differs from a 4-neighbour's.
    std::vector<bool> edge(expected.pixelCount(), false);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
                const int nx = x + dx, ny = y + dy;
                if (nx >= w || ny >= h) continue;
                bool differs = covered(x, y) != covered(nx, ny);
                if (!differs && depth && covered(x, y)) {
                    const float a = z(x, y), b = z(nx, ny);
                    differs = std::abs(a - b) > 0.02f * std::min(a, b);
                }
                if (differs) edge[std::size_t(y) * w + x] = edge[std::size_t(ny) * w + nx] = true;
            }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool nearEdge = false;
            for (int dy = -edgeMargin; dy <= edgeMargin && !nearEdge; ++dy)
                for (int dx = -edgeMargin; dx <= edgeMargin && !nearEdge; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx >= 0 && ny >= 0 && nx < w && ny < h)
                        nearEdge = edge[std::size_t(ny) * w + nx];
                }
            if (nearEdge) continue;
            ++d.compared;
            float largest = 0.0f;
            for (int c = 0; c < 4; ++c)
                largest =
                    std::max(largest, std::abs(actual.pixel(x, y)[c] - expected.pixel(x, y)[c]));
            d.largest = std::max(d.largest, largest);
            if (largest > tolerance) ++d.differing;
        }
    return d;
}

} // namespace lantern::test
